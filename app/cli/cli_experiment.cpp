// sublift-cli experiment noise|fit|compress: the papers' experiments (core/analysis/experiments.h,
// docs/experiments.md) on a base file, for any scheme.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "app/cli/cli_json.h"
#include "app/cli/cli_hierarchy.h"
#include "core/complex/connectivity_match.h"
#include "core/base/errors.h"
#include "core/analysis/experiments.h"
#include "core/io/lattice/shape_io.h"
#include "core/base/text_lines.h"

namespace sublift::cli {

namespace {

constexpr const char* kHelp =
    "usage: sublift-cli experiment noise    --scheme S --model BASE --levels J --sigma X [--seed K] [--json]\n"
    "       sublift-cli experiment fit      --scheme S --model BASE --levels J [MODEL] [--json]\n"
    "       sublift-cli experiment compress --scheme S --model BASE --levels J [MODEL] [--keep F ...]\n"
    "                                       [--ranking l2|raw] [--json]\n"
    "  The experiments of Wang & Ma 2009 (Tables 2-4, 6-7) and Bertram 2004 (Table 1), see\n"
    "  docs/experiments.md. Level L of a model is its analysis down to L with the wavelets of\n"
    "  levels >= L dropped, subdivided back to J. Errors are over the level-J vertices, relative\n"
    "  to the reference model's bounding-box diagonal: rms = sqrt(mean |p - q|^2), max = max |p - q|.\n"
    "  noise     BASE subdivided J times is the clean model; every coordinate of every vertex gets\n"
    "            Gaussian noise of standard deviation X * diagonal (Box-Muller on splitmix64 seeded\n"
    "            with K, default 1); each level L = J..0 of the noisy model against the clean one;\n"
    "            ratio = rms(L) / rms(J) (Wang & Ma's R), max_ratio = max(L) / max(J) (Bertram).\n"
    "  fit       each level L of the finest model against the finest model itself.\n"
    "  compress  the finest model with only the largest fraction F of its wavelet coefficients\n"
    "            (and all level-0 scaling coefficients) against itself. --keep F (0..1) may be\n"
    "            repeated or a comma list; default 0,0.03,0.06,...,0.3 (Wang & Ma's 0..30 %).\n"
    "            --ranking l2 (default): by |w| 2^(-j dim/2), the L2 norm of the level-j wavelet\n"
    "            (sqrt2: 2^(-j/2), its levels halve the area);\n"
    "            raw: by |w|.\n"
    "  MODEL (fit, compress): --fine FINE, a file with the connectivity of BASE refined J times\n"
    "            (as 'analyze' takes), or else BASE subdivided J times by the scheme plus the smooth\n"
    "            displacement A * diagonal * sin(2 pi K t / diagonal) per coordinate, t the next\n"
    "            coordinate: --detail A (default 0.01) --waves K (default 4).\n";

double number_option(const Args& a, const std::string& key, double fallback, double lo, double hi) {
  const auto v = a.value(key);
  if (!v) return fallback;
  const auto x = parse_double(*v);
  if (!x || !std::isfinite(*x) || *x < lo || *x > hi) {
    std::ostringstream s;
    s << key << " must be a number in " << lo << ".." << hi << ", got '" << *v << "'";
    throw UsageError(s.str());
  }
  return *x;
}

std::uint64_t seed_option(const Args& a) {
  const auto v = a.value("--seed");
  if (!v) return 1;
  std::uint64_t n = 0;
  auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), n);
  if (ec != std::errc() || p != v->data() + v->size()) throw UsageError("--seed must be a non-negative integer, got '" + *v + "'");
  return n;
}

std::vector<double> keep_option(const Args& a) {
  std::vector<double> out;
  const auto it = a.lists.find("--keep");
  if (it == a.lists.end()) {
    for (int p = 0; p <= 30; p += 3) out.push_back(p / 100.0);
    return out;
  }
  for (const std::string& item : it->second)
    for (const double x : number_list(item, "--keep")) {
      if (!(x >= 0 && x <= 1)) throw UsageError("--keep takes fractions in 0..1, got '" + item + "'");
      out.push_back(x);
    }
  return out;
}

// Scientific numbers for the tables (relative errors span many decades), "-" for undefined ratios.
std::string num(double x, const char* fmt = "%.4e") {
  if (std::isnan(x)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, x);
  return buf;
}

nlohmann::json or_null(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }

// The finest model of fit/compress: --fine FINE checked against the refined base, or the smooth one.
std::vector<double> finest_model(const Args& a, Hierarchy& h, const Shape& base, const std::string& base_path,
                                 nlohmann::json& info) {
  if (const auto fine_path = a.value("--fine")) {
    if (a.value("--detail") || a.value("--waves")) throw UsageError("--fine and --detail/--waves exclude each other");
    Shape fine = read_shape(*fine_path);
    std::cerr << fine.report.format(*fine_path);
    if (const std::string why = connectivity_mismatch(h.levels.back(), fine.base); !why.empty())
      throw InputError(*fine_path, 0, "is not " + base_path + " refined " + std::to_string(h.finest_level()) + " times: " + why);
    info["fine"] = *fine_path;
    return std::move(fine.positions);
  }
  const double detail = number_option(a, "--detail", 0.01, 0, 1);
  const double waves = number_option(a, "--waves", 4, 0, 1e6);
  set_base(h, base.positions);
  info["detail"] = detail;
  info["waves"] = waves;
  return smooth_perturbation(synthesize(h, h.finest_level()), detail, waves);
}

void print_levels(const LevelExperiment& r, bool ratios) {
  std::cout << "level  rms (rel.)   max (rel.)" << (ratios ? "   R = rms/rms(J)  max/max(J)" : "") << "\n";
  for (const LevelError& e : r.levels) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%5d  %-11s  %-11s", e.level, num(e.rms).c_str(), num(e.max).c_str());
    std::cout << buf;
    if (ratios) {
      std::snprintf(buf, sizeof buf, "  %-15s  %s", num(e.ratio, "%.4f").c_str(), num(e.max_ratio, "%.4f").c_str());
      std::cout << buf;
    }
    std::cout << "\n";
  }
}

nlohmann::json levels_json(const LevelExperiment& r, bool ratios) {
  nlohmann::json rows = nlohmann::json::array();
  for (const LevelError& e : r.levels) {
    nlohmann::json row = {{"level", e.level}, {"rms", e.rms}, {"max", e.max}};
    if (ratios) {
      row["ratio"] = or_null(e.ratio);
      row["max_ratio"] = or_null(e.max_ratio);
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

int run_experiment(int argc, char** argv) {
  if (argc < 3 || std::string(argv[2]) == "--help" || std::string(argv[2]) == "-h") {
    if (argc < 3) throw UsageError("expected noise, fit or compress");
    std::cout << kHelp;
    return 0;
  }
  const std::string kind = argv[2];
  if (kind != "noise" && kind != "fit" && kind != "compress")
    throw UsageError("unknown experiment '" + kind + "' (expected noise, fit or compress)");
  std::set<std::string> with_value{"--scheme", "--model", "--levels"};
  std::map<std::string, int> multi;
  if (kind == "noise") with_value.insert({"--sigma", "--seed"});
  if (kind != "noise") with_value.insert({"--fine", "--detail", "--waves"});
  if (kind == "compress") {
    with_value.insert("--ranking");
    multi["--keep"] = 1;
  }
  const Args a = parse_args(argc, argv, 3, with_value, {"--json", "--help"}, multi);
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (!a.positional.empty()) throw UsageError("unexpected argument '" + a.positional.front() + "'");
  const auto model = a.value("--model");
  if (!model) throw UsageError("missing --model BASE");
  const Scheme scheme = scheme_option(a);
  const int levels = levels_option(a, scheme);
  double sigma = 0;
  if (kind == "noise") {
    if (!a.value("--sigma")) throw UsageError("missing --sigma X");
    sigma = number_option(a, "--sigma", 0, 0, 1);
  }
  const std::uint64_t seed = seed_option(a);
  const std::vector<double> fractions = kind == "compress" ? keep_option(a) : std::vector<double>{};
  Ranking ranking = Ranking::L2;
  if (const auto r = a.value("--ranking")) {
    if (*r == "raw") ranking = Ranking::Raw;
    else if (*r != "l2") throw UsageError("--ranking must be l2 or raw, got '" + *r + "'");
  }

  Shape base = read_shape(*model);
  add_topology_warnings(base.report, base.base);
  std::cerr << base.report.format(*model);
  check_refined_size(base.base, levels, scheme);
  Hierarchy h = make_hierarchy(base.base, levels, scheme, 3);
  nlohmann::json j = {{"experiment", kind}, {"scheme", scheme_name(scheme)}, {"model", *model},
                      {"finest_level", levels}, {"finest_vertices", h.num_vertices(levels)},
                      {"warnings", report_json(base.report)}};
  const bool json = a.has("--json");

  if (kind == "noise") {
    const LevelExperiment r = noise_experiment(h, base.positions, sigma, seed);
    if (json) {
      j.update({{"sigma", sigma}, {"seed", seed}, {"diagonal", r.diagonal}, {"levels", levels_json(r, true)}});
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << "noise experiment: " << scheme_name(scheme) << ", " << *model << " refined " << levels << " times ("
                << r.finest_vertices << " vertices), sigma " << sigma << " x diagonal " << num(r.diagonal, "%.6g")
                << ", seed " << seed << "\n";
      print_levels(r, true);
    }
    return 0;
  }
  const std::vector<double> fine = finest_model(a, h, base, *model, j);
  if (kind == "fit") {
    const LevelExperiment r = fit_experiment(h, fine);
    if (json) {
      j.update({{"diagonal", r.diagonal}, {"levels", levels_json(r, false)}});
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << "fit experiment: " << scheme_name(scheme) << ", " << *model << " refined " << levels << " times ("
                << r.finest_vertices << " vertices), diagonal " << num(r.diagonal, "%.6g") << "\n";
      print_levels(r, false);
    }
    return 0;
  }
  const CompressExperiment r = compress_experiment(h, fine, fractions, ranking);
  if (json) {
    nlohmann::json rows = nlohmann::json::array();
    for (const KeepError& k : r.rows)
      rows.push_back({{"fraction", k.fraction}, {"kept", k.kept}, {"rms", k.rms}, {"max", k.max}});
    j.update({{"diagonal", r.diagonal}, {"wavelets", r.wavelets}, {"ranking", ranking == Ranking::L2 ? "l2" : "raw"},
              {"keep", rows}});
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "compress experiment: " << scheme_name(scheme) << ", " << *model << " refined " << levels << " times ("
              << r.finest_vertices << " vertices, " << r.wavelets << " wavelets), ranking "
              << (ranking == Ranking::L2 ? "l2" : "raw") << ", diagonal " << num(r.diagonal, "%.6g") << "\n";
    std::cout << "kept %   kept     rms (rel.)   max (rel.)\n";
    for (const KeepError& k : r.rows) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%6.2f  %-8zu %-11s  %s", 100 * k.fraction, k.kept, num(k.rms).c_str(),
                    num(k.max).c_str());
      std::cout << buf << "\n";
    }
  }
  return 0;
}

}  // namespace sublift::cli
