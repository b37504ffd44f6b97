// Switching a session's scheme (core/edit/scheme_switch.h) in parts, as the modeler does on a
// worker thread: the copied input gives the hierarchy the switch's rule defines, progress
// rises from 0 to the end, and answering false cancels at any report with nothing changed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/complex/complex_build.h"
#include "core/complex/shapes.h"
#include "core/edit/scheme_switch.h"
#include "core/edit/session.h"
#include "core/multires/hierarchy.h"
#include "tests/test_shapes.h"

namespace sublift {
namespace {

// A cubic torus with detail: its finest net moved off the pure subdivision.
Session detailed_torus() {
  const SurfaceMesh m = make_quad_torus(10, 7);
  Hierarchy h = make_hierarchy(complex_from_surface_mesh(m), 3, Scheme::Cubic, 3);
  set_base(h, flatten_positions(m));
  std::vector<double> fine = synthesize(h, 3);
  const std::vector<double> r = testing::random_values(fine.size(), 11, -0.02, 0.02);
  for (std::size_t i = 0; i < fine.size(); ++i) fine[i] += r[i];
  analyze(h, fine);
  return Session(std::move(h));
}

TEST(SchemeSwitch, InPartsEqualsOneCallWithProgressAndCancel) {
  const Session s = detailed_torus();
  for (Scheme to : {Scheme::Linear, Scheme::Sqrt2}) {
    SCOPED_TRACE(scheme_name(to));
    // What a switch is (the header's rule), built here without progress: the new scheme's
    // levels from the base, then the shown finest net analysed (same refinement) or the
    // base's net set (sqrt(2): 2 levels per split).
    const Hierarchy& old = s.hierarchy();
    SchemeSwitch whole;
    whole.hierarchy = make_hierarchy(old.levels.front(), to == Scheme::Sqrt2 ? 6 : 3, to, 3);
    if (to == Scheme::Sqrt2) set_base(whole.hierarchy, s.positions(0));
    else analyze(whole.hierarchy, s.positions(3));
    EXPECT_EQ(switch_scheme(s, to).hierarchy.coeffs, whole.hierarchy.coeffs);
    const SchemeSwitchInput in = scheme_switch_input(s, to);
    std::vector<double> fractions;
    std::vector<std::string> stages;
    const SchemeSwitch parts = switch_scheme(in, [&](const char* stage, double f) {
      stages.push_back(stage);
      fractions.push_back(f);
      return true;
    });
    EXPECT_EQ(parts.kept_detail, to == Scheme::Linear);  // same refinement as cubic: detail kept
    ASSERT_EQ(parts.hierarchy.finest_level(), whole.hierarchy.finest_level());
    EXPECT_EQ(parts.hierarchy.finest_level(), to == Scheme::Sqrt2 ? 6 : 3);
    EXPECT_EQ(parts.hierarchy.coeffs, whole.hierarchy.coeffs);  // bit for bit
    // One report per level, then one for the last stage; rising from 0.
    ASSERT_EQ(fractions.size(), std::size_t(parts.hierarchy.finest_level()) + 1);
    EXPECT_EQ(fractions.front(), 0.0);
    for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_GE(fractions[i], fractions[i - 1]);
    EXPECT_EQ(fractions.back(), 0.95);
    EXPECT_EQ(stages.front(), "building the levels");
    EXPECT_EQ(stages.back(), to == Scheme::Linear ? "analysing the shape" : "setting the base");
    // Cancelled at every report in turn.
    for (std::size_t k = 0; k < fractions.size(); ++k) {
      std::size_t calls = 0;
      EXPECT_THROW(switch_scheme(in, [&](const char*, double) { return calls++ < k; }), Cancelled) << k;
      EXPECT_EQ(calls, k + 1);
    }
  }
  // A triangle scheme on quads is refused before anything is built, naming a face.
  try {
    (void)scheme_switch_input(s, Scheme::Loop);
    FAIL() << "quads accepted by Loop";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("face 0 has 4 corners"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sublift
