// The CLI refuses work that would not fit in memory before starting it (issue 18), and the
// prediction behind that is honest: it bounds the peak memory the command really takes.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "core/complex/complex_build.h"
#include "core/multires/hierarchy.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_util.h"

namespace sublift {
namespace {

using testing::kAddressSanitizer;

using testing::run_cli;

const char* kTwoQuads = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n";

std::string write(const testing::TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir.file(name);
  std::ofstream(path) << text;
  return path;
}

TEST(CliMemory, SubdivideRefusesTwelveLevelsUpFrontWithThePredictedSize) {
  const testing::TempDir dir("sublift_cli_memory_refuse");
  const std::string in = write(dir, "two_quads.obj", kTwoQuads);
  const testing::ScopedEnv budget("SUBLIFT_MEMORY_BUDGET", "4G");
  const auto r = run_cli({"subdivide", in, "--scheme", "cubic", "--levels", "12", "-o", dir.file("out.obj")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("subdividing to level 12 (33566721 vertices) needs about 13 GB, more than the memory budget of 4.0 GB "
                       "(SUBLIFT_MEMORY_BUDGET=4G)"),
            std::string::npos)
      << r.err;
  EXPECT_LT(r.seconds, 5.0) << "refused before building, not after";
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.obj")));
}

TEST(CliMemory, AMalformedBudgetIsNamed) {
  const testing::TempDir dir("sublift_cli_memory_bad");
  const std::string in = write(dir, "two_quads.obj", kTwoQuads);
  const testing::ScopedEnv budget("SUBLIFT_MEMORY_BUDGET", "plenty");
  const auto r = run_cli({"subdivide", in, "--scheme", "cubic", "--levels", "11", "-o", dir.file("out.obj")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("SUBLIFT_MEMORY_BUDGET must be a positive size such as 6G, 512M or 1000000 (bytes); got 'plenty'"),
            std::string::npos)
      << r.err;
}

// The peak resident size of the one child this test process ran (each ctest test is its own
// process, so RUSAGE_CHILDREN holds just that child).
double child_peak_bytes() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return double(u.ru_maxrss) * 1024.0;
}

std::string obj_text(const fixtures::Polygons& m) {
  std::string out;
  for (std::uint32_t v = 0; v < m.num_vertices; ++v)
    out += "v " + std::to_string(m.positions[3 * v]) + " " + std::to_string(m.positions[3 * v + 1]) + " " +
           std::to_string(m.positions[3 * v + 2]) + "\n";
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    out += "f";
    for (std::uint32_t x : m.faces.row(f)) out += " " + std::to_string(x + 1);
    out += "\n";
  }
  return out;
}

void expect_prediction_bounds_peak(const fixtures::Polygons& m, const std::string& scheme, int levels) {
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer's shadow memory inflates the resident size";
  const testing::TempDir dir("sublift_cli_memory_peak_" + scheme);
  const std::string in = write(dir, "in.obj", obj_text(m));
  const auto r = run_cli({"subdivide", in, "--scheme", scheme, "--levels", std::to_string(levels), "-o", dir.file("out.ply")}, 120);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Complex c = complex_from_polygons(m.num_vertices, m.faces);
  const double predicted = predicted_hierarchy_bytes(c, levels, parse_scheme(scheme));
  const double peak = child_peak_bytes();
  // The process's own start-up (libraries, the allocator) is about 8 MB whatever the mesh.
  EXPECT_GE(predicted + 16e6, peak) << "the check would let through work that does not fit";
  EXPECT_LE(predicted, 2.0 * peak) << "the check would refuse work that fits";
}

TEST(CliMemory, PredictionBoundsThePeakOfCubicSubdivision) { expect_prediction_bounds_peak(fixtures::torus(4, 4), "cubic", 7); }

TEST(CliMemory, PredictionBoundsThePeakOfLoopSubdivision) {
  fixtures::Polygons m = fixtures::octahedron();  // the fixture has no positions
  m.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  expect_prediction_bounds_peak(m, "loop", 7);
}

}  // namespace
}  // namespace sublift
