// sqrt(2) coefficient tables (issue 7, paper 001): the face-point rule (eq. 1), the 4-point rules
// (eq. 11), omega (eq. 7, Table 1) and eta (eq. 12-14), and `sublift-cli coefficients`.
// Expectations are the paper's printed numbers and fractions derived by hand (comments).
#include <cmath>
#include <numbers>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/base/errors.h"
#include "core/schemes/sqrt2/sqrt2_coefficients.h"
#include "tests/cli_run.h"

namespace sublift {
namespace {

using Omega = std::array<double, 12>;

// Half a unit of the 6th printed decimal, plus rounding slack.
constexpr double kPrinted = 5e-7 + 1e-12;

TEST(Sqrt2Coefficients, FaceAlphaRegularAndValence3) {
  // n = 4: t_j = j pi/2, alpha_j = (1 + cos t_j + sin t_j + cos t_{j-1} - sin t_{j-1}) / 8.
  const double regular[4] = {3.0 / 8.0, 3.0 / 8.0, -1.0 / 8.0, -1.0 / 8.0};
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(sqrt2_face_alpha(4, j), regular[j], 1e-16) << j;
  // n = 3: alpha_0 = alpha_1 = (3/2 + sqrt(3)/2) / 6, alpha_2 = -sqrt(3)/6.
  const double s3 = std::sqrt(3.0);
  EXPECT_NEAR(sqrt2_face_alpha(3, 0), (1.5 + s3 / 2) / 6, 1e-15);
  EXPECT_NEAR(sqrt2_face_alpha(3, 1), (1.5 + s3 / 2) / 6, 1e-15);
  EXPECT_NEAR(sqrt2_face_alpha(3, 2), -s3 / 6, 1e-15);
  EXPECT_EQ(kSqrt2Alpha0, 0.5);
  for (int n = 3; n <= 20; ++n) {  // affine invariance: alpha_0 + sum_j alpha_j = 1; mirror j <-> 1-j
    double sum = kSqrt2Alpha0;
    for (int j = 0; j < n; ++j) {
      sum += sqrt2_face_alpha(n, j);
      EXPECT_NEAR(sqrt2_face_alpha(n, j), sqrt2_face_alpha(n, (n + 1 - j) % n), 1e-15) << n << " " << j;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << n;
  }
}

TEST(Sqrt2Coefficients, FourPointRules) {
  const auto a = sqrt2_four_point_weights();
  EXPECT_EQ(a, (std::array<double, 4>{-1.0 / 16, 9.0 / 16, 9.0 / 16, -1.0 / 16}));
  const auto b = sqrt2_four_point_corner_weights();
  EXPECT_EQ(b, (std::array<double, 3>{-1.0 / 8, 6.0 / 8, 3.0 / 8}));
  // (b) is the quadratic through p0, p1, p2 at x = 2, 1, 0 evaluated at x = 1/2.
  for (int d = 0; d <= 2; ++d)
    EXPECT_NEAR(b[0] * std::pow(2.0, d) + b[1] * 1.0 + b[2] * (d == 0 ? 1.0 : 0.0), std::pow(0.5, d), 1e-15);
  // (a) is the cubic through x = -3, -1, 1, 3 at x = 0.
  for (int d = 0; d <= 3; ++d) {
    double v = 0;
    for (int k = 0; k < 4; ++k) v += a[std::size_t(k)] * std::pow(-3.0 + 2 * k, d);
    EXPECT_NEAR(v, d == 0 ? 1.0 : 0.0, 1e-15) << d;
  }
}

TEST(Sqrt2Coefficients, RegularOmegaExact) {
  const Omega w = sqrt2_omega(4, 4, 4, 4);
  for (int i = 0; i < 12; ++i)
    EXPECT_NEAR(w[std::size_t(i)], i < 4 ? -265312.0 / 1449569.0 : 55648.0 / 1449569.0, 1e-15) << i;
}

// Table 1: n0, omega_0, omega_1 = omega_3, omega_2, omega_4 = omega_11, omega_5 = omega_10,
// omega_6 = omega_9, omega_7 = omega_8 (n1 = n2 = n3 = 4; omega_11 = 0 for n0 = 3).
constexpr double kTable1[10][8] = {
    {3, -0.194948, -0.187294, -0.179998, 0.070769, 0.033456, 0.039126, 0.037738},
    {4, -0.183028, -0.183028, -0.183028, 0.038389, 0.038389, 0.038389, 0.038389},
    {5, -0.167962, -0.177081, -0.187028, 0.018896, 0.039953, 0.038052, 0.039126},
    {6, -0.156338, -0.171716, -0.189868, 0.008222, 0.040061, 0.037848, 0.039609},
    {7, -0.146869, -0.167518, -0.191976, 0.003050, 0.039585, 0.037777, 0.039954},
    {8, -0.138752, -0.164354, -0.193600, 0.000622, 0.038932, 0.037794, 0.040219},
    {9, -0.131590, -0.161965, -0.194887, -0.000468, 0.038260, 0.037863, 0.040433},
    {10, -0.125168, -0.160137, -0.195932, -0.000898, 0.037627, 0.037960, 0.040610},
    {11, -0.119353, -0.158715, -0.196797, -0.000999, 0.037050, 0.038069, 0.040761},
    {12, -0.114054, -0.157591, -0.197526, -0.000938, 0.036531, 0.038184, 0.040890},
};

TEST(Sqrt2Coefficients, Table1) {
  // Table column -> the omega slots it prints.
  const std::vector<std::vector<int>> slots = {{0}, {1, 3}, {2}, {4, 11}, {5, 10}, {6, 9}, {7, 8}};
  for (const auto& row : kTable1) {
    const int n0 = int(row[0]);
    const Omega w = sqrt2_omega(n0, 4, 4, 4);
    for (std::size_t c = 0; c < slots.size(); ++c)
      for (int s : slots[c]) {
        if (n0 == 3 && s == 11) {
          EXPECT_EQ(w[11], 0.0);  // the exception of Table 1
          continue;
        }
        EXPECT_NEAR(w[std::size_t(s)], row[c + 1], kPrinted) << "n0=" << n0 << " omega_" << s;
      }
  }
}

// Rotating the face (p'_i = p_{i+1}) moves phi_{4+2i}, phi_{5+2i} to slots 4+2(i-1), 5+2(i-1):
// omega'_i = omega_{i+1} (i < 4), omega'_{4+k} = omega_{4+(k+2)%8}.
Omega rotated(const Omega& w) {
  Omega r{};
  for (int i = 0; i < 4; ++i) r[std::size_t(i)] = w[std::size_t((i + 1) % 4)];
  for (int k = 0; k < 8; ++k) r[std::size_t(4 + k)] = w[std::size_t(4 + (k + 2) % 8)];
  return r;
}

TEST(Sqrt2Coefficients, RotationSymmetry) {
  const std::vector<std::array<int, 4>> cases = {{5, 4, 4, 4}, {3, 4, 4, 4}, {3, 7, 5, 6},
                                                 {6, 3, 9, 3}, {12, 5, 3, 8}, {3, 3, 3, 3}};
  for (auto n : cases) {
    Omega w = sqrt2_omega(n[0], n[1], n[2], n[3]);
    for (int turn = 1; turn < 4; ++turn) {
      n = {n[1], n[2], n[3], n[0]};
      w = rotated(w);
      const Omega r = sqrt2_omega(n[0], n[1], n[2], n[3]);
      for (std::size_t s = 0; s < 12; ++s)
        EXPECT_NEAR(r[s], w[s], 1e-13) << n[0] << n[1] << n[2] << n[3] << " slot " << s;
    }
  }
}

TEST(Sqrt2Coefficients, MirrorSymmetry) {
  // Mirroring across the diagonal p0 p2 swaps p1 <-> p3 and phi_{4+k} <-> phi_{11-k}. For a
  // valence-3 corner the two coinciding slots are compared through their sum (one of them is 0).
  const std::vector<std::array<int, 4>> cases = {{5, 6, 7, 8}, {3, 4, 5, 6}, {4, 3, 9, 5}};
  for (auto n : cases) {
    const Omega w = sqrt2_omega(n[0], n[1], n[2], n[3]);
    const Omega m = sqrt2_omega(n[0], n[3], n[2], n[1]);
    const int corner[4] = {0, 3, 2, 1};
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(m[std::size_t(i)], w[std::size_t(corner[i])], 1e-13);
    auto outer = [](const Omega& o, const std::array<int, 4>& v, int k) {  // merged at valence 3
      const int corner_of_k = (k % 2 == 0) ? k / 2 : (k / 2 + 1) % 4;
      if (v[std::size_t(corner_of_k)] != 3) return o[std::size_t(4 + k)];
      const int kept = 2 * corner_of_k, dropped = (2 * corner_of_k + 7) % 8;
      return o[std::size_t(4 + kept)] + o[std::size_t(4 + dropped)];
    };
    const std::array<int, 4> nm{n[0], n[3], n[2], n[1]};
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(outer(m, nm, k), outer(w, n, 7 - k), 1e-13) << k;
  }
}

TEST(Sqrt2Coefficients, Valence3DropsOneSlotAtAnyCorner) {
  // The corner-0 case of Table 1, moved to corner k by rotation: slot 4 + (2k+7)%8 is exactly 0
  // and slot 4 + 2k carries 0.070769.
  for (int k = 0; k < 4; ++k) {
    std::array<int, 4> n{4, 4, 4, 4};
    n[std::size_t(k)] = 3;
    const Omega w = sqrt2_omega(n[0], n[1], n[2], n[3]);
    for (int s = 0; s < 12; ++s) {
      if (s == 4 + (2 * k + 7) % 8)
        EXPECT_EQ(w[std::size_t(s)], 0.0) << k;
      else
        EXPECT_NE(w[std::size_t(s)], 0.0) << k << " " << s;
    }
    EXPECT_NEAR(w[std::size_t(k)], -0.194948, kPrinted);
    EXPECT_NEAR(w[std::size_t(4 + 2 * k)], 0.070769, kPrinted);
  }
  const Omega all3 = sqrt2_omega(3, 3, 3, 3);
  for (int s : {5, 7, 9, 11}) EXPECT_EQ(all3[std::size_t(s)], 0.0);
}

TEST(Sqrt2Coefficients, CacheAndOnTheFly) {
  EXPECT_EQ(sqrt2_omega(5, 6, 7, 8), sqrt2_omega_solve({5, 6, 7, 8}));
  // Beyond the table: solved on the fly, continuing Table 1's monotone trend of omega_0.
  const Omega w13 = sqrt2_omega(13, 4, 4, 4), w40 = sqrt2_omega(40, 4, 4, 4);
  EXPECT_GT(w13[0], kTable1[9][1]);
  EXPECT_GT(w40[0], w13[0]);
  const Omega big = sqrt2_omega(1000, 1000, 1000, 1000);
  for (double x : big) EXPECT_TRUE(std::isfinite(x));
  // Concurrent first use of the same keys gives the same values.
  std::vector<Omega> got(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&got, t] { got[std::size_t(t)] = sqrt2_omega(7, 11, 3, 9); });
  for (auto& th : threads) th.join();
  for (int t = 1; t < 4; ++t) EXPECT_EQ(got[std::size_t(t)], got[0]);
}

TEST(Sqrt2Coefficients, ValenceRange) {
  EXPECT_THROW(sqrt2_omega(2, 4, 4, 4), TopologyError);
  EXPECT_THROW(sqrt2_omega(4, 4, 4, 1001), TopologyError);
  EXPECT_THROW(sqrt2_omega_solve({4, 0, 4, 4}), TopologyError);
}

TEST(Sqrt2Coefficients, Eta) {
  // Printed in sec. 4.
  const auto a = sqrt2_eta_inner();
  EXPECT_NEAR(a[0], 0.070575, kPrinted);
  EXPECT_NEAR(a[3], 0.070575, kPrinted);
  EXPECT_NEAR(a[1], -0.304712, kPrinted);
  EXPECT_NEAR(a[2], -0.304712, kPrinted);
  const auto b = sqrt2_eta_corner();
  EXPECT_NEAR(b[0], 0.122233, kPrinted);
  EXPECT_NEAR(b[1], -0.410513, kPrinted);
  // By hand from Figure 5's masks (x256): case (a) with eta_0 = eta_3 = x, eta_1 = eta_2 = y:
  // 421 x + 45 y = 16, 45 x + 483 y = -144; case (b): G = [423 48; 48 482], H = (-32, 192).
  EXPECT_NEAR(a[0], 2368.0 / 33553.0, 1e-15);
  EXPECT_NEAR(a[1], -10224.0 / 33553.0, 1e-15);
  EXPECT_NEAR(b[0], 12320.0 / 100791.0, 1e-15);
  EXPECT_NEAR(b[1], -41376.0 / 100791.0, 1e-15);
}

// --- sublift-cli coefficients ---------------------------------------------------------------

testing::ProcessResult cli(const std::vector<std::string>& args) { return testing::run_cli(args); }

std::vector<double> json_array(const std::string& out, const char* key) {
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_EQ(j.size(), 1u);
  return j.at(key).get<std::vector<double>>();
}

TEST(Sqrt2CoefficientsCli, OmegaJson) {
  for (const std::array<int, 4> n : {std::array<int, 4>{5, 4, 4, 4}, {3, 5, 6, 7}, {4, 4, 4, 4}}) {
    const auto r = cli({"coefficients", "--scheme", "sqrt2", "--valences", std::to_string(n[0]),
                        std::to_string(n[1]), std::to_string(n[2]), std::to_string(n[3]), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<double> got = json_array(r.out, "omega");
    const Omega want = sqrt2_omega(n[0], n[1], n[2], n[3]);
    ASSERT_EQ(got.size(), 12u);
    for (std::size_t s = 0; s < 12; ++s) EXPECT_EQ(got[s], want[s]) << s;
  }
  const auto r = cli({"coefficients", "--scheme", "sqrt2", "--valences", "3", "4", "4", "4", "--json"});
  EXPECT_EQ(json_array(r.out, "omega")[11], 0.0);
  EXPECT_NEAR(json_array(r.out, "omega")[4], 0.070769, kPrinted);
}

TEST(Sqrt2CoefficientsCli, EtaJsonAndText) {
  auto r = cli({"coefficients", "--scheme", "sqrt2", "--boundary", "a", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<double> eta = json_array(r.out, "eta");
  ASSERT_EQ(eta.size(), 4u);
  EXPECT_NEAR(eta[1], -0.304712, kPrinted);
  r = cli({"coefficients", "--scheme", "sqrt2", "--boundary", "b", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  eta = json_array(r.out, "eta");
  ASSERT_EQ(eta.size(), 2u);
  EXPECT_NEAR(eta[0], 0.122233, kPrinted);
  r = cli({"coefficients", "--scheme", "sqrt2", "--boundary", "b"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("eta_1"), std::string::npos) << r.out;
  r = cli({"coefficients", "--scheme", "sqrt2", "--valences", "3", "4", "4", "4"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("omega_11"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("-0.194948"), std::string::npos) << r.out;
  EXPECT_EQ(cli({"coefficients", "--help"}).exit_code, 0);
}

TEST(Sqrt2CoefficientsCli, UsageErrors) {
  const std::vector<std::vector<std::string>> bad = {
      {"coefficients"},
      {"coefficients", "--valences", "4", "4", "4", "4"},
      {"coefficients", "--scheme", "loop", "--valences", "4", "4", "4", "4"},
      {"coefficients", "--scheme", "sqrt2"},
      {"coefficients", "--scheme", "sqrt2", "--valences", "4", "4", "4"},
      {"coefficients", "--scheme", "sqrt2", "--valences", "2", "4", "4", "4"},
      {"coefficients", "--scheme", "sqrt2", "--valences", "4", "4", "4", "1001"},
      {"coefficients", "--scheme", "sqrt2", "--valences", "4", "4", "x", "4"},
      {"coefficients", "--scheme", "sqrt2", "--boundary", "c"},
      {"coefficients", "--scheme", "sqrt2", "--boundary", "a", "--valences", "4", "4", "4", "4"},
      {"coefficients", "--scheme", "sqrt2", "--valences", "4", "4", "4", "4", "--valences", "4",
       "4", "4", "4"},
      {"coefficients", "--scheme", "sqrt2", "--valences", "4", "4", "4", "4", "extra"},
  };
  for (const auto& args : bad) {
    const auto r = cli(args);
    std::string line;
    for (const auto& s : args) line += s + " ";
    EXPECT_EQ(r.exit_code, 2) << line << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << line;
  }
}

}  // namespace
}  // namespace sublift
