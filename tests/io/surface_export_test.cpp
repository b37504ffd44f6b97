// Surfaces with normals as OBJ, PLY, glTF and GLB: each written and read back (OBJ and PLY
// through the import layer, glTF and GLB through tinygltf's loader from memory), normals parsed
// independently, refusal of bad input, and atomic saves.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "core/base/file_io.h"
#include "core/io/mesh/mesh_import.h"
#include "core/complex/shapes.h"
#include "core/io/model/surface_export.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

struct Fixture {
  Csr faces;
  std::vector<double> xyz, normals;
  std::size_t num_vertices() const { return xyz.size() / 3; }
};

// Unit vertex normals: sums of the Newell normals of the incident faces.
std::vector<double> vertex_normals(const Csr& faces, const std::vector<double>& xyz) {
  std::vector<double> n(xyz.size(), 0.0);
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto c = faces.row(f);
    double fn[3] = {0, 0, 0};
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double* p = &xyz[3 * c[i]];
      const double* q = &xyz[3 * c[(i + 1) % c.size()]];
      fn[0] += (p[1] - q[1]) * (p[2] + q[2]);
      fn[1] += (p[2] - q[2]) * (p[0] + q[0]);
      fn[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    for (std::uint32_t v : c)
      for (int k = 0; k < 3; ++k) n[3 * v + k] += fn[k];
  }
  for (std::size_t v = 0; v < n.size() / 3; ++v) {
    const double len = std::hypot(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
    for (int k = 0; k < 3; ++k) n[3 * v + k] /= len;
  }
  return n;
}

// A quad torus with one quad split into two triangles and two quads merged into a hexagon, so
// faces of 3, 4 and 6 corners occur; coordinates that are not exact in float.
Fixture mixed_surface() {
  const SurfaceMesh t = make_quad_torus(8, 5, 1.0 / 3.0 + 1.0, 0.4);
  Fixture s;
  for (const auto& p : t.positions) s.xyz.insert(s.xyz.end(), {p.x + 0.1, p.y - 1e-3, p.z * 1.7});
  auto add = [&](std::vector<std::uint32_t> c) {
    s.faces.items.insert(s.faces.items.end(), c.begin(), c.end());
    s.faces.offsets.push_back(static_cast<std::uint32_t>(s.faces.items.size()));
  };
  // Faces 0 and 5 of the torus share the edge id(1,0)-id(1,1) (faces (i,j) and (i+1,j)).
  const auto f0 = t.face(0), f5 = t.face(5);
  add({f0[0], f0[1], f0[2]});
  add({f0[0], f0[2], f0[3]});
  // Faces 1 and 6: (0,1) and (1,1) share id(1,1)-id(1,2) = corners 1,2 of face 1.
  const auto f1 = t.face(1), f6 = t.face(6);
  add({f1[0], f1[1], f6[1], f6[2], f1[2], f1[3]});
  for (std::size_t f = 2; f < t.num_faces(); ++f)
    if (f != 5 && f != 6) add({t.face(f).begin(), t.face(f).end()});
  add({f5.begin(), f5.end()});
  s.normals = vertex_normals(s.faces, s.xyz);
  return s;
}

std::size_t triangle_count(const Csr& faces) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < faces.rows(); ++f) n += faces.size(f) - 2;
  return n;
}

void expect_faces_equal(const SurfaceMesh& m, const Csr& faces) {
  EXPECT_EQ(m.face_offsets, faces.offsets);
  EXPECT_EQ(m.face_indices, faces.items);
}

double length(const double* n) { return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]); }

// `vn` lines of an OBJ file, parsed here rather than by the import layer (which skips them).
std::vector<double> obj_normals(const std::string& text) {
  std::vector<double> n;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("vn ", 0) == 0) {
      std::istringstream ls(line.substr(3));
      double x, y, z;
      ls >> x >> y >> z;
      n.insert(n.end(), {x, y, z});
    }
  return n;
}

// tinygltf with no file-system access and no image decoding: everything comes from memory.
tinygltf::Model load_gltf(const std::string& bytes, bool binary) {
  tinygltf::TinyGLTF loader;
  tinygltf::FsCallbacks fs{};
  fs.FileExists = [](const std::string&, void*) { return false; };
  fs.ExpandFilePath = [](const std::string& p, void*) { return p; };
  fs.ReadWholeFile = [](std::vector<unsigned char>*, std::string* err, const std::string& p, void*) {
    if (err) *err = "file access refused: " + p;
    return false;
  };
  fs.WriteWholeFile = [](std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; };
  loader.SetFsCallbacks(fs);
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                           void*) { return false; },
                        nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       static_cast<unsigned>(bytes.size()), "")
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()), "");
  EXPECT_TRUE(ok) << err;
  EXPECT_TRUE(warn.empty()) << warn;
  return model;
}

// The values of a tightly packed accessor, as T.
template <class T>
std::vector<T> accessor_values(const tinygltf::Model& m, int accessor, int components) {
  const tinygltf::Accessor& a = m.accessors.at(accessor);
  const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
  const tinygltf::Buffer& b = m.buffers.at(v.buffer);
  const std::size_t n = a.count * components;
  EXPECT_LE(v.byteOffset + a.byteOffset + n * sizeof(T), b.data.size());
  EXPECT_TRUE(v.byteStride == 0 || v.byteStride == components * sizeof(T));
  std::vector<T> out(n);
  std::memcpy(out.data(), b.data.data() + v.byteOffset + a.byteOffset, n * sizeof(T));
  return out;
}

void check_gltf(const tinygltf::Model& m, const Fixture& s) {
  EXPECT_EQ(m.asset.version, "2.0");
  EXPECT_EQ(m.asset.generator, "Sublift");
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].nodes, std::vector<int>{0});
  ASSERT_EQ(m.nodes.size(), 1u);
  EXPECT_EQ(m.nodes[0].mesh, 0);
  ASSERT_EQ(m.meshes.size(), 1u);
  ASSERT_EQ(m.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& p = m.meshes[0].primitives[0];
  EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
  ASSERT_TRUE(p.attributes.count("POSITION"));
  ASSERT_TRUE(p.attributes.count("NORMAL"));
  const std::size_t nv = s.num_vertices();

  const tinygltf::Accessor& pa = m.accessors.at(p.attributes.at("POSITION"));
  EXPECT_EQ(pa.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(pa.type, TINYGLTF_TYPE_VEC3);
  ASSERT_EQ(pa.count, nv);
  const std::vector<float> pos = accessor_values<float>(m, p.attributes.at("POSITION"), 3);
  ASSERT_EQ(pa.minValues.size(), 3u);
  ASSERT_EQ(pa.maxValues.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    float lo = pos[k], hi = pos[k];
    for (std::size_t v = 0; v < nv; ++v) lo = std::min(lo, pos[3 * v + k]), hi = std::max(hi, pos[3 * v + k]);
    EXPECT_EQ(pa.minValues[k], double(lo));  // exactly the float bounds, as validators check
    EXPECT_EQ(pa.maxValues[k], double(hi));
  }
  for (std::size_t i = 0; i < 3 * nv; ++i) EXPECT_EQ(pos[i], static_cast<float>(s.xyz[i])) << i;

  const tinygltf::Accessor& na = m.accessors.at(p.attributes.at("NORMAL"));
  EXPECT_EQ(na.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(na.type, TINYGLTF_TYPE_VEC3);
  EXPECT_FALSE(na.normalized);  // the flag is for integer types; float normals are unit vectors
  ASSERT_EQ(na.count, nv);
  const std::vector<float> nrm = accessor_values<float>(m, p.attributes.at("NORMAL"), 3);
  for (std::size_t v = 0; v < nv; ++v) {
    const double n[3] = {nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]};
    EXPECT_NEAR(length(n), 1.0, 1e-6);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[k], s.normals[3 * v + k], 1e-6);
  }

  const tinygltf::Accessor& ia = m.accessors.at(p.indices);
  EXPECT_EQ(ia.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  EXPECT_EQ(ia.type, TINYGLTF_TYPE_SCALAR);
  ASSERT_EQ(ia.count, 3 * triangle_count(s.faces));
  const std::vector<std::uint32_t> idx = accessor_values<std::uint32_t>(m, p.indices, 1);
  std::vector<std::uint32_t> fans;
  for (std::size_t f = 0; f < s.faces.rows(); ++f) {
    const auto c = s.faces.row(f);
    for (std::size_t i = 1; i + 1 < c.size(); ++i) fans.insert(fans.end(), {c[0], c[i], c[i + 1]});
  }
  EXPECT_EQ(idx, fans);
}

}  // namespace

TEST(SurfaceExport, ObjRoundTrip) {
  TempDir dir("sublift_surface_export_obj");
  const Fixture s = mixed_surface();
  const std::string path = dir.file("s.obj");
  write_surface_with_normals(path, s.faces, s.xyz, s.normals);
  const LoadedMesh back = import_surface_mesh(path);
  EXPECT_TRUE(back.report.empty()) << back.report.format(path);
  ASSERT_EQ(back.mesh.num_vertices(), s.num_vertices());
  expect_faces_equal(back.mesh, s.faces);
  for (std::size_t v = 0; v < s.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(back.mesh.positions[v][k], s.xyz[3 * v + k]);  // 17 digits: exact
  const std::string text = read_file_bytes(path);
  const std::vector<double> n = obj_normals(text);
  ASSERT_EQ(n.size(), s.normals.size());
  for (std::size_t v = 0; v < s.num_vertices(); ++v) {
    EXPECT_NEAR(length(&n[3 * v]), 1.0, 1e-15);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(n[3 * v + k], s.normals[3 * v + k]);
  }
  const auto c = s.faces.row(0);
  EXPECT_NE(text.find("\nf " + std::to_string(c[0] + 1) + "//" + std::to_string(c[0] + 1) + ' '), std::string::npos);
}

TEST(SurfaceExport, BinaryPlyRoundTrip) {
  TempDir dir("sublift_surface_export_ply");
  const Fixture s = mixed_surface();
  const std::string path = dir.file("s.ply");
  write_surface_with_normals(path, s.faces, s.xyz, s.normals);
  const LoadedMesh back = import_surface_mesh(path);
  EXPECT_TRUE(back.report.empty()) << back.report.format(path);
  ASSERT_EQ(back.mesh.num_vertices(), s.num_vertices());
  expect_faces_equal(back.mesh, s.faces);
  for (std::size_t v = 0; v < s.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(back.mesh.positions[v][k], s.xyz[3 * v + k]);  // float64: exact
  // The header as promised, and the normals straight from the binary body.
  const std::string bytes = read_file_bytes(path);
  const std::size_t body = bytes.find("end_header\n") + 11;
  const std::string header = bytes.substr(0, body);
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(header.find("property double nx\nproperty double ny\nproperty double nz\n"), std::string::npos);
  EXPECT_NE(header.find("property list uchar uint vertex_indices"), std::string::npos);
  ASSERT_GE(bytes.size(), body + 48 * s.num_vertices());
  for (std::size_t v = 0; v < s.num_vertices(); ++v) {
    double row[6];
    std::memcpy(row, bytes.data() + body + 48 * v, 48);  // little-endian host (x86-64, aarch64)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(row[k], s.xyz[3 * v + k]);
    EXPECT_NEAR(length(row + 3), 1.0, 1e-15);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(row[3 + k], s.normals[3 * v + k]);
  }
  std::size_t face_bytes = 0;
  for (std::size_t f = 0; f < s.faces.rows(); ++f) face_bytes += 1 + 4 * s.faces.size(f);
  EXPECT_EQ(bytes.size(), body + 48 * s.num_vertices() + face_bytes);
}

TEST(SurfaceExport, PlyFaceOfMoreThan255CornersUsesUintCounts) {
  TempDir dir("sublift_surface_export_wide");
  Fixture s;
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n;
    s.xyz.insert(s.xyz.end(), {std::cos(a), std::sin(a), 0.0});
    s.normals.insert(s.normals.end(), {0.0, 0.0, 2.0});  // not unit: renormalised on write
    s.faces.items.push_back(static_cast<std::uint32_t>(i));
  }
  s.faces.offsets.push_back(n);
  const std::string path = dir.file("wide.ply");
  write_surface_with_normals(path, s.faces, s.xyz, s.normals);
  EXPECT_NE(read_file_bytes(path).find("property list uint uint vertex_indices"), std::string::npos);
  const LoadedMesh back = import_surface_mesh(path);
  ASSERT_EQ(back.mesh.num_faces(), 1u);
  EXPECT_EQ(back.mesh.face_size(0), std::size_t(n));
  const std::vector<double> on = obj_normals([&] {
    write_surface_with_normals(dir.file("wide.obj"), s.faces, s.xyz, s.normals);
    return read_file_bytes(dir.file("wide.obj"));
  }());
  ASSERT_EQ(on.size(), s.normals.size());
  EXPECT_EQ(on[2], 1.0);
}

TEST(SurfaceExport, GltfAndGlbReadBackThroughTinygltf) {
  TempDir dir("sublift_surface_export_gltf");
  const Fixture s = mixed_surface();
  const std::string gltf = dir.file("s.gltf"), glb = dir.file("s.GLB");
  write_surface_with_normals(gltf, s.faces, s.xyz, s.normals);
  write_surface_with_normals(glb, s.faces, s.xyz, s.normals);
  const std::string text = read_file_bytes(gltf);
  EXPECT_NE(text.find("data:application/octet-stream;base64,"), std::string::npos);
  EXPECT_NE(text.find("\"generator\": \"Sublift\""), std::string::npos);
  {
    SCOPED_TRACE(".gltf");
    check_gltf(load_gltf(text, false), s);
  }
  const std::string bin = read_file_bytes(glb);
  EXPECT_EQ(bin.substr(0, 4), "glTF");
  EXPECT_EQ(bin.size() % 4, 0u);
  {
    SCOPED_TRACE(".glb");
    const tinygltf::Model m = load_gltf(bin, true);
    check_gltf(m, s);
    ASSERT_EQ(m.buffers.size(), 1u);
    EXPECT_TRUE(m.buffers[0].uri.empty());  // the GLB's own BIN chunk
  }
  // A single triangle: the smallest glTF, min/max equal where all values agree.
  Fixture t;
  t.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  t.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  t.faces.items = {0, 1, 2};
  t.faces.offsets = {0, 3};
  write_surface_with_normals(gltf, t.faces, t.xyz, t.normals);
  check_gltf(load_gltf(read_file_bytes(gltf), false), t);
}

TEST(SurfaceExport, SupportedExtensionsAndBadInput) {
  EXPECT_TRUE(surface_export_supported("a.obj"));
  EXPECT_TRUE(surface_export_supported("dir.x/a.PLY"));
  EXPECT_TRUE(surface_export_supported("a.gltf"));
  EXPECT_TRUE(surface_export_supported("a.Glb"));
  EXPECT_FALSE(surface_export_supported("a.off"));
  EXPECT_FALSE(surface_export_supported("a.stl"));
  EXPECT_FALSE(surface_export_supported("obj"));
  EXPECT_FALSE(surface_export_supported(""));

  TempDir dir("sublift_surface_export_bad");
  const Fixture s = mixed_surface();
  auto error = [&](const std::string& name, const Csr& faces, const std::vector<double>& xyz, const std::vector<double>& n) {
    return input_error([&] { write_surface_with_normals(dir.file(name), faces, xyz, n); });
  };
  EXPECT_NE(error("s.stl", s.faces, s.xyz, s.normals).find("expected .obj, .ply, .gltf or .glb"), std::string::npos);
  EXPECT_NE(error("s", s.faces, s.xyz, s.normals).find("cannot export"), std::string::npos);
  std::vector<double> short_normals(s.normals.begin(), s.normals.end() - 3);
  EXPECT_NE(error("s.obj", s.faces, s.xyz, short_normals).find("normals for"), std::string::npos);
  std::vector<double> nan = s.xyz;
  nan[4] = std::nan("");
  EXPECT_NE(error("s.ply", s.faces, nan, s.normals).find("vertex 1 is not finite"), std::string::npos);
  Csr dangling = s.faces;
  dangling.items[2] = 100000;
  EXPECT_NE(error("s.glb", dangling, s.xyz, s.normals).find("names vertex 100000"), std::string::npos);
  // No faces (a lattice whose cells share every face has no boundary): refused in every format,
  // not written as bare vertices.
  Csr empty;
  for (const char* name : {"s.gltf", "s.obj", "s.ply", "s.glb"})
    EXPECT_EQ(error(name, empty, s.xyz, s.normals),
              dir.file(name) + ": the surface has no faces (a lattice without boundary faces?); nothing written");
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));  // nothing written, no temporary left
}

TEST(SurfaceExport, FailedSaveLeavesTheExistingFile) {
  TempDir dir("sublift_surface_export_atomic");
  const Fixture s = mixed_surface();
  for (const char* ext : {"obj", "ply", "gltf", "glb"}) {
    SCOPED_TRACE(ext);
    // The target is a directory: the rename fails, the directory and its content stay.
    const std::string as_dir = dir.file(std::string("d.") + ext);
    std::filesystem::create_directory(as_dir);
    const std::string inside = as_dir + "/keep.txt";
    write_file_atomic(inside, [](std::ostream& o) { o << "keep"; });
    EXPECT_THROW(write_surface_with_normals(as_dir, s.faces, s.xyz, s.normals), IoError);
    EXPECT_TRUE(std::filesystem::is_directory(as_dir));
    EXPECT_EQ(read_file_bytes(inside), "keep");
    // Bad input refused before the file is touched.
    const std::string path = dir.file(std::string("s.") + ext);
    write_file_atomic(path, [](std::ostream& o) { o << "previous"; });
    std::vector<double> nan = s.normals;
    nan[0] = std::nan("");
    EXPECT_THROW(write_surface_with_normals(path, s.faces, s.xyz, nan), InputError);
    EXPECT_EQ(read_file_bytes(path), "previous");
    // A folder that cannot be written (permissions do not stop root; /proc stops everyone).
    if (geteuid() != 0) {
      std::filesystem::permissions(dir.path(), std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
      EXPECT_THROW(write_surface_with_normals(path, s.faces, s.xyz, s.normals), IoError);
      std::filesystem::permissions(dir.path(), std::filesystem::perms::owner_all);
      EXPECT_EQ(read_file_bytes(path), "previous");
    }
    EXPECT_THROW(write_surface_with_normals(std::string("/proc/sublift_surface.") + ext, s.faces, s.xyz, s.normals), IoError);
    EXPECT_THROW(write_surface_with_normals(dir.file(std::string("missing/s.") + ext), s.faces, s.xyz, s.normals), IoError);
  }
  // Only the files made above; no temporaries left behind.
  std::size_t entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    ++entries;
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
  }
  EXPECT_EQ(entries, 8u);
}
