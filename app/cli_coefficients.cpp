// sublift-cli coefficients --scheme S [scheme options] [--json]
// Each scheme brings its own options and printer (kSchemes below); only --scheme, --json and
// --help are shared, so a scheme is added with one table entry.
#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_args.h"
#include "app/cli_commands.h"
#include "core/sqrt2_coefficients.h"

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
    "  --json   {\"omega\": [12 numbers]} or {\"eta\": [4 or 2 numbers]}\n";

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

// Where phi_k sits (core/sqrt2_coefficients.h).
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

struct SchemeCommand {
  std::set<std::string> with_value;
  std::map<std::string, int> multi;
  int (*run)(const Args&);
};

const std::map<std::string, SchemeCommand>& schemes() {
  static const std::map<std::string, SchemeCommand> s{
      {"sqrt2", {{"--boundary"}, {{"--valences", 4}}, run_sqrt2}},
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
