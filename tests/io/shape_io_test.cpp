// Reading and writing shapes by extension, polylines (OBJ `l`), the tags that carry feature
// dims through files, exact level sizes before refinement, and the connectivity check of
// `analyze`.
#include <algorithm>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "core/complex/cell_shapes.h"
#include "core/complex/complex_build.h"
#include "core/complex/connectivity_match.h"
#include "core/complex/feature_tags.h"
#include "core/base/file_io.h"
#include "core/io/lattice/lattice_format.h"
#include "core/complex/level_counts.h"
#include "core/io/mesh/mesh_export.h"
#include "core/io/mesh/mesh_import.h"
#include "core/complex/refine.h"
#include "core/io/lattice/shape_io.h"
#include "core/complex/shapes.h"
#include "tests/io_test_util.h"
#include "tests/test_util.h"

using namespace sublift;
using sublift::testing::dims_by_vertices;
using sublift::testing::input_error;
using sublift::testing::TempDir;

namespace {

const std::string kAssets = SUBLIFT_ASSETS_DIR;

const std::string kCurveObj =
    "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n"          // open chain 1-4
    "v 0 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"          // closed square 5-8
    "l 1 2/1 3 4\nl 5 6 7 8 5\nt corner 1/1/0 6 10\n";

Complex surface_with_features() {
  const SurfaceMesh torus = make_quad_torus(8, 6);
  Csr faces;
  faces.offsets = torus.face_offsets;
  faces.items = torus.face_indices;
  FeatureTags t;
  for (std::uint32_t i = 0; i < 8; ++i) t.crease_edges.emplace_back(i * 6, ((i + 1) % 8) * 6);  // a crease loop
  t.crease_edges.emplace_back(3, 4);  // a dart
  t.corner_vertices = {2 * 6};
  return complex_from_polygons(static_cast<std::uint32_t>(torus.num_vertices()), faces, t);
}

Complex lattice_with_features() {
  return read_shape(kAssets + "/feature_surface.lattice").base;
}

// assign_feature_dims(derive_feature_tags(c)) on c's bare topology gives c's dims back.
void expect_tags_reproduce_dims(const Complex& c) {
  Complex bare;
  bare.dim = c.dim;
  bare.num_vertices = c.num_vertices;
  bare.edge_verts = c.edge_verts;
  bare.faces = c.faces;
  bare.face_edges = c.face_edges;
  bare.cell_faces = c.cell_faces;
  assign_feature_dims(bare, derive_feature_tags(c));
  EXPECT_EQ(bare.vertex_dim, c.vertex_dim);
  EXPECT_EQ(bare.edge_dim, c.edge_dim);
  EXPECT_EQ(bare.face_dim, c.face_dim);
}

}  // namespace

TEST(Polylines, ObjReaderKeepsThemWithRelativeIndices) {
  const LoadedMesh m = import_surface_mesh_from_memory("c.obj", kCurveObj + "v 9 9 9\nl -1 -2\n");
  ASSERT_EQ(m.mesh.num_polylines(), 3u);
  EXPECT_EQ(m.mesh.num_faces(), 0u);
  EXPECT_EQ(std::vector<std::uint32_t>(m.mesh.polyline(0).begin(), m.mesh.polyline(0).end()),
            (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(std::vector<std::uint32_t>(m.mesh.polyline(2).begin(), m.mesh.polyline(2).end()),
            (std::vector<std::uint32_t>{8, 7}));
  EXPECT_TRUE(m.report.empty()) << m.report.format("c.obj");
}

TEST(Polylines, BadOnesAreDroppedAndItemisedWithLines) {
  const LoadedMesh m = import_surface_mesh_from_memory("c.obj",
                                                       "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n"  // 1-4
                                                       "l 1 2\n"                               // 5 ok
                                                       "l 1 9\n"                               // 6 out of range
                                                       "l 3\n"                                 // 7 one vertex
                                                       "l 3 3\n"                               // 8 one distinct
                                                       "l 2 1\n"                               // 9 segment reused
                                                       "l 2 3 3 4\n"                           // 10 repaired
                                                       "l 0 1\n"                               // 11 zero index
                                                       "p 1\n");                               // 12 ignored
  ASSERT_EQ(m.mesh.num_polylines(), 2u);
  auto lines = [&](const char* what) {
    const auto* w = sublift::testing::find_warning(m.report, what);
    return w ? w->first_lines : std::vector<std::size_t>{};
  };
  EXPECT_EQ(lines("polyline dropped: vertex index out of range"), std::vector<std::size_t>{6});
  EXPECT_EQ(lines("polyline dropped: fewer than 2 vertices"), std::vector<std::size_t>{7});
  EXPECT_EQ(lines("fewer than 2 distinct"), std::vector<std::size_t>{8});
  EXPECT_EQ(lines("segment occurs twice"), std::vector<std::size_t>{9});
  EXPECT_EQ(lines("polyline repaired"), std::vector<std::size_t>{10});
  EXPECT_EQ(lines("unreadable or zero"), std::vector<std::size_t>{11});
  EXPECT_EQ(lines("point element ignored"), std::vector<std::size_t>{12});
}

TEST(Polylines, WriteReadRoundTripIsExact) {
  TempDir dir("sublift_polyline_rt");
  LoadedMesh m = import_surface_mesh_from_memory("c.obj", kCurveObj);
  m.mesh.positions[1] = {1.0 / 3.0, -2.2250738585072014e-308, 1e29};
  const std::string path = dir.file("c.obj");
  write_surface_mesh(path, m.mesh);
  const LoadedMesh back = import_surface_mesh(path);
  EXPECT_EQ(back.mesh.positions, m.mesh.positions);
  EXPECT_EQ(back.mesh.line_offsets, m.mesh.line_offsets);
  EXPECT_EQ(back.mesh.line_indices, m.mesh.line_indices);
  EXPECT_THROW(write_surface_mesh(dir.file("c.off"), m.mesh), InputError);  // OFF has no polylines
  EXPECT_THROW(write_surface_mesh(dir.file("c.ply"), m.mesh), InputError);
}

TEST(ShapeIo, ReadsEveryFormatByExtension) {
  const Shape surf = read_shape(kAssets + "/crease_loop.obj");
  EXPECT_EQ(surf.base.dim, 2);
  EXPECT_EQ(surf.positions.size(), 3 * std::size_t(surf.base.num_vertices));
  std::size_t creases = 0;
  for (auto d : surf.base.edge_dim) creases += d == 1;
  EXPECT_EQ(creases, 4u);
  const Shape curve = read_shape_from_memory("c.obj", kCurveObj);
  EXPECT_EQ(curve.base.dim, 1);
  EXPECT_EQ(curve.base.num_edges(), 7u);
  EXPECT_EQ(curve.base.vertex_dim[6], 0);  // corner tag (0-based, as OpenSubdiv writes it)
  EXPECT_EQ(curve.base.vertex_dim[5], 1);
  EXPECT_EQ(curve.base.vertex_dim[0], 0);  // open end
  EXPECT_EQ(curve.base.vertex_dim[1], 1);
  EXPECT_EQ(read_shape(kAssets + "/prism_ring.lattice").base.num_cells(), 8u);
  EXPECT_NE(input_error([] { read_shape_from_memory("x.stl", "solid"); }).find("unsupported format '.stl'"),
            std::string::npos);
  EXPECT_THROW(read_shape("/no/such/file.lattice"), IoError);
}

TEST(ShapeIo, WritesEveryDimensionAndReadsItBack) {
  TempDir dir("sublift_shape_io");
  struct Case { Complex c; std::vector<const char*> exts; };
  const Shape curve = read_shape_from_memory("c.obj", kCurveObj);
  const Case cases[] = {{refine(curve.base), {"obj", "vtk"}},
                        {refine(surface_with_features()), {"obj", "vtk"}},
                        {refine(lattice_with_features()), {"lattice", "vtk"}}};
  for (const Case& k : cases) {
    const auto xyz = sublift::testing::awkward_positions(k.c.num_vertices, k.c.num_vertices);
    for (const char* ext : k.exts) {
      SCOPED_TRACE(std::string("dim ") + std::to_string(k.c.dim) + " ." + ext);
      const std::string path = dir.file(std::string("s.") + ext);
      EXPECT_TRUE(write_shape(path, k.c, xyz).empty());
      const Shape back = read_shape(path);
      EXPECT_EQ(back.positions, xyz);
      EXPECT_EQ(back.base.num_edges(), k.c.num_edges());
      EXPECT_EQ(back.base.num_faces(), k.c.num_faces());
      EXPECT_EQ(back.base.num_cells(), k.c.num_cells());
      EXPECT_EQ(dims_by_vertices(back.base), dims_by_vertices(k.c));
      EXPECT_EQ(connectivity_mismatch(k.c, back.base), "");
      EXPECT_TRUE(back.report.empty()) << back.report.format(path);
    }
  }
  // Formats that cannot hold a dimension are refused; OFF/PLY drop tags with a note.
  const Complex s = surface_with_features();
  const auto xyz = sublift::testing::awkward_positions(s.num_vertices, 1);
  EXPECT_THROW(write_shape(dir.file("s.lattice"), s, xyz), InputError);
  EXPECT_THROW(write_shape(dir.file("s.stl"), s, xyz), InputError);
  EXPECT_THROW(write_shape(dir.file("c.off"), curve.base, curve.positions), InputError);
  const auto notes = write_shape(dir.file("s.off"), s, xyz);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("cannot hold feature tags"), std::string::npos);
  EXPECT_EQ(shape_output_problem("x.obj", 3), "a lattice cannot be written as .obj; use .lattice, .ovm or .vtk");
  EXPECT_EQ(shape_output_problem("x.vtk", 1), "");
}

TEST(ShapeIo, CurvesAreWrittenAsMaximalPolylines) {
  TempDir dir("sublift_curve_chains");
  const Shape curve = read_shape_from_memory("c.obj", kCurveObj);
  write_shape(dir.file("c.obj"), curve.base, curve.positions);
  const LoadedMesh m = import_surface_mesh(dir.file("c.obj"));
  ASSERT_EQ(m.mesh.num_polylines(), 2u);  // one open chain, one closed loop
  EXPECT_EQ(m.mesh.polyline(0).size(), 4u);
  EXPECT_EQ(m.mesh.polyline(1).size(), 5u);
  EXPECT_EQ(m.mesh.polyline(1).front(), m.mesh.polyline(1).back());
}

TEST(FeatureTags, DerivedTagsReproduceTheDimsOfRefinedLevels) {
  std::vector<double> pos;
  Complex curve = make_curve_loop(9, pos);
  assign_feature_dims(curve, {{}, {4}, {}});
  for (const Complex& base : {curve, surface_with_features(), lattice_with_features(),
                              read_shape(kAssets + "/prism_ring.lattice").base}) {
    SCOPED_TRACE("dim " + std::to_string(base.dim));
    expect_tags_reproduce_dims(base);
    const Complex one = refine(base);
    expect_tags_reproduce_dims(one);
    expect_tags_reproduce_dims(refine(one));
  }
  // The feature-surface asset's tags are exactly its 9 inner faces.
  const FeatureTags t = derive_feature_tags(lattice_with_features());
  EXPECT_EQ(t.feature_faces.size(), 9u);
  EXPECT_TRUE(t.crease_edges.empty());
  EXPECT_TRUE(t.corner_vertices.empty());
}

TEST(LevelCounts, PredictionsEqualRefinement) {
  std::vector<double> pos;
  for (const Complex& base : {make_curve_loop(5, pos), surface_with_features(), read_shape(kAssets + "/mixed_polygons.obj").base,
                              read_shape(kAssets + "/prism_ring.lattice").base, read_shape(kAssets + "/pyramid_cell.lattice").base,
                              lattice_with_features()}) {
    const std::vector<double> want = predicted_vertex_counts(base, 3);
    Complex c = base;
    for (int j = 0; j <= 3; ++j) {
      EXPECT_EQ(want[static_cast<std::size_t>(j)], double(c.num_vertices)) << "dim " << base.dim << " level " << j;
      if (j < 3) c = refine(c);
    }
  }
}

TEST(CellShapes, HexahedronOrderFromAnyFaceOrderAndOrientation) {
  // A cube whose faces are listed shuffled and with mixed orientations.
  const Shape s = read_lattice("sublift-lattice 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "cell\nf 5 6 2 1\nf 7 6 5 4\nf 0 1 2 3\nf 2 6 7 3\nf 0 4 5 1\nf 3 7 4 0\nend\n",
                               "c.lattice");
  const auto loops = oriented_cell_loops(s.base, s.positions, 0);
  const auto h = hexahedron_vertices(loops);
  ASSERT_TRUE(h.has_value());
  auto p = [&](int i) { return glm::dvec3(s.positions[3 * (*h)[i]], s.positions[3 * (*h)[i] + 1], s.positions[3 * (*h)[i] + 2]); };
  // VTK: 0-1-2-3 a quad, 4+i above i, right-handed.
  EXPECT_GT(glm::dot(glm::cross(p(1) - p(0), p(3) - p(0)), p(4) - p(0)), 0);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(glm::length(p(4 + i) - p(i)), 1.0);
  const Shape w = read_shape(kAssets + "/prism_ring.lattice");
  EXPECT_FALSE(hexahedron_vertices(oriented_cell_loops(w.base, w.positions, 0)).has_value());
}

TEST(CellShapes, LatticeLoopsAgreeAcrossSharedFacesAndPointOutward) {
  for (const char* name : {"/prism_ring.lattice", "/hex_block_4.lattice"}) {
  SCOPED_TRACE(name);
  const Shape s = read_shape(kAssets + name);
  const Complex& c = s.base;
  const std::vector<double>& xyz = s.positions;
  // Mirrored, every cell is inside out under its own vertex order; arbitrary positions invert
  // some cells and not others. Either way a shared face runs opposite ways in its two cells.
  std::vector<double> mirrored = xyz;
  for (std::size_t i = 0; i < mirrored.size(); i += 3) mirrored[i] = -mirrored[i];
  for (const auto& positions : {xyz, mirrored, sublift::testing::awkward_positions(c.num_vertices, 7)}) {
    const auto loops = oriented_lattice_loops(c, positions);
    ASSERT_EQ(loops.size(), c.num_cells());
    std::size_t shared = 0;
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
      const auto users = c.face_cells.row(f);
      if (users.size() != 2) continue;
      auto loop_in = [&](std::uint32_t k) {
        const auto row = c.cell_faces.row(k);
        return loops[k][static_cast<std::size_t>(std::find(row.begin(), row.end(), f) - row.begin())];
      };
      auto a = loop_in(users[0]), b = loop_in(users[1]);
      std::reverse(b.begin(), b.end());
      std::rotate(b.begin(), std::find(b.begin(), b.end(), a[0]), b.end());
      EXPECT_EQ(a, b) << "face " << f;
      ++shared;
    }
    EXPECT_GT(shared, 0u);
  }
  // Where the geometry is sane (as given, or mirrored as a whole) every cell is outward.
  for (const auto& positions : {xyz, mirrored}) {
    const auto loops = oriented_lattice_loops(c, positions);
    for (std::uint32_t k = 0; k < c.num_cells(); ++k)
      EXPECT_EQ(loops[k], oriented_cell_loops(c, positions, k)) << "cell " << k;
  }
  }
}

TEST(ConnectivityMatch, NamesTheFirstDifference) {
  const Complex a = refine(lattice_with_features());
  EXPECT_EQ(connectivity_mismatch(a, a), "");
  const Complex b = refine(refine(lattice_with_features()));
  EXPECT_NE(connectivity_mismatch(b, a).find("vertices"), std::string::npos);
  // Same counts, one face different: swap two vertex numbers in the surface's face list.
  const Complex s = surface_with_features();
  Csr faces = s.faces;
  std::swap(faces.items[0], faces.items[6]);  // faces (8 6 7 1) and (1 7 0 2): valid, but not the torus's
  const std::string why = connectivity_mismatch(s, complex_from_polygons(s.num_vertices, faces));
  EXPECT_NE(why.find("face"), std::string::npos) << why;
  EXPECT_NE(connectivity_mismatch(s, a).find("dimension"), std::string::npos);
}
