#include <cstdio>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/mesh/mesh_import.h"

using namespace sublift;

TEST(MeshExport, RoundTripIsExactInEveryFormat) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  SurfaceMesh m;
  for (int i = 0; i < 50; ++i) m.positions.emplace_back(u(rng), u(rng) * 1e-9, u(rng) * 1e7);
  for (std::uint32_t i = 0; i + 4 < 50; i += 4) {
    const std::uint32_t quad[4] = {i, i + 1, i + 2, i + 3};
    const std::uint32_t tri[3] = {i + 1, i + 4, i + 2};
    m.add_face(quad);
    m.add_face(tri);
  }
  m.positions[49] = {0.1, 1.0 / 3.0, -2.2250738585072014e-308};  // subnormal edge of the range
  const std::uint32_t last[5] = {45, 46, 47, 48, 49};
  m.add_face(last);
  m.tags.push_back({"crease", {0, 1}, {2.5}, {}, 0});
  for (const char* ext : {"obj", "off", "ply"}) {
    const std::string path = (std::filesystem::temp_directory_path() / ("sublift_rt." + std::string(ext))).string();
    write_surface_mesh(path, m);
    const LoadedMesh back = import_surface_mesh(path);
    EXPECT_EQ(back.mesh.positions, m.positions) << ext;
    EXPECT_EQ(back.mesh.face_indices, m.face_indices) << ext;
    EXPECT_EQ(back.mesh.face_offsets, m.face_offsets) << ext;
    if (std::string(ext) == "obj") {
      ASSERT_EQ(back.mesh.tags.size(), 1u);
      EXPECT_EQ(back.mesh.tags[0].floats, std::vector<double>{2.5});
    }
    std::filesystem::remove(path);
  }
}

TEST(MeshExport, FailedWriteLeavesPreviousFileIntact) {
  const auto dir = std::filesystem::temp_directory_path() / "sublift_atomic";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "keep.obj").string();
  write_file_atomic(path, [](std::ostream& o) { o << "old contents\n"; });
  EXPECT_THROW(write_file_atomic(path, [](std::ostream& o) {
                 o << "half written";
                 throw IoError("simulated failure");
               }),
               IoError);
  EXPECT_EQ(read_file_bytes(path), "old contents\n");
  std::size_t leftovers = 0;
  for (auto& e : std::filesystem::directory_iterator(dir)) leftovers += e.path().filename() != "keep.obj";
  EXPECT_EQ(leftovers, 0u);  // the temporary file is removed
  EXPECT_THROW(write_surface_mesh((dir / "x.stl").string(), SurfaceMesh{}), InputError);
  EXPECT_THROW(write_surface_mesh("/nonexistent_dir/x.obj", SurfaceMesh{}), IoError);
  std::filesystem::remove_all(dir);
}
