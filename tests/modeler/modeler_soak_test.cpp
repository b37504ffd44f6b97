// The modeler soak test (issue 18): a seeded random sequence of the operations a user runs —
// open, scheme, subdivide, level, select, soft radius, move (drags, some cancelled), rotate and
// scale about random pivots, brush strokes of every kind, mirror editing on and off (issue 19),
// gain, detail frames, compress (view, apply, off), undo, redo, save and reopen — on every bundled
// sample with every scheme that takes it, through ModelerState (the calls the mouse, the keys
// and `sublift --script` make). After every step:
//   - every level's control net equals a fresh dense synthesis of the session's coefficients
//     with its gains (the local resynthesis and fold-back are checked against the plain path);
//   - an operation the modeler refuses (Error) leaves every coefficient and net bit for bit;
//   - an operation that makes a history entry is undone and redone at once: the state before
//     and after it come back (coefficients and gains bit for bit, nets to rounding);
// after each episode, undo back to its start restores every coefficient bit for bit (and every
// net to rounding), redo to the end restores the edited state, and a saved project reopens with
// the same coefficients bit for bit. Memory: a second pass over every case ends with no more
// resident memory than the first plus a margin (outside AddressSanitizer, whose quarantine
// holds freed memory; there LeakSanitizer checks leaks at exit instead).
//
// Steps: SUBLIFT_SOAK_STEPS per case (default 40; 8 under AddressSanitizer, the sanitizer pass
// of scripts/test); the seed is SUBLIFT_SOAK_SEED (default 18) and is printed with every failure.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/modeler/modeler_state.h"
#include "app/modeler/script_runner.h"
#include "core/base/errors.h"
#include "core/multires/hierarchy.h"
#include "core/schemes/registry.h"
#include "tests/io_test_util.h"
#include "tests/test_util.h"

namespace sublift {
namespace {

using testing::kAddressSanitizer;

const std::string kAssets = SUBLIFT_ASSETS_DIR;
constexpr std::uint32_t kMaxFinestVertices = 2500;  // subdivide stops here: the checks stay cheap

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

bool same_bits(std::span<const double> a, std::span<const double> b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Everything an operation may change that undo must give back.
struct Snapshot {
  std::vector<double> coeffs, gains;
  std::vector<std::vector<double>> levels;
  bool local = false;
};

Snapshot snapshot(const ModelerState& m) {
  const Session& s = m.session();
  Snapshot out{s.hierarchy().coeffs, {s.gains().begin(), s.gains().end()}, {}, s.detail_frames() == DetailFrames::Local};
  for (int l = 0; l <= s.finest_level(); ++l) out.levels.emplace_back(s.positions(l).begin(), s.positions(l).end());
  return out;
}

// "" when equal, else what differs first: the coefficients, gains and frames bit for bit; the
// level nets bit for bit when net_tol < 0, else to net_tol. (Undo and redo of a gain rebuild
// the nets above it by a dense synthesis, where the edits before had updated them in place:
// the same coefficients, nets equal to rounding. Every other operation, a refusal and a
// cancelled drag give the nets back bit for bit.)
std::string difference(const Snapshot& a, const Snapshot& b, double net_tol = -1) {
  if (a.levels.size() != b.levels.size())
    return "finest level " + std::to_string(a.levels.size() - 1) + " vs " + std::to_string(b.levels.size() - 1);
  if (!same_bits(a.coeffs, b.coeffs)) return "coefficients";
  if (!same_bits(a.gains, b.gains)) return "gains";
  for (std::size_t l = 0; l < a.levels.size(); ++l) {
    if (net_tol < 0) {
      if (!same_bits(a.levels[l], b.levels[l])) return "level " + std::to_string(l) + " control net";
      continue;
    }
    double e = a.levels[l].size() == b.levels[l].size() ? 0.0 : INFINITY;
    for (std::size_t i = 0; i < a.levels[l].size() && i < b.levels[l].size(); ++i)
      e = std::max(e, std::abs(a.levels[l][i] - b.levels[l][i]));
    if (!(e <= net_tol)) return "level " + std::to_string(l) + " control net (by " + std::to_string(e) + ")";
  }
  if (a.local != b.local) return "detail frames";
  return "";
}

// Largest difference between a level's net and a fresh dense synthesis of the coefficients with
// the session's gains applied (wavelets of level l sit on level l+1's new vertices).
double consistency_error(const Session& s, int* worst_level) {
  const Hierarchy& h = s.hierarchy();
  const bool gained = std::any_of(s.gains().begin(), s.gains().end(), [](double g) { return g != 1.0; });
  std::optional<Hierarchy> scaled;
  if (gained) {
    scaled = h;
    for (int l = 0; l < s.finest_level(); ++l)
      for (std::size_t i = 3 * std::size_t(s.num_vertices(l)); i < 3 * std::size_t(s.num_vertices(l + 1)); ++i)
        scaled->coeffs[i] *= s.gain(l);
  }
  double worst = 0;
  for (int l = 0; l <= s.finest_level(); ++l) {
    const std::vector<double> fresh = synthesize(gained ? *scaled : h, l);
    const auto net = s.positions(l);
    double e = fresh.size() == net.size() ? 0.0 : INFINITY;
    for (std::size_t i = 0; i < fresh.size() && i < net.size(); ++i) e = std::max(e, std::abs(fresh[i] - net[i]));
    if (e > worst) worst = e, *worst_level = l;
  }
  return worst;
}

double extent(const ModelerState& m) {
  double r = 1.0;
  for (double x : m.session().positions(0)) r = std::max(r, std::abs(x));
  return r;
}

std::size_t resident_bytes() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

std::vector<std::string> samples() {
  std::vector<std::string> out;
  for (const char* dir : {"", "/curves", "/ffd"})
    for (const auto& e : std::filesystem::directory_iterator(kAssets + dir)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".obj" || ext == ".lattice")) out.push_back(e.path().string());
    }
  std::sort(out.begin(), out.end());
  return out;
}

struct Stats {
  std::map<std::string, int> ops, refused;
  int steps = 0;
};

// One case: `steps` random operations on the open model, then undo to the start, redo to the
// end, save and reopen. Returns false after the first failed check (the rest would repeat it).
bool run_episode(ModelerState& m, std::mt19937_64& rng, int steps, const std::string& project, Stats& stats) {
  const Snapshot start = snapshot(m);
  const std::size_t start_position = m.session().undo_position();
  const double tol = 1e-10 * extent(m);
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<std::uint64_t>(std::max(n, 1))); };
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  static const char* kOps[] = {"level", "subdivide", "select", "soft", "move", "move-cancel", "gain",
                               "frames", "compress-apply", "compress-view", "undo", "redo",
                               "rotate", "scale", "stroke", "mirror"};
  static const int kWeights[] = {2, 1, 3, 1, 6, 1, 2, 1, 1, 1, 3, 2, 2, 1, 3, 1};
  std::discrete_distribution<int> choose(std::begin(kWeights), std::end(kWeights));
  std::string log;  // the episode's operations, for the failure messages
  for (int step = 0; step < steps; ++step) {
    const std::string op = kOps[choose(rng)];
    SCOPED_TRACE("step " + std::to_string(step) + ": " + op);
    log += " " + op;
    const Snapshot before = snapshot(m);
    const std::size_t position = m.session().undo_position();
    const int J = m.session().finest_level();
    try {
      if (op == "level") {
        m.set_level(pick(J + 1));
      } else if (op == "subdivide") {
        if (m.session().num_vertices(J) > kMaxFinestVertices) continue;
        m.subdivide();
      } else if (op == "select") {
        const auto n = m.session().num_vertices(m.level());
        std::vector<unsigned> sel;
        for (int k = 1 + pick(3); k > 0; --k) sel.push_back(static_cast<unsigned>(pick(static_cast<int>(n))));
        m.set_selection(sel);
      } else if (op == "soft") {
        m.set_soft_radius(pick(2) ? 0.0 : uniform(0.2, 1.5) * m.default_soft_radius());
      } else if (op == "move" || op == "move-cancel") {
        if (m.selection().empty()) m.set_selection({0});
        m.begin_drag("Move");
        double total[3] = {0, 0, 0};
        try {
          for (int k = 1 + pick(3); k > 0; --k) {
            for (double& t : total) t += uniform(-0.1, 0.1) * extent(m);
            m.drag_to(total);
          }
        } catch (const Error&) {
          m.cancel_drag();
          throw;
        }
        if (op == "move-cancel") {
          m.cancel_drag();
          const std::string d = difference(before, snapshot(m));
          EXPECT_EQ(d, "") << "a cancelled drag left a change";
          if (!d.empty()) return false;
        } else {
          m.end_drag();
        }
      } else if (op == "rotate" || op == "scale") {
        // Issue 19's transforms about a random pivot, with the symmetry the episode has on.
        if (m.selection().empty()) m.set_selection({0});
        m.set_pivot(static_cast<Pivot>(pick(4)));
        m.set_cursor({uniform(-1, 1) * extent(m), uniform(-1, 1) * extent(m), 0.0});
        m.begin_transform(op == "rotate" ? TransformMode::Rotate : TransformMode::Scale);
        try {
          for (int k = 1 + pick(2); k > 0; --k) {
            const glm::dvec3 axis(uniform(-1, 1), uniform(-1, 1), uniform(0.1, 1));
            if (op == "rotate") m.transform_to(axis, uniform(-1.5, 1.5), glm::dvec3(1.0));
            else m.transform_to(axis, 0.0, glm::dvec3(uniform(0.6, 1.4), uniform(0.6, 1.4), uniform(0.6, 1.4)));
          }
        } catch (const Error&) {
          m.cancel_drag();
          throw;
        }
        m.end_drag();
      } else if (op == "stroke") {
        // A brush stroke of a few dabs at control points of the edit level.
        BrushSettings b;
        b.kind = static_cast<BrushKind>(pick(6));
        b.radius = uniform(0.5, 3.0) * m.default_soft_radius();
        b.strength = uniform(0.1, 1.0);
        b.falloff = static_cast<Falloff>(pick(4));
        b.invert = pick(2) != 0;
        m.set_brush(b);
        m.begin_stroke();  // refuses (and changes nothing) for normal brushes off surfaces
        try {
          const auto n = static_cast<int>(m.session().num_vertices(m.level()));
          for (int k = 1 + pick(3); k > 0; --k) {
            const auto p = m.session().positions(m.level());
            const std::size_t v = 3 * static_cast<std::size_t>(pick(n));
            Dab d;
            d.center = {p[v], p[v + 1], p[v + 2]};
            d.view_dir = glm::dvec3(0.0);
            d.motion = {uniform(-0.05, 0.05) * extent(m), uniform(-0.05, 0.05) * extent(m), 0.0};
            m.dab(d);
          }
        } catch (const Error&) {
          m.cancel_drag();
          throw;
        }
        m.end_drag();
      } else if (op == "mirror") {
        m.set_symmetry(pick(3), pick(2) != 0);  // a partial map on an asymmetric sample is fine
      } else if (op == "gain") {
        if (J == 0) continue;
        const int l = pick(J);
        static const double kGains[] = {0.0, 0.5, 1.0, 1.7};
        m.begin_gain(l);
        try {
          m.set_gain(l, kGains[pick(4)]);
        } catch (const Error&) {
          m.end_gain();
          throw;
        }
        m.end_gain();
      } else if (op == "frames") {
        m.set_local_frames(m.session().detail_frames() == DetailFrames::World);
      } else if (op == "compress-apply" || op == "compress-view") {
        m.set_compression(uniform(0.0, 1.0));
        if (op == "compress-apply") m.apply_compression();
        m.compression_off();
      } else if (op == "undo") {
        m.undo();
      } else if (op == "redo") {
        m.redo();
      }
      ++stats.ops[op];
    } catch (const Error& e) {
      ++stats.refused[op];
      log += "(refused)";
      m.compression_off();
      const std::string d = difference(before, snapshot(m));
      EXPECT_EQ(d, "") << "refused (" << e.what() << ") but changed";
      if (!d.empty()) return false;
      continue;
    }
    ++stats.steps;
    // An operation that made a history entry: undo gives back the state before it and redo the
    // state after it, bit for bit.
    if (op != "undo" && op != "redo" && m.session().undo_position() == position + 1) {
      Snapshot after = snapshot(m);
      m.undo();
      Snapshot now = snapshot(m);
      now.local = before.local;
      std::string d = difference(before, now, tol);
      EXPECT_EQ(d, "") << "undo of " << op << ", after" << log;
      m.redo();
      if (d.empty()) d = difference(after, snapshot(m), tol);
      EXPECT_EQ(d, "") << "redo of " << op << ", after" << log;
      if (!d.empty()) return false;
    }
    int level = 0;
    const double err = consistency_error(m.session(), &level);
    EXPECT_LE(err, tol) << "level " << level << " differs from a fresh synthesis";
    if (!(err <= tol)) return false;
  }
  // Undo to the start, redo to the end: both bit for bit.
  // Detail frames are a setting, not an edit: undo leaves them, so compare without them.
  Snapshot end = snapshot(m);
  const std::size_t end_position = m.session().undo_position();
  while (m.session().undo_position() > start_position && m.undo()) {
  }
  Snapshot now = snapshot(m);
  now.local = start.local;
  std::string d = difference(start, now, tol);
  EXPECT_EQ(d, "") << "undo to the start, after" << log;
  if (!d.empty()) return false;
  while (m.session().undo_position() < end_position && m.redo()) {
  }
  d = difference(end, snapshot(m), tol);
  EXPECT_EQ(d, "") << "redo to the end, after" << log;
  if (!d.empty()) return false;
  // Save and reopen: the same coefficients, gains and frames bit for bit; the nets are a fresh
  // synthesis of them now (the session's were updated in place), so they agree to rounding.
  m.save_project(project);
  const int level = m.level();
  m.open(project);
  d = difference(end, snapshot(m), tol);
  EXPECT_EQ(d, "") << "reopened project " << project;
  EXPECT_EQ(m.level(), level);
  return d.empty() && m.level() == level;
}

TEST(ModelerSoak, RandomOperationsOnEverySampleAndScheme) {
  const int steps = env_int("SUBLIFT_SOAK_STEPS", kAddressSanitizer ? 8 : 40);
  const auto seed = static_cast<std::uint64_t>(env_int("SUBLIFT_SOAK_SEED", 18));
  sublift::testing::TempDir dir("sublift_soak");
  const std::vector<std::string> files = samples();
  ASSERT_GE(files.size(), 15u) << "bundled samples missing from " << kAssets;
  Stats stats;
  std::set<std::string> schemes_run;
  int cases = 0;
  std::size_t rss_first = 0;
  for (int pass = 0; pass < (kAddressSanitizer ? 1 : 2); ++pass) {
    for (const std::string& file : files) {
      for (const SchemeInfo& scheme : all_schemes()) {
        const std::string name = std::filesystem::path(file).filename().string() + " " + scheme.name;
        SCOPED_TRACE(name + " (SUBLIFT_SOAK_SEED=" + std::to_string(seed) + ", pass " + std::to_string(pass) + ")");
        std::mt19937_64 rng(seed * 1000003 + std::hash<std::string>{}(name) + static_cast<std::uint64_t>(pass));
        ModelerState m;
        try {
          m.open(file, 1, scheme.id);
        } catch (const Error& e) {
          // Refusals the registry predicts: a surface scheme on a curve or lattice, a triangle
          // scheme on polygons. Any other refusal of a bundled sample is a failure.
          const bool predicted = scheme.surfaces_only || scheme.triangles_only;
          EXPECT_TRUE(predicted) << "refused: " << e.what();
          continue;
        }
        const std::string project = dir.file("soak.sublift");
        const bool ok = run_episode(m, rng, steps, project, stats) &&
                        run_episode(m, rng, std::max(steps / 4, 4), project, stats);  // from the reopened project
        if (!ok) return;
        schemes_run.insert(scheme.name);
        ++cases;
      }
    }
    if (pass == 0) rss_first = resident_bytes();
  }
  if (!kAddressSanitizer) {
    const std::size_t rss = resident_bytes();
    EXPECT_LE(rss, rss_first + (std::size_t(64) << 20)) << "resident memory grew from " << rss_first << " to " << rss
                                                        << " bytes over a second pass of the same operations";
  }
  // Every scheme ran, on enough cases, and every operation both ran and was counted.
  EXPECT_EQ(schemes_run.size(), all_schemes().size());
  EXPECT_GE(cases, 40);
  for (const char* op : {"level", "subdivide", "select", "soft", "move", "move-cancel", "gain", "frames",
                         "compress-apply", "compress-view", "undo", "redo"})
    EXPECT_GT(stats.ops[op], 0) << op << " never ran";
  std::string refused;
  for (const auto& [op, n] : stats.refused) refused += " " + op + " " + std::to_string(n);
  std::printf("soak: %d cases, %d steps checked; refused:%s\n", cases, stats.steps, refused.empty() ? " none" : refused.c_str());
}

// The script runner's failures of the input are not marked internal (the fuzz target aborts on
// internal ones): a missing file, a bad number, a usage error, a command without a model, a
// refusal of the model's own.
TEST(ScriptRunner, InputErrorsAreNotInternal) {
  const std::string cube = kAssets + "/cube.obj";
  for (const std::string& script : {std::string("open /no/such/file.obj"), std::string("level 1"),
                                   "open " + cube + "\nmove 1 x 2", "open " + cube + "\nmove 1 2",
                                   "open " + cube + "\nscheme loop", "open " + cube + "\nsubdivide 99",
                                   "open " + cube + "\ngain 5 2", "open " + cube + "\nbogus"}) {
    SCOPED_TRACE(script);
    ModelerState state;
    ScriptRunner runner("t.script", script);
    const ScriptStep step = runner.next(state);
    EXPECT_EQ(step.kind, ScriptStep::Kind::Error);
    EXPECT_FALSE(step.internal);
    EXPECT_EQ(step.message.find("internal"), std::string::npos) << step.message;
    EXPECT_EQ(step.message.rfind("script:", 0), 0u) << step.message;
  }
}

// `sublift --script FILE --json`: one JSON object per command, the state after it, and the
// failure as the last line.
TEST(ScriptRunner, JsonLinePerCommand) {
  const std::string cube = kAssets + "/cube.obj";
  ModelerState state;
  ScriptRunner runner("t.script", "# a comment\nopen " + cube + "\nsubdivide\n\nlevel 1\nselect 0\nmove 0 0 1\nbogus\nundo\n");
  std::ostringstream out;
  runner.set_json_output(&out);
  const ScriptStep step = runner.next(state);
  EXPECT_EQ(step.kind, ScriptStep::Kind::Error);
  std::vector<nlohmann::json> lines;
  std::istringstream in(out.str());
  for (std::string l; std::getline(in, l);) lines.push_back(nlohmann::json::parse(l));
  ASSERT_EQ(lines.size(), 6u) << out.str();  // comments and blank lines are no commands; undo never ran
  const std::vector<std::pair<int, std::string>> expected = {
      {2, "open"}, {3, "subdivide"}, {5, "level"}, {6, "select"}, {7, "move"}, {8, "bogus"}};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(lines[i]["line"], expected[i].first);
    EXPECT_EQ(lines[i]["command"], expected[i].second);
    EXPECT_EQ(lines[i]["ok"], i + 1 < lines.size());
    EXPECT_GE(lines[i]["ms"].get<double>(), 0.0);
  }
  EXPECT_EQ(lines[0]["finest_level"], 2);  // opened with two levels
  EXPECT_EQ(lines[1]["finest_level"], 3);
  EXPECT_EQ(lines[2]["level"], 1);
  EXPECT_EQ(lines[2]["vertices"], state.session().num_vertices(1));
  EXPECT_EQ(lines[5]["message"], "script:8: unknown command 'bogus'");
  EXPECT_EQ(lines[5]["message"], step.message);
  // Before a model is open there is no level to report.
  ModelerState empty;
  ScriptRunner none("t.script", "level 1\n");
  std::ostringstream o2;
  none.set_json_output(&o2);
  none.next(empty);
  const auto j = nlohmann::json::parse(o2.str());
  EXPECT_FALSE(j.contains("level"));
  EXPECT_EQ(j["ok"], false);
}

}  // namespace
}  // namespace sublift
