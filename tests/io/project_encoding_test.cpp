// Compact projects (issue 20, version 2): zero wavelets take a bit each, a lossless save is bit
// for bit, quantized saves report their error, damaged encodings are refused, and version-1
// projects written by earlier Sublifts still open.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/analysis/compress.h"
#include "core/base/file_io.h"
#include "core/io/project/coefficient_codec.h"
#include "core/io/project/project_io.h"
#include "tests/io_test_util.h"
#include "tests/noisy_hierarchy.h"

using namespace sublift;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::string error_of(const std::string& bytes) {
  return input_error([&] { read_project_from_memory("p.sublift", bytes); });
}

// The header's stored_vertices.
std::size_t stored_in(const std::string& bytes) {
  const std::string key = "\"stored_vertices\":";
  return std::stoul(bytes.substr(bytes.find(key) + key.size(), 20));
}

std::string header_of(const std::string& bytes) { return bytes.substr(0, bytes.find('\n', bytes.find('\n') + 1) + 1); }

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

}  // namespace

TEST(ProjectEncoding, ZeroWaveletsTakeABitAndTheRoundTripIsBitExact) {
  TempDir dir("sublift_project_sparse");
  Hierarchy h = sublift::testing::noisy_torus(12, 8, 3, Scheme::Cubic, 3, 0.01);
  const std::uint32_t V0 = h.levels[0].num_vertices;
  // Every other wavelet vertex zero; one of the kept ones holds -0.0 and a subnormal.
  for (std::size_t v = V0; v < h.coeffs.size() / 3; v += 2)
    for (int k = 0; k < 3; ++k) h.coeffs[3 * v + k] = 0.0;
  h.coeffs[3 * (V0 + 1)] = -0.0;
  h.coeffs[3 * (V0 + 1) + 1] = std::numeric_limits<double>::denorm_min();
  const std::string path = dir.file("p.sublift");
  const SavedProject s = write_project(path, h);
  EXPECT_EQ(s.encoding, "sparse");
  EXPECT_EQ(s.bytes, std::filesystem::file_size(path));
  EXPECT_TRUE(same_bits(read_project(path).coeffs, h.coeffs));
  const std::string bytes = read_file_bytes(path);
  EXPECT_EQ(bytes.substr(0, 18), "sublift-project 2\n");
  EXPECT_NE(header_of(bytes).find("\"encoding\":\"sparse\""), std::string::npos) << header_of(bytes);
  // A hierarchy without a zero wavelet is stored dense: the mask would only add to it.
  const Hierarchy full = sublift::testing::noisy_torus(12, 8, 3, Scheme::Cubic, 4, 0.01);
  EXPECT_EQ(write_project(path, full).encoding, "dense");
  EXPECT_TRUE(same_bits(read_project(path).coeffs, full.coeffs));
}

TEST(ProjectEncoding, PureSubdivisionStoresAlmostNothingButItsBase) {
  TempDir dir("sublift_project_pure");
  Hierarchy h = sublift::testing::noisy_torus(12, 8, 4, Scheme::Cubic, 3, 0.01);
  const std::uint32_t V0 = h.levels[0].num_vertices;
  std::fill(h.coeffs.begin() + 3 * V0, h.coeffs.end(), 0.0);
  const std::string path = dir.file("pure.sublift");
  const SavedProject s = write_project(path, h);
  EXPECT_EQ(s.encoding, "sparse");
  // Header, base topology, level 0 and one bit per wavelet vertex: under 3 % of the dense values.
  EXPECT_LT(double(s.bytes), 0.03 * 8.0 * double(h.coeffs.size())) << s.bytes;
  EXPECT_TRUE(same_bits(read_project(path).coeffs, h.coeffs));
}

TEST(ProjectEncoding, AQuarterOfTheWaveletsTakesAtMost35PercentOfTheFullProject) {
  TempDir dir("sublift_project_quarter");
  const Hierarchy h = sublift::testing::noisy_torus(16, 12, 4, Scheme::Cubic, 7, 0.02);
  const SavedProject full = write_project(dir.file("full.sublift"), h);
  const Compression c = Compressor(h).run(CompressMode::Keep, 0.25);
  Hierarchy kept = h;
  kept.coeffs = c.coeffs;
  const SavedProject quarter = write_project(dir.file("quarter.sublift"), kept);
  EXPECT_EQ(full.encoding, "dense");
  EXPECT_EQ(quarter.encoding, "sparse");
  EXPECT_LE(double(quarter.bytes), 0.35 * double(full.bytes)) << quarter.bytes << " of " << full.bytes;
  EXPECT_TRUE(same_bits(read_project(dir.file("quarter.sublift")).coeffs, kept.coeffs));
  // Quantized to 16 bits: smaller still, each coefficient within half a step of its level's.
  const SavedProject q16 = write_project(dir.file("q16.sublift"), kept, {}, 16);
  EXPECT_EQ(q16.encoding, "quantized");
  EXPECT_LT(q16.bytes, quarter.bytes / 3);
  const Hierarchy back = read_project(dir.file("q16.sublift"));
  double worst = 0.0;
  for (std::size_t i = 0; i < kept.coeffs.size(); ++i) worst = std::max(worst, std::abs(back.coeffs[i] - kept.coeffs[i]));
  EXPECT_EQ(worst, q16.max_quantization_error);  // the reported error is the one read back
  double largest = 0.0;
  for (std::size_t i = 3 * h.levels[0].num_vertices; i < kept.coeffs.size(); ++i) largest = std::max(largest, std::abs(kept.coeffs[i]));
  EXPECT_LE(worst, 0.5 * largest / 32767.0 * (1 + 1e-12));
  EXPECT_GT(worst, 0.0);
  // The scaling coefficients of level 0 stay exact.
  for (std::size_t i = 0; i < 3 * h.levels[0].num_vertices; ++i) EXPECT_EQ(back.coeffs[i], kept.coeffs[i]);
  // Fewer bits, more error, fewer bytes.
  const SavedProject q8 = write_project(dir.file("q8.sublift"), kept, {}, 8);
  const SavedProject q32 = write_project(dir.file("q32.sublift"), kept, {}, 32);
  EXPECT_LT(q8.bytes, q16.bytes);
  EXPECT_LT(q16.bytes, q32.bytes);
  EXPECT_GT(q8.max_quantization_error, q16.max_quantization_error);
  EXPECT_GT(q16.max_quantization_error, q32.max_quantization_error);
}

TEST(ProjectEncoding, QuantizationRefusesBadWidthsAndIntegerProjects) {
  TempDir dir("sublift_project_qbad");
  const Hierarchy h = sublift::testing::noisy_torus(6, 4, 1, Scheme::Cubic, 1, 0.01);
  EXPECT_THROW(write_project(dir.file("a.sublift"), h, {}, 12), Error);
  Hierarchy integer = make_hierarchy(h.levels[0], 1, Scheme::Linear, 3, true);
  EXPECT_THROW(write_project(dir.file("b.sublift"), integer, {}, 16), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.sublift")));
  EXPECT_NO_THROW(write_project(dir.file("c.sublift"), integer));  // lossless is fine
}

TEST(ProjectEncoding, RefusesDamagedEncodings) {
  TempDir dir("sublift_project_encbad");
  Hierarchy h = sublift::testing::noisy_torus(8, 6, 2, Scheme::Cubic, 5, 0.01);
  const std::uint32_t V0 = h.levels[0].num_vertices;
  for (std::size_t v = V0; v < h.coeffs.size() / 3; v += 3)
    for (int k = 0; k < 3; ++k) h.coeffs[3 * v + k] = 0.0;
  const std::string path = dir.file("p.sublift");
  write_project(path, h);
  const std::string good = read_file_bytes(path);
  ASSERT_NO_THROW(read_project_from_memory("p.sublift", good));
  ASSERT_EQ(stored_in(good), 2 * (h.coeffs.size() / 3 - V0) / 3);
  // The mask sits right after the base topology and level 0, before the stored values.
  const std::size_t W = h.coeffs.size() / 3 - V0;
  std::size_t stored = 0;
  for (std::size_t i = 0; i < W; ++i) stored += i % 3 != 0;
  const std::size_t mask = good.size() - stored * 24 - (W + 7) / 8;
  // A bit more than the header's stored_vertices: refused, naming both counts.
  std::string extra = good;
  extra[mask] = static_cast<char>(extra[mask] | 1);  // vertex V0 was zeroed (i % 3 == 0)
  EXPECT_NE(error_of(extra).find("coefficient mask marks " + std::to_string(stored + 1) + " wavelet vertices, the header says " +
                                 std::to_string(stored)),
            std::string::npos)
      << error_of(extra);
  // Padding bits past the last wavelet.
  if (W % 8) {
    std::string pad = good;
    pad[mask + W / 8] = static_cast<char>(static_cast<unsigned char>(pad[mask + W / 8]) | 0x80);
    EXPECT_NE(error_of(pad).find("bits set past the last wavelet"), std::string::npos) << error_of(pad);
  }
  // Header keys.
  EXPECT_NE(error_of(replaced(good, "\"encoding\":\"sparse\"", "\"encoding\":\"zip\"")).find("must be dense, sparse or quantized"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(good, "\"stored_vertices\":", "\"stored_vertices\":99999999,\"x\":")).find("truncated payload"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(good, "sublift-project 2", "sublift-project 1")).find("header version is not 1"), std::string::npos);
  // Quantized: a negative step.
  write_project(path, h, {}, 8);
  const std::string q = read_file_bytes(path);
  const std::size_t q_stored = stored_in(q);  // quantized to 0 in every channel: not stored
  EXPECT_LE(q_stored, stored);
  const std::size_t steps = q.size() - q_stored * 3 - 2 * 3 * 8;  // two wavelet levels, three channels
  std::string neg = q;
  const double minus = -1.0;
  std::memcpy(neg.data() + steps, &minus, 8);
  EXPECT_NE(error_of(neg).find("quantization step 0 is not a finite non-negative number"), std::string::npos) << error_of(neg);
  EXPECT_NE(error_of(replaced(q, "\"bits\":8", "\"bits\":12")).find("header 'bits' must be 8, 16 or 32, got 12"), std::string::npos);
}

TEST(ProjectEncoding, VersionOneProjectsStillOpen) {
  // Written by the Sublift of issue 18 (fuzz/seeds/project, version 1, dense coefficients).
  const std::filesystem::path seeds = std::filesystem::path(SUBLIFT_ASSETS_DIR) / "../fuzz/seeds/project";
  TempDir dir("sublift_project_v1");
  int opened = 0;
  for (const auto& f : std::filesystem::directory_iterator(seeds)) {
    const std::string bytes = read_file_bytes(f.path().string());
    if (bytes.substr(0, 18) != "sublift-project 1\n") continue;  // the version-2 seeds beside them
    ProjectExtras x;
    const Hierarchy h = read_project_from_memory(f.path().string(), bytes, &x);
    // Saved again: version 2, the same hierarchy and session state.
    write_project(dir.file("again.sublift"), h, x);
    ProjectExtras y;
    const Hierarchy back = read_project(dir.file("again.sublift"), &y);
    EXPECT_TRUE(same_bits(back.coeffs, h.coeffs)) << f.path();
    EXPECT_EQ(y.gains, x.gains) << f.path();
    EXPECT_EQ(y.current_level, x.current_level) << f.path();
    EXPECT_EQ(y.local_frames, x.local_frames) << f.path();
    ++opened;
  }
  EXPECT_GE(opened, 7);
  // Version 1 has no encodings.
  const std::string v1 = read_file_bytes((seeds / "cube_cubic.sublift").string());
  EXPECT_NE(error_of(replaced(v1, "\"coefficients\":", "\"encoding\":\"sparse\",\"coefficients\":")).find("'encoding' needs version 2"),
            std::string::npos);
}
