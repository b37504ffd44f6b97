// Never write what cannot be read back: every writer refuses a non-finite coordinate or one
// beyond the supported magnitude (core/base/magnitude.h) with a message naming the vertex and
// the value, and leaves no file; the value at the limit itself is written and read back.
#include <cmath>
#include <filesystem>
#include <cstring>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "core/base/file_io.h"
#include "core/base/magnitude.h"
#include "core/io/lattice/lattice_format.h"
#include "core/io/lattice/vtk_format.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/model/model.h"
#include "core/io/model/surface_export.h"
#include "core/io/project/project_io.h"
#include "core/multires/hierarchy.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

constexpr double kHuge = 1.7e308;
const double kInf = std::numeric_limits<double>::infinity();

// Every message names the path, the vertex, the coordinate and its value.
std::string expected(const std::string& path, int vertex, int coordinate, const std::string& why, const std::string& value) {
  return path + ": position of vertex " + std::to_string(vertex) + " " + why + " (coordinate " + std::to_string(coordinate) +
         " is " + value + "); nothing written";
}

const std::string kBeyond = "exceeds the supported magnitude 1e30";

Shape cube_lattice() {
  return read_lattice("sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                      "hex 0 1 2 3 4 5 6 7\n",
                      "c.lattice");
}

}  // namespace

TEST(Magnitude, OneLimitPrintedAsTheReadersPrintIt) {
  EXPECT_EQ(max_coordinate_text(), "1e30");
  EXPECT_TRUE(in_supported_range(kMaxCoordinate));
  EXPECT_TRUE(in_supported_range(-kMaxCoordinate));
  EXPECT_FALSE(in_supported_range(std::nextafter(kMaxCoordinate, kInf)));
  EXPECT_FALSE(in_supported_range(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(in_supported_range(-kInf));
  const double v[] = {0.0, -1e30, 2e30, kInf};
  EXPECT_EQ(first_out_of_range(v), std::optional<std::size_t>(2));
  EXPECT_EQ(first_out_of_range(std::span<const double>(v, 2)), std::nullopt);
  EXPECT_EQ(out_of_range_text(kHuge), "exceeds the supported magnitude 1e30 (1.7e+308)");
  EXPECT_EQ(out_of_range_text(-kInf), "is not finite (-inf)");
}

TEST(WritersRange, SurfaceMeshWritersRefuseAndWriteNothing) {
  TempDir dir("sublift_writers_mesh");
  SurfaceMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::uint32_t tri[3] = {0, 1, 2};
  m.add_face(tri);
  for (const char* ext : {"obj", "off", "ply"}) {
    const std::string path = dir.file(std::string("m.") + ext);
    SurfaceMesh bad = m;
    bad.positions[2].y = kHuge;
    EXPECT_EQ(input_error([&] { write_surface_mesh(path, bad); }), expected(path, 2, 1, kBeyond, "1.7e+308"));
    bad.positions[2].y = 1;
    bad.positions[1].z = -kInf;
    EXPECT_EQ(input_error([&] { write_surface_mesh(path, bad); }), expected(path, 1, 2, "is not finite", "-inf"));
    EXPECT_FALSE(std::filesystem::exists(path)) << path;
    // The limit itself is written and read back exactly.
    bad.positions[1].z = -kMaxCoordinate;
    write_surface_mesh(path, bad);
    EXPECT_EQ(import_surface_mesh(path).mesh.positions, bad.positions) << path;
  }
}

TEST(WritersRange, LatticeAndVtkWritersRefuseAndWriteNothing) {
  TempDir dir("sublift_writers_lattice");
  const Shape s = cube_lattice();
  std::vector<double> xyz = s.positions;
  xyz[3 * 6 + 0] = std::numeric_limits<double>::quiet_NaN();
  for (const char* ext : {"lattice", "vtk"}) {
    const std::string path = dir.file(std::string("c.") + ext);
    auto write = [&] { std::string(ext) == "vtk" ? write_vtk(path, s.base, xyz) : write_lattice(path, s.base, xyz); };
    EXPECT_EQ(input_error(write), expected(path, 6, 0, "is not finite", "nan"));
    EXPECT_FALSE(std::filesystem::exists(path)) << path;
  }
  xyz[3 * 6 + 0] = 1e31;
  const std::string path = dir.file("c.vtk");
  EXPECT_EQ(input_error([&] { write_vtk(path, s.base, xyz); }), expected(path, 6, 0, kBeyond, "1e+31"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(WritersRange, SurfacesWithNormalsRefuseInEveryFormat) {
  TempDir dir("sublift_writers_normals");
  Csr faces;
  faces.offsets = {0, 3};
  faces.items = {0, 1, 2};
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, kHuge, 0};
  const std::vector<double> n = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  for (const char* ext : {"obj", "ply", "gltf", "glb"}) {
    const std::string path = dir.file(std::string("s.") + ext);
    EXPECT_EQ(input_error([&] { write_surface_with_normals(path, faces, xyz, n); }), expected(path, 2, 1, kBeyond, "1.7e+308"));
    EXPECT_FALSE(std::filesystem::exists(path)) << path;
  }
}

TEST(WritersRange, ModelExportRefuses) {
  TempDir dir("sublift_writers_model");
  const Model model = import_model(std::string(SUBLIFT_ASSETS_DIR) + "/cube.obj");
  std::vector<double> world = model.positions;
  world[4] = kInf;
  const std::string path = dir.file("out.obj");
  EXPECT_EQ(input_error([&] { export_model(model, world, path); }), expected(path, 1, 1, "is not finite", "inf"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(WritersRange, ProjectWriterAndReaderRefuseCoefficientsOutOfRange) {
  TempDir dir("sublift_writers_project");
  Hierarchy h = make_hierarchy(cube_lattice().base, 1, Scheme::Cubic, 3, false);
  const std::uint32_t v = h.num_vertices(0) + 2;  // a wavelet: born at level 1
  h.coeffs[3 * v + 1] = kHuge;
  const std::string path = dir.file("p.sublift");
  try {
    write_project(path, h);
    ADD_FAILURE() << "written";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot save project: coefficient at vertex " + std::to_string(v) +
                                         ", level 1, channel 1 exceeds the supported magnitude 1e30 (1.7e+308); nothing written");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  // The reader refuses the same file made by hand: the good file with the value patched in
  // (no zero wavelet, so the coefficients are stored dense, in place).
  std::fill(h.coeffs.begin(), h.coeffs.end(), 0.5);
  ASSERT_EQ(write_project(path, h).encoding, "dense");
  std::string bytes = read_file_bytes(path);
  const std::size_t at = bytes.size() - 8 * (h.coeffs.size() - (3 * v + 1));
  ASSERT_EQ(std::memcmp(bytes.data() + at, &h.coeffs[3 * v + 1], 8), 0);
  std::memcpy(bytes.data() + at, &kHuge, 8);
  EXPECT_EQ(input_error([&] { read_project_from_memory("p.sublift", bytes); }),
            "p.sublift: coefficient at vertex " + std::to_string(v) + ", level 1, channel 1 exceeds the supported magnitude 1e30 (1.7e+308)");
  const double scaling = -kInf;
  std::memcpy(bytes.data() + bytes.size() - 8 * h.coeffs.size(), &scaling, 8);  // vertex 0, channel 0
  EXPECT_EQ(input_error([&] { read_project_from_memory("p.sublift", bytes); }),
            "p.sublift: coefficient at vertex 0, level 0, channel 0 is not finite (-inf)");
}

TEST(WritersRange, SynthesisThatOverflowsIsRefusedNamingLevelAndVertex) {
  // Coefficients at the limit whose synthesis exceeds it: the level-0 net is in range, level 1
  // is not (the first face point, vertex 20, is its face's mean plus lifted wavelets).
  Hierarchy h = make_hierarchy(cube_lattice().base, 2, Scheme::Linear, 3, false);
  std::fill(h.coeffs.begin(), h.coeffs.end(), kMaxCoordinate);
  EXPECT_NO_THROW(synthesize_in_range(h, 0));
  try {
    synthesize_in_range(h, 2);
    ADD_FAILURE() << "no overflow reported";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "synthesis overflows at level 1: vertex 20, channel 0 exceeds the supported magnitude 1e30 (2.25e+30)");
  }
  EXPECT_FALSE(in_supported_range(synthesize(h, 2)[3 * 20]));  // the unchecked synthesis gives the garbage
}
