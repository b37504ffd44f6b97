#include <gtest/gtest.h>

#include <cmath>

#include "core/complex/complex_build.h"

#include "core/base/errors.h"
#include "core/io/mesh/mesh_import.h"
#include "tests/test_util.h"

using namespace sublift;
using sublift::testing::find_warning;
using sublift::testing::load;
using sublift::testing::load_error;

namespace {
const std::string kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
}

TEST(ImportObj, ReadsVerticesAndPolygonsInFileOrder) {
  const LoadedMesh m = load("a.obj", "# c\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 2 0\n"
                                     "f 1 2 3 4\nf 4/1 3/2 5/3\n");
  ASSERT_EQ(m.mesh.num_vertices(), 5u);
  ASSERT_EQ(m.mesh.num_faces(), 2u);
  EXPECT_EQ(m.mesh.face_size(0), 4u);
  EXPECT_EQ(std::vector<std::uint32_t>(m.mesh.face(1).begin(), m.mesh.face(1).end()),
            (std::vector<std::uint32_t>{3, 2, 4}));
  EXPECT_EQ(m.mesh.positions[4], glm::dvec3(0.5, 2, 0));
  EXPECT_TRUE(m.report.empty());
}

TEST(ImportObj, AcceptsAllCornerFormsAndRelativeIndices) {
  const LoadedMesh m = load("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                                     "f 1/1/1 2//1 3/1\nv 1 1 0\nf -3 -1 -2\n");
  ASSERT_EQ(m.mesh.num_faces(), 2u);
  EXPECT_EQ(std::vector<std::uint32_t>(m.mesh.face(1).begin(), m.mesh.face(1).end()),
            (std::vector<std::uint32_t>{1, 3, 2}));
}

TEST(ImportObj, BomAndCrlfLoadIdenticallyToPlainLf) {
  const LoadedMesh plain = load("a.obj", kSquare);
  std::string crlf;
  for (char c : kSquare) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (const std::string& variant : {"\xEF\xBB\xBF" + kSquare, crlf, "\xEF\xBB\xBF" + crlf}) {
    const LoadedMesh m = load("a.obj", variant);
    EXPECT_EQ(m.mesh.positions, plain.mesh.positions);
    EXPECT_EQ(m.mesh.face_indices, plain.mesh.face_indices);
    EXPECT_TRUE(m.report.empty());
  }
}

TEST(ImportObj, KeepsIsolatedVerticesWithoutRenumbering) {
  const LoadedMesh m = load("a.obj", "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 2 3 4\n");
  ASSERT_EQ(m.mesh.num_vertices(), 4u);
  EXPECT_EQ(m.mesh.face_indices, (std::vector<std::uint32_t>{1, 2, 3}));
  const ImportWarning* w = find_warning(m.report, "used by no face");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->count, 1u);
  EXPECT_EQ(w->first_lines, std::vector<std::size_t>{1});
}

TEST(ImportObj, DropsBadFacesWithCountsAndLines) {
  const LoadedMesh m = load("a.obj",
                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"  // lines 1-4
                            "f 1 2 3\n"                              // 5 ok
                            "f 1 2 9\n"                              // 6 out of range
                            "f 0 1 2\n"                              // 7 zero index
                            "f -9 1 2\n"                             // 8 before first vertex
                            "f 1 2\n"                                // 9 two vertices
                            "f 1\n"                                  // 10 one vertex
                            "f 1 x 2\n"                              // 11 garbage
                            "f 2 4 4 3\n"                            // 12 consecutive repeat: repaired
                            "f 1 2 1 3\n"                            // 13 non-simple
                            "f 3 2 1\n");                            // 14 reverse duplicate of 5
  ASSERT_EQ(m.mesh.num_faces(), 2u);
  EXPECT_EQ(std::vector<std::uint32_t>(m.mesh.face(1).begin(), m.mesh.face(1).end()),
            (std::vector<std::uint32_t>{1, 3, 2}));
  const ImportWarning* range = find_warning(m.report, "out of range");
  ASSERT_NE(range, nullptr);
  EXPECT_EQ(range->count, 2u);
  EXPECT_EQ(range->first_lines, (std::vector<std::size_t>{6, 8}));
  EXPECT_EQ(find_warning(m.report, "unreadable or zero")->first_lines, (std::vector<std::size_t>{7, 11}));
  EXPECT_EQ(find_warning(m.report, "fewer than 3 vertices")->count, 2u);
  EXPECT_EQ(find_warning(m.report, "repaired")->first_lines, std::vector<std::size_t>{12});
  EXPECT_EQ(find_warning(m.report, "occurs twice")->first_lines, std::vector<std::size_t>{13});
  EXPECT_EQ(find_warning(m.report, "duplicate")->first_lines, std::vector<std::size_t>{14});
  const std::string text = m.report.format("a.obj");
  EXPECT_NE(text.find("a.obj: warning: 2 x face dropped: vertex index out of range (lines 6, 8)"),
            std::string::npos) << text;
}

TEST(ImportObj, UnreadableVertexLineKeepsNumberingAndDropsItsFaces) {
  const LoadedMesh m = load("a.obj", "v 0 0 0\nv 1 abc 0\nv 1 0 0\nv 0 1 0\nf 1 3 4\nf 1 2 3\n");
  ASSERT_EQ(m.mesh.num_vertices(), 4u);
  EXPECT_EQ(m.mesh.positions[2], glm::dvec3(1, 0, 0));  // not shifted down to index 1
  ASSERT_EQ(m.mesh.num_faces(), 1u);
  EXPECT_EQ(m.mesh.face_indices, (std::vector<std::uint32_t>{0, 2, 3}));
  EXPECT_EQ(find_warning(m.report, "unreadable vertex")->first_lines, std::vector<std::size_t>{2});
  EXPECT_EQ(find_warning(m.report, "unreadable vertex line")->count, 1u);
  EXPECT_EQ(find_warning(m.report, "uses an unreadable vertex")->first_lines, std::vector<std::size_t>{6});
}

TEST(ImportObj, RefusesNonFiniteAndHugeCoordinatesWithLine) {
  std::size_t line = 0;
  EXPECT_NE(load_error("a.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", &line).find("non-finite"), std::string::npos);
  EXPECT_EQ(line, 2u);
  EXPECT_NE(load_error("a.obj", "v 0 0 0\nv 0 1 0\nv 0 0 -inf\nf 1 2 3\n", &line).find("a.obj:3"), std::string::npos);
  EXPECT_NE(load_error("a.obj", "v 0 0 0\nv 0 1 0\nv 0 0 1e39\nf 1 2 3\n", &line).find("magnitude"), std::string::npos);
  EXPECT_EQ(line, 3u);
}

TEST(ImportObj, RefusesFilesWithoutFaces) {
  EXPECT_NE(load_error("e.obj", "").find("no vertices and no faces"), std::string::npos);
  EXPECT_NE(load_error("c.obj", "# only\n# comments\n").find("no vertices"), std::string::npos);
  EXPECT_NE(load_error("p.obj", "v 0 0 0\nv 1 0 0\n").find("2 vertices but no faces"), std::string::npos);
  // Every face dropped: the error lists why.
  const std::string e = load_error("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  EXPECT_NE(e.find("out of range (line 4)"), std::string::npos) << e;
}

TEST(ImportObj, RefusesBinaryGarbage) {
  std::string junk = "v 0 0 0\n";
  for (int i = 0; i < 64; ++i) junk += static_cast<char>((i * 37) & 0xff);
  std::size_t line = 0;
  EXPECT_NE(load_error("g.obj", junk, &line).find("binary data"), std::string::npos);
  EXPECT_EQ(line, 2u);
}

TEST(ImportObj, ReadsOpenSubdivTags) {
  const LoadedMesh m = load("t.obj", kSquare +
                                         "t crease 2/1/0 0 1 2.5\n"
                                         "t corner 1/1/0 3 10\n"
                                         "t interpolateboundary 1/0/0 1\n"
                                         "t crease 2/1/0 0 99 1\n"    // vertex out of range
                                         "t crease 2/1 0 1 1\n");     // malformed counts
  ASSERT_EQ(m.mesh.tags.size(), 3u);
  EXPECT_EQ(m.mesh.tags[0].name, "crease");
  EXPECT_EQ(m.mesh.tags[0].ints, (std::vector<std::int64_t>{0, 1}));
  EXPECT_EQ(m.mesh.tags[0].floats, std::vector<double>{2.5});
  EXPECT_EQ(m.mesh.tags[0].line, 6u);
  EXPECT_EQ(m.mesh.tags[1].name, "corner");
  EXPECT_EQ(find_warning(m.report, "names a vertex out of range")->first_lines, std::vector<std::size_t>{9});
  EXPECT_EQ(find_warning(m.report, "malformed")->first_lines, std::vector<std::size_t>{10});
}

// Issue 20: OpenSubdiv's semi-sharp creases (0 < sharpness < 10) keep their sharpness (10 and
// above: infinitely sharp); a fractional one is named once (the fraction is not blended), and
// every semi-sharp tag is named with which schemes honour it per level.
TEST(ImportObj, SemiSharpCreasesKeepTheirSharpness) {
  const LoadedMesh m = load("t.obj", kSquare + "t crease 2/1/0 0 1 2.5\nt crease 2/1/0 1 2 10\nt crease 2/1/0 2 3 0.5\nt corner 1/1/0 3 2\n");
  ImportReport report;
  const FeatureTags tags = feature_tags_from_obj(m.mesh.tags, report);
  ASSERT_EQ(tags.crease_edges.size(), 3u);
  EXPECT_EQ(tags.crease_sharpness, (std::vector<float>{2.5f, INFINITY, 0.5f}));
  EXPECT_EQ(tags.corner_sharpness, (std::vector<float>{2.0f}));
  const ImportWarning* fraction = find_warning(report, "fractional sharpness");
  ASSERT_NE(fraction, nullptr);
  EXPECT_EQ(fraction->first_lines, (std::vector<std::size_t>{6, 8}));
  const ImportWarning* per_level = find_warning(report, "semi-sharp crease tags: sharp for s levels (sqrt2: at every level)");
  ASSERT_NE(per_level, nullptr);
  EXPECT_EQ(per_level->count, 2u);  // 2.5 and 0.5 (10 is infinitely sharp)
  EXPECT_NE(find_warning(report, "semi-sharp corner tags: sharp for s levels"), nullptr);
}

TEST(ImportObj, ReportsIgnoredStatements) {
  const LoadedMesh m = load("a.obj", kSquare + "p 1\nfoo bar\ng grp\ns 1\nusemtl m\nl 1 2\n");
  EXPECT_EQ(find_warning(m.report, "point element ignored")->first_lines, std::vector<std::size_t>{6});
  EXPECT_EQ(find_warning(m.report, "unknown statement")->first_lines, std::vector<std::size_t>{7});
  EXPECT_EQ(m.report.warnings.size(), 2u);
  EXPECT_EQ(m.mesh.num_faces(), 1u);
  EXPECT_EQ(m.mesh.num_polylines(), 1u);  // `l` lines are kept as polylines (curves)
}

TEST(ImportObj, PolylinesWithoutFacesAreACurveNotAnError) {
  const LoadedMesh m = load("c.obj", "v 0 0 0\nv 1 0 0\nv 2 1 0\nl 1 2 3\n");
  EXPECT_EQ(m.mesh.num_faces(), 0u);
  ASSERT_EQ(m.mesh.num_polylines(), 1u);
  EXPECT_TRUE(m.report.empty());
  // Every polyline dropped: refused, naming why.
  const std::string e = load_error("d.obj", "v 0 0 0\nv 1 0 0\nl 1 5\n");
  EXPECT_NE(e.find("no usable face or polyline"), std::string::npos) << e;
  EXPECT_NE(e.find("out of range (line 3)"), std::string::npos) << e;
}

TEST(ImportObj, FileErrorsNameTheFile) {
  EXPECT_THROW(import_surface_mesh("/nonexistent/x.obj"), IoError);
  EXPECT_THROW(import_surface_mesh("/tmp"), Error);
  EXPECT_THROW(import_surface_mesh("mesh.stl"), InputError);
  try {
    import_surface_mesh("/nonexistent/x.obj");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.obj"), std::string::npos);
  }
}
