// .sublift projects: bit-exact round trips for curves, surfaces and lattices (any channels,
// integer flag), and refusal of every kind of damaged file before anything is allocated.
#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "core/complex/complex_build.h"
#include "core/base/file_io.h"
#include "core/io/lattice/lattice_format.h"
#include "core/io/project/project_io.h"
#include "core/complex/shapes.h"
#include "tests/io_test_util.h"

using namespace sublift;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

// A hierarchy with random, awkward coefficients (subnormals, -0, huge and tiny values).
Hierarchy random_hierarchy(Complex base, int levels, int channels, bool integer, std::uint64_t seed) {
  Hierarchy h = make_hierarchy(std::move(base), levels, Scheme::Cubic, channels, integer);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < h.coeffs.size(); ++i) {
    const double x = u(rng);
    h.coeffs[i] = integer ? std::round(x * 1000) : x * std::pow(10.0, double(i % 40) - 20.0);
  }
  if (!integer && h.coeffs.size() > 3) {
    h.coeffs[0] = -0.0;
    h.coeffs[1] = std::numeric_limits<double>::denorm_min();
    h.coeffs[2] = 1.0 / 3.0;
  }
  return h;
}

void expect_same(const Hierarchy& a, const Hierarchy& b) {
  EXPECT_EQ(a.scheme, b.scheme);
  EXPECT_EQ(a.integer, b.integer);
  EXPECT_EQ(a.channels, b.channels);
  ASSERT_EQ(a.levels.size(), b.levels.size());
  ASSERT_EQ(a.coeffs.size(), b.coeffs.size());
  EXPECT_EQ(std::memcmp(a.coeffs.data(), b.coeffs.data(), a.coeffs.size() * sizeof(double)), 0);  // bit-exact, -0 too
  const Complex &x = a.levels[0], &y = b.levels[0];
  EXPECT_EQ(x.dim, y.dim);
  EXPECT_EQ(x.num_vertices, y.num_vertices);
  EXPECT_EQ(x.edge_verts, y.edge_verts);
  EXPECT_EQ(x.faces.offsets, y.faces.offsets);
  EXPECT_EQ(x.faces.items, y.faces.items);
  EXPECT_EQ(x.face_edges.items, y.face_edges.items);
  EXPECT_EQ(x.cell_faces.offsets, y.cell_faces.offsets);
  EXPECT_EQ(x.cell_faces.items, y.cell_faces.items);
  EXPECT_EQ(x.vertex_dim, y.vertex_dim);
  EXPECT_EQ(x.edge_dim, y.edge_dim);
  EXPECT_EQ(x.face_dim, y.face_dim);
  for (std::size_t j = 0; j < a.levels.size(); ++j) EXPECT_EQ(a.levels[j].num_vertices, b.levels[j].num_vertices);
}

Complex lattice_with_features() {
  return read_lattice(
             "sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
             "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0 1 2\nv 0.5 0.5 3\n"
             "hex 0 1 2 3 4 5 6 7\nhex 4 5 6 7 8 9 10 11\npyramid 8 9 10 11 12\nfeature_face 4 5 6 7\ncrease 0 1\ncorner 2\n",
             "l.lattice")
      .base;
}

std::string saved(const Hierarchy& h, const TempDir& dir) {
  const std::string path = dir.file("p.sublift");
  write_project(path, h);
  return read_file_bytes(path);
}

std::string error_of(const std::string& bytes) {
  return input_error([&] { read_project_from_memory("p.sublift", bytes); });
}

}  // namespace

TEST(ProjectIo, RoundTripIsBitExactForEveryDimension) {
  TempDir dir("sublift_project_rt");
  std::vector<double> pos;
  const Complex curve = make_curve_loop(7, pos);
  const SurfaceMesh torus = make_quad_torus(6, 4);
  Csr faces;
  faces.offsets = torus.face_offsets;
  faces.items = torus.face_indices;
  const Complex surface = complex_from_polygons(static_cast<std::uint32_t>(torus.num_vertices()), faces, {{{0, 1}}, {5}, {}});
  struct Case { Complex base; int levels, channels; bool integer; };
  const Case cases[] = {{curve, 3, 1, false}, {surface, 2, 3, false}, {surface, 1, 4, true},
                        {lattice_with_features(), 2, 3, false}, {lattice_with_features(), 0, 2, true}};
  std::uint64_t seed = 1;
  for (const Case& c : cases) {
    SCOPED_TRACE("dim " + std::to_string(c.base.dim) + ", levels " + std::to_string(c.levels));
    const Hierarchy h = random_hierarchy(c.base, c.levels, c.channels, c.integer, seed++);
    const std::string path = dir.file("p.sublift");
    write_project(path, h);
    const Hierarchy back = read_project(path);
    expect_same(h, back);
    EXPECT_EQ(synthesize(h, c.levels), synthesize(back, c.levels));
  }
}

TEST(ProjectIo, RefusesBadMagicVersionAndHeader) {
  TempDir dir("sublift_project_bad");
  const std::string good = saved(random_hierarchy(lattice_with_features(), 1, 3, false, 9), dir);
  EXPECT_NE(error_of("").find("not a Sublift project"), std::string::npos);
  EXPECT_NE(error_of("PK\x03\x04 zip").find("not a Sublift project"), std::string::npos);
  std::string v3 = good;
  v3[16] = '3';
  EXPECT_NE(error_of(v3).find("unsupported project version '3'"), std::string::npos) << error_of(v3);
  EXPECT_NE(error_of("sublift-project 1\n{not json}\n").find("p.sublift:2: malformed header"), std::string::npos);
  EXPECT_NE(error_of("sublift-project 1\n{\"format\":\"sublift-project\"}\n").find("malformed header"), std::string::npos);
  EXPECT_NE(error_of("sublift-project 1\n").find("header"), std::string::npos);
  // Header fields out of range.
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  EXPECT_NE(error_of(with("\"levels\":1", "\"levels\":13")).find("levels 13 outside"), std::string::npos);
  EXPECT_NE(error_of(with("\"scheme\":\"cubic\"", "\"scheme\":\"catmark\"")).find("unknown scheme 'catmark'"), std::string::npos);
  EXPECT_NE(error_of(with("\"channels\":3", "\"channels\":0")).find("channels 0"), std::string::npos);
  EXPECT_NE(error_of(with("\"dim\":3", "\"dim\":4")).find("dim 4"), std::string::npos);
  // Numbers of the wrong kind: JSON takes 1e20 or 2.5 anywhere, a cast would not.
  EXPECT_NE(error_of(with("\"levels\":1", "\"levels\":1.5")).find("p.sublift:2: header 'levels' is not an integer"), std::string::npos);
  EXPECT_NE(error_of(with("\"coefficients\":", "\"coefficients\":1e20,\"x\":")).find("header 'coefficients' is not a count"), std::string::npos);
  EXPECT_NE(error_of(with("\"vertices\":", "\"vertices\":-3,\"x\":")).find("header 'vertices' is not a count"), std::string::npos);
  EXPECT_NE(error_of(with("\"channels\":3", "\"channels\":3.0")).find("header 'channels' is not an integer"), std::string::npos);
  EXPECT_NE(error_of(with("\"channels\":3", "\"disc\":2.5,\"channels\":3")).find("header 'disc' is not an integer"), std::string::npos);
}

TEST(ProjectIo, RefusesTruncatedOrPaddedPayloadAndLyingCounts) {
  TempDir dir("sublift_project_size");
  const std::string good = saved(random_hierarchy(lattice_with_features(), 1, 3, false, 3), dir);
  EXPECT_NO_THROW(read_project_from_memory("p.sublift", good));
  EXPECT_NE(error_of(good.substr(0, good.size() - 1)).find("truncated payload"), std::string::npos);
  EXPECT_NE(error_of(good + "x").find("but the header announces"), std::string::npos);
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    return s.replace(s.find(from), from.size(), to);
  };
  // Counts that would need terabytes are refused by size before anything is read.
  EXPECT_NE(error_of(with("\"coefficients\":", "\"coefficients\":99999999999")).find("truncated payload"), std::string::npos);
  EXPECT_NE(error_of(with("\"vertices\":13", "\"vertices\":4000000000")).find("truncated payload"), std::string::npos);
  // A count whose bytes exceed what a long long holds: the message, not an undefined cast.
  EXPECT_NE(error_of(with("\"coefficients\":", "\"coefficients\":9000000000000000000,\"x\":")).find("announces 7.2e+19 bytes"),
            std::string::npos)
      << error_of(with("\"coefficients\":", "\"coefficients\":9000000000000000000,\"x\":"));
  // One more level than the coefficients cover (the payload size is unchanged: the check is
  // against the refined base, before it is built).
  const std::string e = error_of(with("\"levels\":1", "\"levels\":2"));
  EXPECT_NE(e.find("levels of this base"), std::string::npos) << e;
}

TEST(ProjectIo, RefusesDamagedPayloads) {
  TempDir dir("sublift_project_payload");
  const Hierarchy h = random_hierarchy(lattice_with_features(), 1, 3, false, 5);
  const std::string good = saved(h, dir);
  const std::size_t payload = good.find('\n', good.find('\n') + 1) + 1;
  // First u32 of edge_verts: a vertex that does not exist.
  std::string dangling = good;
  const std::uint32_t big = 1000;
  std::memcpy(dangling.data() + payload, &big, 4);
  EXPECT_NE(error_of(dangling).find("names vertex 1000"), std::string::npos) << error_of(dangling);
  // A face-dim byte out of range (face_dim is just before the coefficients).
  std::string bad_dim = good;
  bad_dim[good.size() - h.coeffs.size() * 8 - 1] = 7;
  EXPECT_NE(error_of(bad_dim).find("feature dim"), std::string::npos) << error_of(bad_dim);
  // A NaN coefficient.
  std::string nan = good;
  const double q = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan.data() + good.size() - 8, &q, 8);
  EXPECT_NE(error_of(nan).find("is not finite"), std::string::npos);
  // Face offsets out of order (second offset made huge).
  std::string offs = good;
  const std::size_t face_offsets = payload + 4 * h.levels[0].edge_verts.size();
  const std::uint32_t huge = 0x7fffffff;
  std::memcpy(offs.data() + face_offsets + 4, &huge, 4);
  EXPECT_NE(error_of(offs).find("offsets"), std::string::npos) << error_of(offs);
}

TEST(ProjectIo, FailedSaveKeepsThePreviousFile) {
  TempDir dir("sublift_project_atomic");
  const Hierarchy h = random_hierarchy(lattice_with_features(), 1, 3, false, 2);
  EXPECT_THROW(write_project("/nonexistent_dir/p.sublift", h), IoError);
  const std::string path = dir.file("p.sublift");
  write_project(path, h);
  const std::string before = read_file_bytes(path);
  write_project(path, h);  // replaced atomically: same bytes, no temporary left behind
  EXPECT_EQ(read_file_bytes(path), before);
  std::size_t files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
}

namespace {

// Removes `"key":value,` from the one-line JSON header (values here are scalars or flat arrays).
std::string without_key(std::string s, const std::string& key) {
  const std::size_t at = s.find("\"" + key + "\":");
  EXPECT_NE(at, std::string::npos) << key;
  if (at == std::string::npos) return s;
  std::size_t end = at + key.size() + 3;
  if (s[end] == '[') end = s.find(']', end) + 1;
  else end = s.find_first_of(",}", end);
  if (s[end] == ',') ++end;
  return s.erase(at, end - at);
}

// Replaces the value of `"key":` in the header by `value` (adds the key when absent).
std::string with_value(const std::string& s, const std::string& key, const std::string& value) {
  std::string t = s.find("\"" + key + "\":") == std::string::npos ? s : without_key(s, key);
  return t.insert(t.find('{') + 1, "\"" + key + "\":" + value + ",");
}

}  // namespace

TEST(ProjectIo, ExtrasRoundTrip) {
  TempDir dir("sublift_project_extras");
  const Hierarchy h = random_hierarchy(lattice_with_features(), 2, 3, false, 11);
  const ProjectExtras extras{1, {1.0 / 3.0, -2.5}, true, {}, {}};
  const std::string path = dir.file("p.sublift");
  write_project(path, h, extras);
  ProjectExtras back;
  expect_same(h, read_project(path, &back));
  EXPECT_EQ(back.current_level, 1);
  EXPECT_EQ(back.gains, extras.gains);  // exact: the JSON header prints round-trip digits
  EXPECT_TRUE(back.local_frames);
  // The other entry points read the same file; null extras are allowed.
  expect_same(h, read_project(path));
  expect_same(h, read_project(path, nullptr));
  ProjectExtras mem;
  expect_same(h, read_project_from_memory("p.sublift", read_file_bytes(path), &mem));
  EXPECT_EQ(mem.gains, extras.gains);
  // Empty gains mean all 1; the two-argument writer stores the defaults.
  write_project(path, h, ProjectExtras{2, {}, false, {}, {}});
  read_project(path, &back);
  EXPECT_EQ(back.current_level, 2);
  EXPECT_EQ(back.gains, std::vector<double>(2, 1.0));
  EXPECT_FALSE(back.local_frames);
  write_project(path, h);
  back = ProjectExtras{1, {5.0}, true, {}, {}};
  read_project(path, &back);
  EXPECT_EQ(back.current_level, 0);
  EXPECT_EQ(back.gains, std::vector<double>(2, 1.0));
  EXPECT_FALSE(back.local_frames);
  // The session keys need no version of their own (version 2 is the coefficients' encoding).
  EXPECT_EQ(read_file_bytes(path).substr(0, 18), "sublift-project 2\n");
  // A fitted project's base-to-mesh map (docs/fit.md).
  ProjectExtras fitted;
  const std::uint32_t nb = h.levels[0].num_vertices;
  fitted.fit_source.mesh = "/scans/bunny \"1\".obj";
  fitted.fit_source.mesh_vertices = 5000;
  for (std::uint32_t v = 0; v < nb; ++v) fitted.fit_source.base_vertex.push_back(4999 - 7 * v);
  write_project(path, h, fitted);
  back = {};
  expect_same(h, read_project(path, &back));
  EXPECT_EQ(back.fit_source.mesh, fitted.fit_source.mesh);
  EXPECT_EQ(back.fit_source.mesh_vertices, 5000u);
  EXPECT_EQ(back.fit_source.base_vertex, fitted.fit_source.base_vertex);
  // Not fitted: none.
  write_project(path, h);
  read_project(path, &back);
  EXPECT_TRUE(back.fit_source.empty());
}

TEST(ProjectIo, VersionOneFilesWithoutExtrasLoadWithDefaults) {
  TempDir dir("sublift_project_old");
  const Hierarchy h = random_hierarchy(lattice_with_features(), 2, 3, false, 12);
  std::string old = saved(h, dir);
  for (const char* key : {"current_level", "gains", "local_frames"}) old = without_key(old, key);
  ASSERT_EQ(old.find("current_level"), std::string::npos);
  ASSERT_EQ(old.find("gains"), std::string::npos);
  ASSERT_EQ(old.find("local_frames"), std::string::npos);
  ProjectExtras x{2, {3.0, 4.0}, true, {}, {}};
  expect_same(h, read_project_from_memory("old.sublift", old, &x));
  EXPECT_EQ(x.current_level, 0);
  EXPECT_EQ(x.gains, std::vector<double>(2, 1.0));
  EXPECT_FALSE(x.local_frames);
  expect_same(h, read_project_from_memory("old.sublift", old));
  // An explicitly empty gain list is all 1 too.
  x = {};
  read_project_from_memory("p.sublift", with_value(saved(h, dir), "gains", "[]"), &x);
  EXPECT_EQ(x.gains, std::vector<double>(2, 1.0));
}

TEST(ProjectIo, RefusesBadExtras) {
  TempDir dir("sublift_project_bad_extras");
  const Hierarchy h = random_hierarchy(lattice_with_features(), 2, 3, false, 13);
  const std::string good = saved(h, dir);
  ASSERT_NO_THROW(read_project_from_memory("p.sublift", good));
  struct Case { const char* key; const char* value; const char* says; };
  const Case cases[] = {
      {"current_level", "-1", "current_level -1 outside 0..2"},
      {"current_level", "3", "current_level 3 outside 0..2"},
      {"current_level", "1.5", "'current_level' is not an integer"},
      {"current_level", "\"1\"", "'current_level' is not an integer"},
      {"gains", "[1.0]", "1 gains, but a project of 2 levels takes 2"},
      {"gains", "[1.0,2.0,3.0]", "3 gains"},
      {"gains", "[1.0,null]", "gain of level 1 is not a number"},
      {"gains", "[1.0,\"x\"]", "gain of level 1 is not a number"},
      {"gains", "[1e999,1.0]", "malformed header"},  // JSON has no infinity: overflow is a parse error
      {"gains", "1.0", "'gains' is not an array"},
      {"local_frames", "1", "'local_frames' is not true or false"},
      {"fit_source", "[]", "'fit_source' is not an object"},
      {"fit_source", "{\"mesh\":\"m.obj\",\"mesh_vertices\":10,\"base_vertex\":[]}", "base_vertex is not a non-empty array"},
      {"fit_source", "{\"mesh\":\"m.obj\",\"mesh_vertices\":10,\"base_vertex\":[1,2]}", "fit_source names 2 base vertices, but the base has"},
      {"fit_source", "{\"mesh\":\"m.obj\",\"mesh_vertices\":10,\"base_vertex\":[-1]}", "something other than a vertex number"},
      {"fit_source", "{\"mesh\":\"m.obj\",\"base_vertex\":[1]}", "malformed header"},
      {"fit_source", "{\"mesh\":\"m.obj\",\"mesh_vertices\":1e20,\"base_vertex\":[1]}", "header 'mesh_vertices' is not a count"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.key) + " = " + c.value);
    std::size_t line = 0;
    ProjectExtras x;
    const std::string e = input_error([&] { read_project_from_memory("p.sublift", with_value(good, c.key, c.value), &x); }, &line);
    EXPECT_NE(e.find(c.says), std::string::npos) << e;
    EXPECT_NE(e.find("p.sublift"), std::string::npos) << e;
    EXPECT_EQ(line, 2u) << e;
    // The old entry point refuses the same file.
    EXPECT_FALSE(input_error([&] { read_project_from_memory("p.sublift", with_value(good, c.key, c.value)); }).empty());
  }
  {  // a base vertex past the mesh's vertices
    std::string list;
    for (std::uint32_t v = 0; v < h.levels[0].num_vertices; ++v) list += (v ? "," : "") + std::string(v == 2 ? "7" : "0");
    std::size_t line = 0;
    const std::string e = input_error(
        [&] { read_project_from_memory("p.sublift", with_value(good, "fit_source", "{\"mesh\":\"m.obj\",\"mesh_vertices\":5,\"base_vertex\":[" + list + "]}")); },
        &line);
    EXPECT_NE(e.find("base vertex 2 is mesh vertex 7, but the mesh has 5"), std::string::npos) << e;
    EXPECT_EQ(line, 2u);
  }
  // The writer refuses bad extras and leaves no file behind.
  const std::string path = dir.file("bad.sublift");
  EXPECT_THROW(write_project(path, h, ProjectExtras{3, {}, false, {}, {}}), Error);
  EXPECT_THROW(write_project(path, h, ProjectExtras{0, {1.0}, false, {}, {}}), Error);
  EXPECT_THROW(write_project(path, h, ProjectExtras{0, {1.0, std::numeric_limits<double>::infinity()}, false, {}, {}}), Error);
  ProjectExtras wrong_map;
  wrong_map.fit_source = {"m.obj", 3, std::vector<std::uint32_t>(h.levels[0].num_vertices, 3)};  // vertex 3 of 3
  EXPECT_THROW(write_project(path, h, wrong_map), Error);
  wrong_map.fit_source.base_vertex.pop_back();
  wrong_map.fit_source.base_vertex.assign(wrong_map.fit_source.base_vertex.size(), 0);
  EXPECT_THROW(write_project(path, h, wrong_map), Error);  // one base vertex short
  EXPECT_FALSE(std::filesystem::exists(path));
}
