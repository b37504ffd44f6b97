// The up-front memory check (core/base/memory_budget.h, issue 18): the budget's sources and
// format, and hierarchies, sessions and fits refused before they are built.
#include <gtest/gtest.h>

#include <string>

#include "core/base/errors.h"
#include "core/base/memory_budget.h"
#include "core/complex/complex_build.h"
#include "core/edit/session.h"
#include "core/multires/hierarchy.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_util.h"

namespace sublift {
namespace {

// SUBLIFT_MEMORY_BUDGET for one scope.
struct BudgetScope : testing::ScopedEnv {
  explicit BudgetScope(const char* value) : ScopedEnv("SUBLIFT_MEMORY_BUDGET", value) {}
};

// Two unit quads side by side: level L of a 1-to-4 scheme has (2^(L+1) + 1)(2^L + 1) vertices.
Complex two_quads() {
  Csr f;
  f.offsets = {0};
  fixtures::push_row(f, {0, 1, 4, 3});
  fixtures::push_row(f, {1, 2, 5, 4});
  return complex_from_polygons(6, f);
}

using testing::error_text;

TEST(MemoryBudget, ReadsSizesWithUnits) {
  {
    BudgetScope b("6G");
    const MemoryBudget m = memory_budget();
    EXPECT_EQ(m.bytes, 6.0 * 1024 * 1024 * 1024);
    EXPECT_EQ(m.source, "SUBLIFT_MEMORY_BUDGET=6G");
  }
  {
    BudgetScope b("512M");
    EXPECT_EQ(memory_budget().bytes, 512.0 * 1024 * 1024);
  }
  {
    BudgetScope b("1.5GB");
    EXPECT_EQ(memory_budget().bytes, 1.5 * 1024 * 1024 * 1024);
  }
  {
    BudgetScope b("1000000");
    EXPECT_EQ(memory_budget().bytes, 1e6);
  }
  // Unset: the machine's available memory, more than nothing and less than a petabyte.
  const MemoryBudget m = memory_budget();
  EXPECT_GT(m.bytes, 1e6);
  EXPECT_LT(m.bytes, 1e15);
  EXPECT_NE(m.source.find("SUBLIFT_MEMORY_BUDGET"), std::string::npos) << "says how to choose: " << m.source;
}

TEST(MemoryBudget, RefusesMalformedSizesByName) {
  for (const char* bad : {"lots", "-5G", "6X", "0", "G"}) {
    BudgetScope b(bad);
    const std::string e = error_text([] { memory_budget(); });
    EXPECT_EQ(e, std::string("SUBLIFT_MEMORY_BUDGET must be a positive size such as 6G, 512M or 1000000 (bytes); got '") + bad + "'");
  }
}

TEST(MemoryBudget, FormatsBytes) {
  EXPECT_EQ(format_bytes(512), "512 bytes");
  EXPECT_EQ(format_bytes(1536), "1.5 KB");
  EXPECT_EQ(format_bytes(320.0 * 1024 * 1024), "320 MB");
  EXPECT_EQ(format_bytes(12.25 * 1024 * 1024 * 1024), "12 GB");
}

TEST(MemoryBudget, SmallWorkIsNeverChecked) {
  BudgetScope b("1000");  // smaller than anything
  EXPECT_NO_THROW(check_memory(kUncheckedBytes, "small work"));
  EXPECT_NO_THROW(make_hierarchy(two_quads(), 4, Scheme::Cubic, 3));
  EXPECT_EQ(error_text([] { check_memory(kUncheckedBytes + 1, "this"); }),
            "this needs about 64 MB, more than the memory budget of 1000 bytes (SUBLIFT_MEMORY_BUDGET=1000)");
}

TEST(MemoryBudget, TwelveLevelsOfTwoQuadsAreRefusedUpFront) {
  // 33,566,721 vertices at level 12 (issue 18: it climbed to 8 GB and died after 20 s).
  EXPECT_EQ(predicted_level_counts(two_quads(), 12, Scheme::Cubic).back(), 8193.0 * 4097.0);
  BudgetScope b("4G");
  const std::string e = error_text([] { make_hierarchy(two_quads(), 12, Scheme::Cubic, 3); });
  EXPECT_EQ(e, "subdividing to level 12 (33566721 vertices) needs about 13 GB, more than the memory budget of 4.0 GB "
               "(SUBLIFT_MEMORY_BUDGET=4G)");
}

TEST(MemoryBudget, ASessionRefusesTheLevelThatWouldNotFitAndStaysAsItWas) {
  Hierarchy h = make_hierarchy(two_quads(), 8, Scheme::Cubic, 3);
  Session s(std::move(h));
  BudgetScope b("100M");  // level 9: 525,825 vertices, about 200 MB
  const std::string e = error_text([&] { s.subdivide(); });
  EXPECT_EQ(e, "subdividing to level 9 (525825 vertices) needs about 201 MB, more than the memory budget of 100 MB "
               "(SUBLIFT_MEMORY_BUDGET=100M)");
  EXPECT_EQ(s.finest_level(), 8);
}

TEST(MemoryBudget, LatticesCostMorePerVertex) {
  const fixtures::Cells block = fixtures::hex_block(4);
  const Complex c = complex_from_cells(block.num_vertices, block.face_loops, block.cell_faces);
  const double v = predicted_level_counts(c, 4, Scheme::Cubic).back();
  EXPECT_EQ(v, 65.0 * 65.0 * 65.0);
  EXPECT_EQ(predicted_hierarchy_bytes(c, 4, Scheme::Cubic), v * scheme_info(Scheme::Cubic).peak_bytes[1]);
  EXPECT_GT(scheme_info(Scheme::Cubic).peak_bytes[1], scheme_info(Scheme::Cubic).peak_bytes[0]);
}

}  // namespace
}  // namespace sublift
