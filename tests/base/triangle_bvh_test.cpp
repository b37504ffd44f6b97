// The triangle BVH's queries (core/base/triangle_bvh.h) against brute force over every triangle
// with other algorithms: the closest point by projection onto the plane, else the nearest of
// the three edges (the BVH uses Ericson's Voronoi regions); ray hits by the plane's parameter
// and a barycentric inside test (the BVH uses Moller-Trumbore).
#include "core/base/triangle_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/geometric.hpp>

#include "core/base/errors.h"
#include "core/base/parallel.h"

namespace sublift {
namespace {

struct Soup {
  std::vector<double> xyz;
  Csr faces;  // triangles, and every 5th face a quad (two fan triangles)
};

glm::dvec3 at(const Soup& s, std::uint32_t v) { return {s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]}; }

Soup soup(int faces, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), d(-0.15, 0.15);
  Soup s;
  std::uint32_t n = 0;
  for (int f = 0; f < faces; ++f) {
    const glm::dvec3 c(u(rng), u(rng), u(rng));
    const int corners = f % 5 == 4 ? 4 : 3;
    if (corners == 4) {  // a planar convex quad
      const glm::dvec3 a(d(rng), d(rng), d(rng)), b(d(rng), d(rng), d(rng));
      for (const glm::dvec3& p : {c - a - b, c + a - b, c + a + b, c - a + b}) s.xyz.insert(s.xyz.end(), {p.x, p.y, p.z});
    } else {
      for (int k = 0; k < 3; ++k) s.xyz.insert(s.xyz.end(), {c.x + d(rng), c.y + d(rng), c.z + d(rng)});
    }
    for (int k = 0; k < corners; ++k) s.faces.items.push_back(n++);
    s.faces.offsets.push_back(static_cast<std::uint32_t>(s.faces.items.size()));
  }
  return s;
}

glm::dvec3 on_segment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 e = b - a;
  return a + std::clamp(glm::dot(p - a, e) / glm::dot(e, e), 0.0, 1.0) * e;
}

// Barycentric coordinates (v, w) of q in the plane of (a, b, c): q = a + v (b - a) + w (c - a).
bool inside(const glm::dvec3& q, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, r = q - a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2), d1 = glm::dot(r, e1), d2 = glm::dot(r, e2);
  const double det = d11 * d22 - d12 * d12, v = (d22 * d1 - d12 * d2) / det, w = (d11 * d2 - d12 * d1) / det;
  return v >= 0 && w >= 0 && v + w <= 1;
}

glm::dvec3 closest_brute(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  const glm::dvec3 q = p - glm::dot(p - a, n) * n;
  if (inside(q, a, b, c)) return q;
  glm::dvec3 best = on_segment(p, a, b);
  for (const glm::dvec3& x : {on_segment(p, b, c), on_segment(p, c, a)})
    if (glm::distance(x, p) < glm::distance(best, p)) best = x;
  return best;
}

// Every fan triangle of the soup as (a, b, c, face).
template <class F>
void for_each_triangle(const Soup& s, F&& f) {
  for (std::uint32_t g = 0; g < s.faces.rows(); ++g) {
    const auto r = s.faces.row(g);
    for (std::size_t k = 1; k + 1 < r.size(); ++k) f(at(s, r[0]), at(s, r[k]), at(s, r[k + 1]), g);
  }
}

TEST(TriangleBvh, ClosestPointsAgreeWithBruteForce) {
  const Soup s = soup(300, 1);
  const TriangleBvh bvh(s.xyz, s.faces);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.3, 1.3);
  for (int q = 0; q < 300; ++q) {
    const glm::dvec3 p(u(rng), u(rng), u(rng)), facing(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    double best = std::numeric_limits<double>::infinity(), best_facing = best;
    std::uint32_t face = UINT32_MAX;
    for_each_triangle(s, [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, std::uint32_t g) {
      const double d = glm::distance(closest_brute(p, a, b, c), p);
      if (d < best) best = d, face = g;
      if (glm::dot(glm::cross(b - a, c - a), facing) > 0) best_facing = std::min(best_facing, d);
    });
    const TriangleBvh::Closest c = bvh.closest(p);
    EXPECT_NEAR(c.distance, best, 1e-12);
    EXPECT_NEAR(glm::distance(c.point, p), c.distance, 1e-12);
    EXPECT_EQ(c.face, face);  // the polygon, also for a quad's second triangle
    EXPECT_NEAR(bvh.closest(p, facing).distance, best_facing, 1e-12);
    // A hint (here any polygon: the nearest, a random one, none at all) only starts the search.
    for (const std::uint32_t hint : {face, static_cast<std::uint32_t>(rng() % s.faces.rows()), UINT32_MAX, 1u << 30}) {
      const TriangleBvh::Closest h = bvh.closest(p, nullptr, hint);
      EXPECT_EQ(h.distance, c.distance) << hint;  // the same answer, bit for bit
      EXPECT_EQ(h.face, c.face);
      EXPECT_EQ(h.point, c.point);
      const TriangleBvh::Closest hf = bvh.closest(p, &facing, hint), f = bvh.closest(p, facing);
      EXPECT_EQ(hf.distance, f.distance) << hint;
      EXPECT_EQ(hf.face, f.face);
    }
  }
}

// Large meshes build the root's two halves on two threads; the hierarchy is laid out as the
// one-thread build lays it: the same answers, and every ray's hits in the same order (which
// follows the node layout), bit for bit; closest points also against brute force.
TEST(TriangleBvh, BuiltOnTwoThreadsAsOnOne) {
  const Soup s = soup(40000, 5);  // 48,000 triangles: above the side-by-side size
  const int threads = parallel_threads();
  set_parallel_threads(1);
  const TriangleBvh one(s.xyz, s.faces);
  set_parallel_threads(2);
  const TriangleBvh two(s.xyz, s.faces);
  set_parallel_threads(threads);
  ASSERT_EQ(one.num_triangles(), 48000u);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-0.3, 1.3);
  std::vector<double> h1, h2;
  std::vector<std::uint32_t> f1, f2;
  for (int q = 0; q < 400; ++q) {
    const glm::dvec3 p(u(rng), u(rng), u(rng)), dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    const TriangleBvh::Closest a = one.closest(p), b = two.closest(p);
    EXPECT_EQ(a.distance, b.distance);
    EXPECT_EQ(a.face, b.face);
    EXPECT_EQ(a.point, b.point);
    // Searched up from a hint's leaf (in either half of the side-by-side build): the same answer.
    const TriangleBvh::Closest c = two.closest(p, nullptr, static_cast<std::uint32_t>(rng() % s.faces.rows()));
    EXPECT_EQ(c.distance, a.distance);
    EXPECT_EQ(c.face, a.face);
    EXPECT_EQ(one.nearest_hit(p, dir, -dir, 10.0), two.nearest_hit(p, dir, -dir, 10.0));
    h1.clear(), h2.clear(), f1.clear(), f2.clear();
    one.all_hits(p, dir, h1, &f1);
    two.all_hits(p, dir, h2, &f2);
    EXPECT_EQ(h1, h2) << "the hits come in another order: the node layout differs";
    EXPECT_EQ(f1, f2);
    if (q % 20 == 0) {
      double best = std::numeric_limits<double>::infinity();
      for_each_triangle(s, [&](const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z, std::uint32_t) {
        best = std::min(best, glm::distance(closest_brute(p, x, y, z), p));
      });
      EXPECT_NEAR(b.distance, best, 1e-12);
    }
  }
}

TEST(TriangleBvh, RayHitsAgreeWithBruteForce) {
  const Soup s = soup(300, 3);
  const TriangleBvh bvh(s.xyz, s.faces);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0), w(-1.0, 1.0);
  int hit_rays = 0, both_ways = 0;
  for (int q = 0; q < 300; ++q) {
    const glm::dvec3 o(u(rng), u(rng), u(rng)), dir(w(rng), w(rng), w(rng)), facing(w(rng), w(rng), w(rng));
    std::vector<double> expected;
    double nearest_facing = std::numeric_limits<double>::infinity();
    for_each_triangle(s, [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, std::uint32_t) {
      const glm::dvec3 n = glm::cross(b - a, c - a);
      const double den = glm::dot(n, dir);
      if (std::abs(den) < 1e-9) return;
      const double t = glm::dot(n, a - o) / den;
      if (t < 0 || !inside(o + t * dir, a, b, c)) return;
      expected.push_back(t);
      if (glm::dot(n, facing) > 0) nearest_facing = std::min(nearest_facing, t);
    });
    std::vector<double> hits;
    std::vector<std::uint32_t> faces;
    bvh.all_hits(o, dir, hits, &faces);
    ASSERT_EQ(hits.size(), faces.size());
    std::sort(hits.begin(), hits.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(hits.size(), expected.size()) << "ray " << q;
    for (std::size_t k = 0; k < hits.size(); ++k) EXPECT_NEAR(hits[k], expected[k], 1e-9);
    hit_rays += !hits.empty();
    const double nh = bvh.nearest_hit(o, dir, facing, 1e30);
    // From a hint's leaf up (the closest polygon, a random one, none): the same answer, bit for
    // bit, with and without a bound.
    for (const std::uint32_t hint : {bvh.closest(o).face, static_cast<std::uint32_t>(rng() % s.faces.rows()), UINT32_MAX}) {
      EXPECT_EQ(bvh.nearest_hit(o, dir, facing, 1e30, hint), nh) << hint;
      const double bound = std::isfinite(nh) ? 1.5 * nh : 0.7;
      EXPECT_EQ(bvh.nearest_hit(o, dir, facing, bound, hint), bvh.nearest_hit(o, dir, facing, bound)) << hint;
      // Both ways in one walk: each side bit for bit its own call's, bounded or not.
      for (const double t_max : {1e30, bound}) {
        const auto [forward, backward] = bvh.nearest_hits(o, dir, facing, t_max, hint);
        EXPECT_EQ(forward, bvh.nearest_hit(o, dir, facing, t_max)) << hint;
        EXPECT_EQ(backward, bvh.nearest_hit(o, -dir, facing, t_max)) << hint;
        both_ways += std::isfinite(forward) && std::isfinite(backward);
      }
    }
    if (!std::isfinite(nearest_facing)) {
      EXPECT_TRUE(std::isinf(nh)) << nh;
    } else {
      EXPECT_NEAR(nh, nearest_facing, 1e-9);
      // A bound below the nearest hit finds nothing; one above it finds the same hit.
      EXPECT_TRUE(std::isinf(bvh.nearest_hit(o, dir, facing, 0.5 * nearest_facing)));
      EXPECT_NEAR(bvh.nearest_hit(o, dir, facing, 1.5 * nearest_facing), nearest_facing, 1e-9);
    }
  }
  EXPECT_GT(hit_rays, 100);  // the soup is dense enough that most rays meet something
  EXPECT_GT(both_ways, 100);  // and often on both sides
}


// Ties: above a grid vertex every face around it is as near. The lowest numbered one is named,
// however the search went and whichever face it was told to start from.
TEST(TriangleBvh, EquallyNearFacesNameTheLowest) {
  Soup s;
  const int n = 12;  // n x n squares, two triangles each, over the unit square
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s.xyz.insert(s.xyz.end(), {double(i) / n, double(j) / n, 0.0});
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (const auto& tri : {std::array{id(i, j), id(i + 1, j), id(i + 1, j + 1)}, std::array{id(i, j), id(i + 1, j + 1), id(i, j + 1)}}) {
        s.faces.items.insert(s.faces.items.end(), tri.begin(), tri.end());
        s.faces.offsets.push_back(static_cast<std::uint32_t>(s.faces.items.size()));
      }
  const TriangleBvh bvh(s.xyz, s.faces);
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) {
      const glm::dvec3 p(double(i) / n, double(j) / n, 0.25);
      // Six triangles meet at the vertex; the lowest is the first of the square below-left.
      const std::uint32_t lowest = static_cast<std::uint32_t>(2 * ((i - 1) + n * (j - 1)));
      EXPECT_EQ(bvh.closest(p).face, lowest);
      for (std::uint32_t hint = 0; hint < s.faces.rows(); hint += 7) EXPECT_EQ(bvh.closest(p, nullptr, hint).face, lowest) << hint;
      const glm::dvec3 up(0, 0, 1);
      EXPECT_EQ(bvh.closest(p, &up, 2 * (i + n * j)).face, lowest);
    }
}

// Triangles whose centres coincide (here twelve copies of one, more than a leaf's count field
// holds) are all still found: by a ray, by a closest-point query from the root and from each hint.
TEST(TriangleBvh, TrianglesWithOneCentreAreAllKept) {
  Soup s;
  s.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (std::uint32_t f = 0; f < 12; ++f) {
    s.faces.items.insert(s.faces.items.end(), {0, 1, 2});
    s.faces.offsets.push_back(static_cast<std::uint32_t>(s.faces.items.size()));
  }
  // Beside them a few others, so the copies are a subtree, not the whole tree.
  for (int k = 0; k < 5; ++k) {
    const std::uint32_t v = static_cast<std::uint32_t>(s.xyz.size() / 3);
    s.xyz.insert(s.xyz.end(), {3.0 + k, 0, 0, 4.0 + k, 0, 0, 3.0 + k, 1, 0});
    s.faces.items.insert(s.faces.items.end(), {v, v + 1, v + 2});
    s.faces.offsets.push_back(static_cast<std::uint32_t>(s.faces.items.size()));
  }
  const TriangleBvh bvh(s.xyz, s.faces);
  std::vector<double> hits;
  std::vector<std::uint32_t> faces;
  bvh.all_hits({0.25, 0.25, 1.0}, {0, 0, -1}, hits, &faces);
  std::sort(faces.begin(), faces.end());
  std::vector<std::uint32_t> copies(12);
  for (std::uint32_t f = 0; f < 12; ++f) copies[f] = f;
  EXPECT_EQ(faces, copies);
  const glm::dvec3 p(0.25, 0.25, 0.5);
  EXPECT_EQ(bvh.closest(p).face, 0u);
  for (std::uint32_t hint = 0; hint < s.faces.rows(); ++hint) EXPECT_EQ(bvh.closest(p, nullptr, hint).face, 0u) << hint;
}

// A refitted hierarchy answers closest-point queries exactly as one built on the moved points
// (any side and one side, from the root and from hints), and a ray meets the same triangles:
// small moves (a fitting round's) and large ones (every vertex anywhere, so the kept tree fits
// badly), on both builds (one thread, and the halves side by side).
TEST(TriangleBvh, RefitAnswersAsAFreshBuild) {
  const int threads = parallel_threads();
  // (The side-by-side build only with small moves: after large ones every query opens most of it.)
  for (const auto& [faces, large] : {std::pair{300, false}, {300, true}, {40000, false}}) {
    const Soup s = soup(faces, 8);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-0.3, 1.3), small(-0.01, 0.01);
    {
      SCOPED_TRACE(std::to_string(faces) + (large ? " faces, large moves" : " faces, small moves"));
      Soup moved = s;
      for (double& x : moved.xyz) x = large ? u(rng) : x + small(rng);
      set_parallel_threads(faces > 1000 ? 2 : 1);
      TriangleBvh refitted(s.xyz, s.faces);
      set_parallel_threads(threads);
      refitted.refit(moved.xyz);
      const TriangleBvh fresh(moved.xyz, moved.faces);
      EXPECT_EQ(refitted.diagonal(), fresh.diagonal());
      std::vector<double> h1, h2;
      for (int q = 0; q < 300; ++q) {
        const glm::dvec3 p(u(rng), u(rng), u(rng)), facing(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        const std::uint32_t hint = static_cast<std::uint32_t>(rng() % s.faces.rows());
        for (const glm::dvec3* side : {static_cast<const glm::dvec3*>(nullptr), &facing})
          for (const std::uint32_t from : {UINT32_MAX, hint}) {
            const TriangleBvh::Closest a = refitted.closest(p, side, from), b = fresh.closest(p, side, from);
            ASSERT_EQ(a.distance, b.distance) << q;
            ASSERT_EQ(a.face, b.face) << q;
            ASSERT_EQ(a.point, b.point) << q;
          }
        const glm::dvec3 dir = facing;
        EXPECT_EQ(refitted.nearest_hit(p, dir, -dir, 10.0), fresh.nearest_hit(p, dir, -dir, 10.0));
        h1.clear(), h2.clear();
        refitted.all_hits(p, dir, h1);
        fresh.all_hits(p, dir, h2);
        std::sort(h1.begin(), h1.end());
        std::sort(h2.begin(), h2.end());
        EXPECT_EQ(h1, h2);
      }
    }
  }
  TriangleBvh bvh(std::vector<double>(9, 0.0), Csr{{0, 3}, {0, 1, 2}});
  EXPECT_THROW(bvh.refit(std::vector<double>(6, 0.0)), Error);
}

}  // namespace
}  // namespace sublift
