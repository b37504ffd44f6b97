// Semi-sharp creases and corners (issue 20; docs/features.md): a crease of sharpness s is a
// feature for floor(s) levels and smooth after, the dims of every level derived from the
// sharpness left, for the Catmull-Clark-style and the triangle splits alike; the transform stays
// exact; projects and OBJ keep the sharpness; sqrt(2) keeps such tags sharp at every level. (Against OpenSubdiv: tests/schemes/peer_osd_test.)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/complex/complex_build.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/project/project_io.h"
#include "core/multires/hierarchy.h"
#include "tests/cli_run.h"
#include "tests/io_test_util.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

namespace fx = fixtures;

// The torus with the ring j = 0 tagged at `s` and vertex 9 a corner of sharpness `c`.
Complex tagged_torus(float s, float c) {
  const fx::Polygons m = fx::torus(8, 8);
  FeatureTags tags;
  for (std::uint32_t i = 0; i < 8; ++i) {
    tags.crease_edges.emplace_back(i, (i + 1) % 8);
    tags.crease_sharpness.push_back(s);
  }
  tags.corner_vertices.push_back(9);
  tags.corner_sharpness.push_back(c);
  return complex_from_polygons(m.num_vertices, m.faces, tags);
}

std::size_t creases(const Complex& c) {
  std::size_t n = 0;
  for (std::uint8_t d : c.edge_dim) n += d == 1;
  return n;
}

TEST(SemiSharp, CreasesSoftenAfterTheirSharpness) {
  const Hierarchy h = make_hierarchy(tagged_torus(2.0f, 1.0f), 4, Scheme::Cubic, 3);
  EXPECT_EQ(creases(h.levels[0]), 8u);
  EXPECT_EQ(creases(h.levels[1]), 16u);  // each crease edge halved, still sharp (s = 1 left)
  EXPECT_EQ(creases(h.levels[2]), 0u);   // s = 0: smooth from level 2 on
  EXPECT_EQ(creases(h.levels[4]), 0u);
  EXPECT_EQ(h.levels[0].vertex_dim[9], 0);  // the corner, sharpness 1: a corner at level 0 only
  EXPECT_EQ(h.levels[1].vertex_dim[9], 2);
  EXPECT_EQ(h.levels[0].vertex_dim[0], 1);  // on the crease while it is sharp
  EXPECT_EQ(h.levels[2].vertex_dim[0], 2);
  // Infinitely sharp stays sharp.
  const Hierarchy sharp = make_hierarchy(tagged_torus(INFINITY, INFINITY), 3, Scheme::Cubic, 3);
  EXPECT_EQ(creases(sharp.levels[3]), 64u);
  EXPECT_EQ(sharp.levels[3].vertex_dim[9], 0);
  // Below 1: never sharp, but kept (OpenSubdiv would blend it at the first level).
  const Complex faint = tagged_torus(0.5f, 0.5f);
  EXPECT_EQ(creases(faint), 0u);
  EXPECT_EQ(faint.edge_sharpness[0] > 0.0f, true);
}

// Random coefficients put into `h`, synthesised to the finest level and analysed back: the
// largest change of a coefficient (0 for a perfect reconstruction but for round-off).
double reconstruction_error(Hierarchy& h, unsigned seed) {
  const std::vector<double> coeffs = testing::random_values(h.coeffs.size(), seed);
  h.coeffs = coeffs;
  Hierarchy back = h;
  analyze(back, synthesize(h, h.finest_level()));
  double worst = 0;
  for (std::size_t i = 0; i < coeffs.size(); ++i) worst = std::max(worst, std::abs(back.coeffs[i] - coeffs[i]));
  return worst;
}

TEST(SemiSharp, PerfectReconstructionAndTheProjectKeepsTheSharpness) {
  Hierarchy h = make_hierarchy(tagged_torus(2.0f, 1.0f), 3, Scheme::Cubic, 3);
  EXPECT_LT(reconstruction_error(h, 11), 1e-12);
  const std::vector<double> fine = synthesize(h, 3);
  testing::TempDir dir("sublift_semisharp_project");
  write_project(dir.file("p.sublift"), h);
  const Hierarchy read = read_project(dir.file("p.sublift"));
  EXPECT_EQ(read.levels[0].edge_sharpness, h.levels[0].edge_sharpness);
  for (int l = 0; l <= 3; ++l) EXPECT_EQ(read.levels[std::size_t(l)].edge_dim, h.levels[std::size_t(l)].edge_dim) << "level " << l;
  EXPECT_EQ(synthesize(read, 3), fine);
  // A header naming an edge beyond the base, or a sharpness <= 0, is refused naming the entry.
  std::ifstream in(dir.file("p.sublift"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const std::size_t at = bytes.find("\"edges\":[[");
  ASSERT_NE(at, std::string::npos);
  std::string bad = bytes;
  bad.replace(at, 10, "\"edges\":[[9999999,1.0],[");
  const std::string why = testing::input_error([&] { read_project_from_memory("bad.sublift", bad); });
  EXPECT_NE(why.find("header 'sharpness' edges: [9999999, 1]"), std::string::npos) << why;
}

TEST(SemiSharp, ObjTagsRoundTripWithTheirSharpness) {
  testing::TempDir dir("sublift_semisharp_obj");
  const fx::Polygons m = fx::torus(8, 8);
  std::ofstream obj(dir.file("t.obj"));
  for (std::size_t v = 0; v < m.positions.size(); v += 3) obj << "v " << m.positions[v] << " " << m.positions[v + 1] << " " << m.positions[v + 2] << "\n";
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    obj << "f";
    for (std::uint32_t v : m.faces.row(f)) obj << " " << v + 1;
    obj << "\n";
  }
  obj << "t crease 2/1/0 0 1 3\nt crease 2/1/0 1 2 10\n";
  obj.close();
  const Shape s = read_shape(dir.file("t.obj"));
  ASSERT_EQ(s.base.edge_sharpness.size(), s.base.num_edges());
  const auto r = testing::run_cli({"subdivide", dir.file("t.obj"), "--scheme", "cubic", "--levels", "0", "-o", dir.file("back.obj")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir.file("back.obj"));
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("t crease 2/1/0 0 1 3"), std::string::npos) << text.substr(text.size() > 400 ? text.size() - 400 : 0);
  EXPECT_NE(text.find("t crease 2/1/0 1 2 10"), std::string::npos);
  // sqrt(2) keeps the tags sharp at every level (the old rule), as said.
  const Hierarchy sqrt2 = make_hierarchy(tagged_torus(1.0f, 1.0f), 2, Scheme::Sqrt2, 3);
  EXPECT_GT(creases(sqrt2.levels[2]), 0u);
}

// The torus of tagged_torus split into triangles (each quad along its 0-2 diagonal), the same
// ring tagged at `s`: the triangle schemes soften it as refine() does (1-to-4 splits give the
// halves of edge e the numbers 2e and 2e + 1 too), and their transforms stay exact.
Complex tagged_tri_torus(float s) {
  const fx::Polygons m = fx::torus(8, 8);
  Csr tris;
  for (std::size_t f = 0; f < m.faces.rows(); ++f) {
    const auto r = m.faces.row(f);
    fx::push_row(tris, {r[0], r[1], r[2]});
    fx::push_row(tris, {r[0], r[2], r[3]});
  }
  FeatureTags tags;
  for (std::uint32_t i = 0; i < 8; ++i) {
    tags.crease_edges.emplace_back(i, (i + 1) % 8);
    tags.crease_sharpness.push_back(s);
  }
  return complex_from_polygons(m.num_vertices, tris, tags);
}

TEST(SemiSharp, TriangleSchemesSoftenTooAndStayExact) {
  for (const Scheme scheme : {Scheme::LinearTri, Scheme::Butterfly, Scheme::Loop}) {
    SCOPED_TRACE(scheme_name(scheme));
    Hierarchy h = make_hierarchy(tagged_tri_torus(2.0f), 3, scheme, 3);
    EXPECT_EQ(creases(h.levels[0]), 8u);
    EXPECT_EQ(creases(h.levels[1]), 16u);
    EXPECT_EQ(creases(h.levels[2]), 0u);
    EXPECT_EQ(creases(h.levels[3]), 0u);
    EXPECT_LT(reconstruction_error(h, 5), 1e-12);
  }
}

}  // namespace
}  // namespace sublift
