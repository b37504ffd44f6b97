// sublift-cli coefficients --scheme S [scheme options] [--json]
// Each scheme brings its own options and printer (kSchemes below); only --scheme, --json and
// --help are shared, so a scheme is added with one table entry.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "core/schemes/sqrt2/sqrt2_coefficients.h"
#include "core/schemes/tri/tri_local.h"
#include "core/schemes/tri/tri_wavelets.h"

namespace sublift::cli {
namespace {

constexpr const char* kHelp =
    "usage: sublift-cli coefficients --scheme S [scheme options] [--json]\n"
    "  The lifting coefficient tables of a wavelet scheme. Schemes and their options:\n"
    "  sqrt2  interpolatory sqrt(2) wavelets (Wang & Ma, paper 001):\n"
    "    --valences N0 N1 N2 N3  omega_0..omega_11 of the face wavelet (eq. 7, Table 1) for a\n"
    "                            face whose corners p0..p3 (counterclockwise) have valences\n"
    "                            N0..N3 (3..1000), in the order of phi_0..phi_11 (docs/sqrt2.md);\n"
    "                            a slot dropped for a valence-3 corner is 0\n"
    "    --boundary a|b          eta of the boundary/crease wavelet (eq. 12): case a, lifted on\n"
    "                            p0..p3; case b (next to the curve end p2), lifted on p0, p1\n"
    "  linear-tri | butterfly | loop  the k-disc wavelets of Lounsbery, DeRose & Warren (paper 004\n"
    "    sec. 6.3) for an edge (a, b) whose first end a has valence N and every other vertex 6:\n"
    "    psi = phi_new - sum_i alpha_i phi_i over the level-j vertices i within K rings of a or b,\n"
    "    scaling functions equal to 1 at their own vertex, inner products exact (sec. 5)\n"
    "    --valence N   3..16 (default 6)\n"
    "    --disc K      1, 2 or 3 rings (default 2)\n"
    "    order of the alpha: a, b, then breadth first, each vertex listing its neighbours\n"
    "    counterclockwise starting from the vertex it was reached from (a from b, b from a);\n"
    "    each entry also gives its ring and a drawing position (a at the origin, b at (1, 0),\n"
    "    wedges of 360/N degrees)\n"
    "  --json   {\"omega\": [12 numbers]} or {\"eta\": [4 or 2 numbers]}; the triangle schemes\n"
    "           {\"alpha\": [...], \"disc\": [{\"ring\", \"x\", \"y\"}...], \"norm\", \"residual\"}\n";

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "% .12f", v);
  return buf;
}

int parse_valence(const std::string& s) {
  int v = 0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size() || v < 3 || v > 1000)
    throw UsageError("--valences: each valence must be an integer in 3..1000, got '" + s + "'");
  return v;
}

// Where phi_k sits (core/schemes/sqrt2/sqrt2_coefficients.h).
std::string sqrt2_slot_name(int k) {
  if (k < 4) return "p" + std::to_string(k);
  const int i = (k - 4) / 2, near = (k % 2 == 0) ? i : (i + 1) % 4;
  return "next to p" + std::to_string(near) + ", across edge p" + std::to_string(i) + " p" +
         std::to_string((i + 1) % 4);
}

int run_sqrt2(const Args& a) {
  const bool json = a.has("--json");
  const auto lv = a.lists.find("--valences");
  const auto boundary = a.value("--boundary");
  if (lv != a.lists.end() && boundary) throw UsageError("give either --valences or --boundary");
  if (boundary) {
    std::vector<double> eta;
    if (*boundary == "a") {
      const auto e = sqrt2_eta_inner();
      eta.assign(e.begin(), e.end());
    } else if (*boundary == "b") {
      const auto e = sqrt2_eta_corner();
      eta.assign(e.begin(), e.end());
    } else {
      throw UsageError("--boundary must be a or b, got '" + *boundary + "'");
    }
    if (json) {
      std::cout << nlohmann::json{{"eta", eta}}.dump() << "\n";
      return 0;
    }
    std::cout << "sqrt(2) boundary/crease lifting coefficients eta (eq. 12), case (" << *boundary
              << "): " << (*boundary == "a" ? "inner curve wavelet between p1 and p2\n"
                                            : "wavelet between p1 and the curve end p2\n");
    for (std::size_t k = 0; k < eta.size(); ++k)
      std::cout << "  eta_" << k << "  (p" << k << ")  " << num(eta[k]) << "\n";
    return 0;
  }
  if (lv == a.lists.end()) throw UsageError("sqrt2 needs --valences N0 N1 N2 N3 or --boundary a|b");
  if (lv->second.size() != 4) throw UsageError("--valences given more than once");
  std::array<int, 4> n{};
  for (std::size_t i = 0; i < 4; ++i) n[i] = parse_valence(lv->second[i]);
  const std::array<double, 12> w = sqrt2_omega(n[0], n[1], n[2], n[3]);
  if (json) {
    std::cout << nlohmann::json{{"omega", w}}.dump() << "\n";
    return 0;
  }
  std::cout << "sqrt(2) lifting coefficients omega (eq. 7), corner valences p0..p3: " << n[0]
            << " " << n[1] << " " << n[2] << " " << n[3] << "\n";
  for (int k = 0; k < 12; ++k) {
    std::string name = sqrt2_slot_name(k);
    const int i = (k - 4) / 2;
    if (k >= 4 && k % 2 == 1 && n[std::size_t((i + 1) % 4)] == 3)
      name += " (dropped: = phi_" + std::to_string(4 + 2 * ((i + 1) % 4)) + ")";
    name.resize(std::max<std::size_t>(name.size(), 48), ' ');
    std::cout << "  omega_" << k << (k < 10 ? "   " : "  ") << name << num(w[std::size_t(k)])
              << "\n";
  }
  return 0;
}


int run_tri(const Args& a) {
  const std::string name = *a.value("--scheme");
  const Scheme s = name == "loop" ? Scheme::Loop : name == "butterfly" ? Scheme::Butterfly : Scheme::LinearTri;
  const int n = static_cast<int>(integer_option(a, "--valence", 6, 3, 16));
  const int k = static_cast<int>(integer_option(a, "--disc", 2, 1, 3));
  TriWaveletBuilder b(s, k);
  std::vector<double> xy;
  const Complex disc = extraordinary_disc(n, b.edge_radius() + 3, &xy);
  const TriRings r = build_tri_rings(disc);
  std::uint32_t e = UINT32_MAX;
  for (std::uint32_t x : disc.vertex_edges.row(0))
    if (disc.edge_verts[2 * x] == 1 || disc.edge_verts[2 * x + 1] == 1) e = x;
  // The edge runs a = 0 (valence n) -> b = 1 whatever its stored direction.
  std::vector<std::uint32_t> d;
  const EdgeWavelet& w = disc.edge_verts[2 * e] == 0 ? b.edge_wavelet(disc, r, e, &d)
                                                    : throw std::logic_error("coefficients: edge stored backwards");
  std::vector<int> ring(d.size(), 0);
  {
    const std::uint32_t seeds[2] = {0, 1}, starts[2] = {1, 0};
    const LocalOrder o = local_order(r, seeds, starts, k);
    for (std::size_t i = 0; i < d.size(); ++i) ring[i] = o.dist[i];
  }
  if (a.has("--json")) {
    nlohmann::json j;
    j["scheme"] = name;
    j["valence"] = n;
    j["disc"] = nlohmann::json::array();
    for (std::size_t i = 0; i < d.size(); ++i)
      j["disc"].push_back({{"ring", ring[i]}, {"x", xy[2 * d[i]]}, {"y", xy[2 * d[i] + 1]}});
    j["k"] = k;
    j["alpha"] = w.alpha;
    j["norm"] = std::sqrt(std::max(0.0, w.norm2));
    j["residual"] = w.residual;
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << name << " k-disc wavelet, first end valence " << n << ", k = " << k << " (" << d.size()
            << " scaling functions; ||psi|| = " << num(std::sqrt(std::max(0.0, w.norm2)))
            << " with a level-j triangle of area 1)\n";
  for (std::size_t i = 0; i < d.size(); ++i) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "  alpha_%-3zu ring %d  at (% .3f, % .3f)  ", i, ring[i], xy[2 * d[i]], xy[2 * d[i] + 1]);
    std::cout << buf << num(w.alpha[i]) << "\n";
  }
  return 0;
}

struct SchemeCommand {
  std::set<std::string> with_value;
  std::map<std::string, int> multi;
  int (*run)(const Args&);
};

const std::map<std::string, SchemeCommand>& schemes() {
  static const std::map<std::string, SchemeCommand> s{
      {"sqrt2", {{"--boundary"}, {{"--valences", 4}}, run_sqrt2}},
      {"linear-tri", {{"--valence", "--disc"}, {}, run_tri}},
      {"butterfly", {{"--valence", "--disc"}, {}, run_tri}},
      {"loop", {{"--valence", "--disc"}, {}, run_tri}},
  };
  return s;
}

}  // namespace

int run_coefficients(int argc, char** argv) {
  // The scheme decides which options exist, so find it before parsing.
  std::string scheme;
  for (int i = 2; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--scheme") scheme = argv[i + 1];
  const auto it = schemes().find(scheme);
  std::set<std::string> with_value{"--scheme"};
  std::map<std::string, int> multi;
  if (it != schemes().end()) {
    with_value.insert(it->second.with_value.begin(), it->second.with_value.end());
    multi = it->second.multi;
  }
  const Args a = parse_args(argc, argv, 2, with_value, {"--json", "--help"}, multi);
  if (a.has("--help")) {
    std::cout << kHelp;
    return 0;
  }
  if (!a.positional.empty()) throw UsageError("unexpected argument '" + a.positional[0] + "'");
  if (!a.value("--scheme")) throw UsageError("missing --scheme");
  if (it == schemes().end()) {
    std::string known;
    for (const auto& [name, _] : schemes()) known += (known.empty() ? "" : ", ") + name;
    throw UsageError("unknown scheme '" + scheme + "' (known: " + known + ")");
  }
  return it->second.run(a);
}

}  // namespace sublift::cli
