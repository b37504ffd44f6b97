#include "core/base/triangle_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/base/errors.h"
#include "core/base/parallel.h"
#include "core/base/points.h"

namespace sublift {

namespace {

// A ray counts as meeting a triangle when its barycentric coordinates are >= -kBaryTolerance:
// rays through a shared edge or vertex then meet at least one of the triangles despite
// rounding (sphere resampling merges the duplicates).
constexpr double kBaryTolerance = 1e-10;
// |det| below this times |e1| |e2| |dir|: the ray is parallel to the triangle's plane.
constexpr double kParallelTolerance = 1e-12;

// Moller-Trumbore: where origin + t * dir meets triangle `t`, the signed parameter into `th`
// (negative: behind the origin); false when it misses. Along -dir every step is this one negated,
// exactly, so its parameter is -th bit for bit.
template <class Tri>
bool ray_triangle_t(const Tri& t, const glm::dvec3& origin, const glm::dvec3& dir, double dir_len, double& th) {
  const glm::dvec3 p = glm::cross(dir, t.e2);
  const double det = glm::dot(t.e1, p);
  if (std::abs(det) <= kParallelTolerance * glm::length(t.e1) * glm::length(t.e2) * dir_len) return false;
  const double inv_det = 1.0 / det;
  const glm::dvec3 s = origin - t.p0;
  const double u = glm::dot(s, p) * inv_det;
  if (u < -kBaryTolerance || u > 1.0 + kBaryTolerance) return false;
  const glm::dvec3 q = glm::cross(s, t.e1);
  const double v = glm::dot(dir, q) * inv_det;
  if (v < -kBaryTolerance || u + v > 1.0 + kBaryTolerance) return false;
  th = glm::dot(t.e2, q) * inv_det;
  return true;
}

// The ray parameter t >= 0 where origin + t * dir meets triangle `t`, or -1.
template <class Tri>
double ray_triangle(const Tri& t, const glm::dvec3& origin, const glm::dvec3& dir, double dir_len) {
  double th = 0.0;
  if (!ray_triangle_t(t, origin, dir, dir_len, th)) return -1.0;
  return th < 0.0 ? -1.0 : th;
}

}  // namespace

// glm::dvec3 is three packed doubles.
TriangleBvh::TriangleBvh(const SurfaceMesh& mesh)
    : TriangleBvh(std::span<const double>(reinterpret_cast<const double*>(mesh.positions.data()),
                                          3 * mesh.num_vertices()),
                  Csr{mesh.face_offsets, mesh.face_indices}) {}

TriangleBvh::Tri TriangleBvh::make_tri(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, std::uint32_t face) {
  const glm::dvec3 e1 = b - a, e2 = c - a;
  return {a, e1, e2, face};
}

void TriangleBvh::grow(const Tri& t, glm::dvec3& lo, glm::dvec3& hi) {
  for (const glm::dvec3& q : {t.p0, t.p0 + t.e1, t.p0 + t.e2}) lo = glm::min(lo, q), hi = glm::max(hi, q);
}

std::uint32_t TriangleBvh::hint_up(std::uint32_t hint) const {
  return hint < face_tris_.rows() && face_tris_.size(hint) > 0 ? up_[face_tris_.row(hint)[0]] : kNoParent;
}

namespace {
// From this many triangles the root's halves are built on two threads (the build is a tenth of
// a fitting round's serial time); below it, one thread.
constexpr std::uint32_t kSideBySide = 1u << 15;
}  // namespace

TriangleBvh::TriangleBvh(std::span<const double> p, const Csr& faces) {
  // Each polygon's fan triangles at their place in polygon order, made in parallel chunks.
  const std::uint32_t nf = static_cast<std::uint32_t>(faces.rows());
  std::vector<std::size_t> first(std::size_t(nf) + 1, 0);
  for (std::uint32_t f = 0; f < nf; ++f) first[f + 1] = first[f] + (faces.size(f) >= 3 ? faces.size(f) - 2 : 0);
  if (first[nf] == 0) return;
  if (first[nf] > kMaxLeafFirst) throw Error("too many triangles for the triangle hierarchy");  // leaf references
  const std::uint32_t n = static_cast<std::uint32_t>(first[nf]);
  // Per triangle in polygon order: its corners, polygon and centre. Sized unzeroed: the loops
  // below touch them first, on both threads.
  UninitVector<std::uint32_t> corners(3 * std::size_t(n)), polygon(n);
  UninitVector<glm::dvec3> centers(n);
  num_vertices_ = p.size() / 3;
  // The bounds: each chunk's own, joined under a lock (min and max are exact in any order).
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
  std::mutex bounds;
  parallel_for(nf, 8192, [&](std::uint32_t b, std::uint32_t e) {
    glm::dvec3 clo(std::numeric_limits<double>::infinity()), chi = -clo;
    for (std::uint32_t f = b; f < e; ++f) {
      const auto c = faces.row(f);
      for (std::size_t i = 1; i + 1 < c.size(); ++i) {
        const std::size_t t = first[f] + i - 1;
        const Tri tri = make_tri(at(p, c[0]), at(p, c[i]), at(p, c[i + 1]), f);
        corners[3 * t] = c[0], corners[3 * t + 1] = c[i], corners[3 * t + 2] = c[i + 1];
        polygon[t] = f;
        centers[t] = tri.p0 + (tri.e1 + tri.e2) / 3.0;
        grow(tri, clo, chi);
      }
    }
    const std::lock_guard<std::mutex> g(bounds);
    lo = glm::min(lo, clo), hi = glm::max(hi, chi);
  });
  diagonal_ = glm::length(hi - lo);
  // Boxes grow by this much on every side, so that a ray grazing a box face (a triangle in an
  // axis plane) is not lost to rounding in the slab test.
  pad_ = 1e-9 * std::max(diagonal_, 1e-300);
  std::vector<std::uint32_t> order(n);
  for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
  nodes_.reserve(n / 2 + 1);
  std::uint32_t mid = 0;
  if (n < kSideBySide || parallel_threads() < 2 || !split(order, centers, 0, n, mid)) {
    root_ = build(nodes_, order, centers, p, corners, 0, n);
  } else {
    // The root's two halves built side by side, then laid out as one depth-first build would:
    // root, left subtree, right subtree (each half's node references moved to its place).
    std::vector<Node> halves[2];
    Built half[2];
    parallel_for(2, 1, [&](std::uint32_t b, std::uint32_t e) {
      for (std::uint32_t k = b; k < e; ++k) {
        halves[k].reserve(n / 4 + 1);
        half[k] = build(halves[k], order, centers, p, corners, k ? mid : 0, k ? n : mid);
      }
    });
    nodes_.emplace_back();
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t offset = static_cast<std::uint32_t>(nodes_.size());
      const auto moved = [&](std::uint32_t ref) { return is_leaf(ref) ? ref : ref + offset; };
      for (Node node : halves[k]) {
        node.child[0] = moved(node.child[0]);
        node.child[1] = moved(node.child[1]);
        nodes_.push_back(node);
      }
      half[k].ref = moved(half[k].ref);
      set_child(nodes_[0], k, half[k]);
    }
    root_ = {0, glm::min(half[0].lo, half[1].lo), glm::max(half[0].hi, half[1].hi)};
  }
  // Each node's and each triangle's place under its parent (index << 1 | side), for searches
  // that start at a leaf.
  up_.assign(n, kNoParent);
  for (std::uint32_t i = 0; i < nodes_.size(); ++i)
    for (std::uint32_t k = 0; k < 2; ++k) {
      const std::uint32_t ref = nodes_[i].child[k];
      if (!is_leaf(ref)) {
        nodes_[ref].parent = i << 1 | k;
        continue;
      }
      for (std::uint32_t t = leaf_first(ref); t < leaf_first(ref) + leaf_count(ref); ++t) up_[t] = i << 1 | k;
    }
  // The triangles in tree order, made again from their corners (the same arithmetic, the same
  // bits), and each one's polygon.
  tris_.resize(n);
  corners_.resize(3 * std::size_t(n));
  Csr tri_face;  // triangle -> its polygon
  tri_face.offsets.resize(std::size_t(n) + 1);
  tri_face.items.resize(n);
  parallel_for(n, 1u << 14, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t i = b; i < e; ++i) {
      const std::uint32_t* c = corners.data() + 3 * std::size_t(order[i]);
      tris_[i] = make_tri(at(p, c[0]), at(p, c[1]), at(p, c[2]), polygon[order[i]]);
      for (int k = 0; k < 3; ++k) corners_[3 * std::size_t(i) + k] = c[k];
      tri_face.items[i] = polygon[order[i]];
      tri_face.offsets[i + 1] = i + 1;
    }
  });
  face_tris_ = transpose(tri_face, polygon[n - 1] + 1);  // polygon is in polygon order
}

void TriangleBvh::refit(std::span<const double> p) {
  if (p.size() != 3 * num_vertices_) throw Error("TriangleBvh::refit: the positions are for another mesh");
  if (tris_.empty()) return;
  // The triangles as the constructor makes them, and their bounds.
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
  std::mutex bounds;
  parallel_for(static_cast<std::uint32_t>(tris_.size()), 8192, [&](std::uint32_t b, std::uint32_t e) {
    glm::dvec3 clo(std::numeric_limits<double>::infinity()), chi = -clo;
    for (std::uint32_t t = b; t < e; ++t) {
      const std::uint32_t* c = corners_.data() + 3 * std::size_t(t);
      tris_[t] = make_tri(at(p, c[0]), at(p, c[1]), at(p, c[2]), tris_[t].face);
      grow(tris_[t], clo, chi);
    }
    const std::lock_guard<std::mutex> g(bounds);
    lo = glm::min(lo, clo), hi = glm::max(hi, chi);
  });
  diagonal_ = glm::length(hi - lo);
  pad_ = 1e-9 * std::max(diagonal_, 1e-300);
  const auto leaf_box = [&](std::uint32_t ref) {
    Built b{ref, glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
    for (std::uint32_t i = leaf_first(ref); i < leaf_first(ref) + leaf_count(ref); ++i) grow(tris_[i], b.lo, b.hi);
    b.lo -= glm::dvec3(pad_);
    b.hi += glm::dvec3(pad_);
    return b;
  };
  // A node's box from its children's (rounded outwards, so still holding its triangles).
  const auto node_box = [&](std::uint32_t i) {
    const Node& n = nodes_[i];
    Built b{i, glm::dvec3(0.0), glm::dvec3(0.0)};
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(double(n.lo[0][a]), double(n.lo[1][a]));
      b.hi[a] = std::max(double(n.hi[0][a]), double(n.hi[1][a]));
    }
    return b;
  };
  // Children come after their parent (depth-first layout): from the last node back.
  for (std::uint32_t i = static_cast<std::uint32_t>(nodes_.size()); i-- > 0;)
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t ref = nodes_[i].child[k];
      set_child(nodes_[i], k, is_leaf(ref) ? leaf_box(ref) : node_box(ref));
    }
  root_ = is_leaf(root_.ref) ? leaf_box(root_.ref) : node_box(root_.ref);
}

bool TriangleBvh::split(std::vector<std::uint32_t>& order, std::span<const glm::dvec3> centers, std::uint32_t begin,
                        std::uint32_t end, std::uint32_t& mid) {
  glm::dvec3 clo(std::numeric_limits<double>::infinity()), chi = -clo;
  for (std::uint32_t i = begin; i < end; ++i) {
    clo = glm::min(clo, centers[order[i]]);
    chi = glm::max(chi, centers[order[i]]);
  }
  const glm::dvec3 extent = chi - clo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  if (end - begin <= kLeafSize) return false;
  mid = begin + (end - begin) / 2;
  if (extent[axis] <= 0.0) return true;  // centres all alike: any halves (a leaf holds at most 7)
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) { return centers[a][axis] < centers[b][axis]; });
  return true;
}

namespace {

// The float nearest x on the side of `down` (down: not above x; else not below): boxes rounded
// outwards still hold their triangles.
float rounded(double x, bool down) {
  float f = static_cast<float>(x);
  if (down ? double(f) > x : double(f) < x) f = std::nextafter(f, down ? -std::numeric_limits<float>::infinity()
                                                                      : std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

void TriangleBvh::set_child(Node& n, int k, const Built& b) {
  n.child[k] = b.ref;
  for (int a = 0; a < 3; ++a) {
    n.lo[k][a] = rounded(b.lo[a], true);
    n.hi[k][a] = rounded(b.hi[a], false);
  }
}

TriangleBvh::Built TriangleBvh::build(std::vector<Node>& nodes, std::vector<std::uint32_t>& order,
                                      std::span<const glm::dvec3> centers, std::span<const double> p,
                                      std::span<const std::uint32_t> corners, std::uint32_t begin, std::uint32_t end) const {
  std::uint32_t mid = 0;
  if (!split(order, centers, begin, end, mid)) {
    Built leaf;
    leaf.ref = kLeaf | (end - begin) << 28 | begin;
    leaf.lo = glm::dvec3(std::numeric_limits<double>::infinity());
    leaf.hi = -leaf.lo;
    for (std::uint32_t i = begin; i < end; ++i) {
      const std::uint32_t* c = corners.data() + 3 * std::size_t(order[i]);
      grow(make_tri(at(p, c[0]), at(p, c[1]), at(p, c[2]), 0), leaf.lo, leaf.hi);
    }
    leaf.lo -= glm::dvec3(pad_);
    leaf.hi += glm::dvec3(pad_);
    return leaf;
  }
  const std::uint32_t index = static_cast<std::uint32_t>(nodes.size());
  nodes.emplace_back();
  const Built left = build(nodes, order, centers, p, corners, begin, mid);
  const Built right = build(nodes, order, centers, p, corners, mid, end);
  set_child(nodes[index], 0, left);
  set_child(nodes[index], 1, right);
  // The children's padded boxes joined: the box of the triangles, padded (x - pad rounds
  // monotonically, so min(a - pad, b - pad) is min(a, b) - pad), without a pass over them.
  return {index, glm::min(left.lo, right.lo), glm::max(left.hi, right.hi)};
}

namespace {

// Whether the ray's parameter interval [tmin, tmax] meets a box.
template <class V>
bool ray_meets_box(const V& lo, const V& hi, const glm::dvec3& origin, const glm::dvec3& inv, double tmin, double tmax) {
  for (int k = 0; k < 3; ++k) {
    const double t1 = (double(lo[k]) - origin[k]) * inv[k], t2 = (double(hi[k]) - origin[k]) * inv[k];
    tmin = std::max(tmin, std::min(t1, t2));
    tmax = std::min(tmax, std::max(t1, t2));
  }
  return tmin <= tmax;
}

}  // namespace

template <class Limit, class Visit>
void TriangleBvh::walk_ray(const glm::dvec3& origin, const glm::dvec3& dir, Limit limit, Visit visit, std::uint32_t hint) const {
  if (tris_.empty()) return;
  // A zero component gets a huge finite inverse: the slab test then needs no special case.
  glm::dvec3 inv;
  for (int k = 0; k < 3; ++k) inv[k] = dir[k] == 0.0 ? 1e300 : 1.0 / dir[k];
  std::array<std::uint32_t, 128> stack;
  const auto descend = [&](std::uint32_t from) {
    std::size_t top = 0;
    stack[top++] = from;
    while (top > 0) {
      const std::uint32_t ref = stack[--top];
      if (is_leaf(ref)) {
        for (std::uint32_t i = leaf_first(ref); i < leaf_first(ref) + leaf_count(ref); ++i) visit(i);
        continue;
      }
      const Node& n = nodes_[ref];
      const auto [t0, t1] = limit();
      // The right child under the left, so the left is searched first.
      if (ray_meets_box(n.lo[1], n.hi[1], origin, inv, t0, t1)) stack[top++] = n.child[1];
      if (ray_meets_box(n.lo[0], n.hi[0], origin, inv, t0, t1)) stack[top++] = n.child[0];
    }
  };
  if (std::uint32_t up = hint_up(hint); up != kNoParent) {
    // From the hint's leaf up (as closest does): each sibling subtree the ray meets within the limit.
    descend(nodes_[up >> 1].child[up & 1]);
    while (up != kNoParent) {
      const Node& n = nodes_[up >> 1];
      const std::uint32_t other = 1 - (up & 1);
      const auto [t0, t1] = limit();
      if (ray_meets_box(n.lo[other], n.hi[other], origin, inv, t0, t1)) descend(n.child[other]);
      up = n.parent;
    }
    return;
  }
  const auto [t0, t1] = limit();
  if (ray_meets_box(root_.lo, root_.hi, origin, inv, t0, t1)) descend(root_.ref);
}

void TriangleBvh::all_hits(const glm::dvec3& origin, const glm::dvec3& dir, std::vector<double>& hits,
                           std::vector<std::uint32_t>* faces) const {
  const double dir_len = glm::length(dir);
  walk_ray(origin, dir, [] { return std::pair(0.0, std::numeric_limits<double>::infinity()); }, [&](std::uint32_t i) {
    const double th = ray_triangle(tris_[i], origin, dir, dir_len);
    if (th < 0.0) return;
    hits.push_back(th);
    if (faces) faces->push_back(tris_[i].face);
  });
}

double TriangleBvh::nearest_hit(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& facing, double t_max,
                                std::uint32_t hint) const {
  double best = std::numeric_limits<double>::infinity();
  const double dir_len = glm::length(dir);
  walk_ray(
      origin, dir, [&] { return std::pair(0.0, std::min(t_max, best)); },
      [&](std::uint32_t i) {
        const Tri& t = tris_[i];
        if (glm::dot(glm::cross(t.e1, t.e2), facing) <= 0.0) return;
        const double th = ray_triangle(t, origin, dir, dir_len);
        if (th >= 0.0 && th <= t_max && th < best) best = th;
      },
      hint);
  return best;
}

std::pair<double, double> TriangleBvh::nearest_hits(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& facing,
                                                   double t_max, std::uint32_t hint) const {
  double forward = std::numeric_limits<double>::infinity(), backward = forward;
  const double dir_len = glm::length(dir);
  walk_ray(
      origin, dir, [&] { return std::pair(-std::min(t_max, backward), std::min(t_max, forward)); },
      [&](std::uint32_t i) {
        const Tri& t = tris_[i];
        if (glm::dot(glm::cross(t.e1, t.e2), facing) <= 0.0) return;
        double th = 0.0;
        if (!ray_triangle_t(t, origin, dir, dir_len, th)) return;
        if (th >= 0.0 && th <= t_max && th < forward) forward = th;
        const double back = -th;  // nearest_hit along -dir meets it at exactly this
        if (back >= 0.0 && back <= t_max && back < backward) backward = back;
      },
      hint);
  return {forward, backward};
}

namespace {

// The closest point of triangle (a, a + e1, a + e2) to p (Ericson, Real-Time Collision
// Detection, 5.1.5: by the Voronoi region of p).
glm::dvec3 closest_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& ab, const glm::dvec3& ac) {
  const glm::dvec3 ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const glm::dvec3 bp = ap - ab;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return a + ab;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = ap - ac;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return a + ac;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return a + ab + (ac - ab) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Written out (glm's version was not inlined: a call per box, a seventh of a fit's time).
template <class V>
inline double box_distance2(const V& lo, const V& hi, const glm::dvec3& p) {
  const double dx = std::max(std::max(double(lo[0]) - p.x, p.x - double(hi[0])), 0.0);
  const double dy = std::max(std::max(double(lo[1]) - p.y, p.y - double(hi[1])), 0.0);
  const double dz = std::max(std::max(double(lo[2]) - p.z, p.z - double(hi[2])), 0.0);
  return (dx * dx + dy * dy) + dz * dz;
}

}  // namespace

TriangleBvh::Closest TriangleBvh::closest(const glm::dvec3& p) const { return closest(p, nullptr, UINT32_MAX); }

TriangleBvh::Closest TriangleBvh::closest(const glm::dvec3& p, const glm::dvec3& facing) const { return closest(p, &facing, UINT32_MAX); }

TriangleBvh::Closest TriangleBvh::closest(const glm::dvec3& p, const glm::dvec3* facing, std::uint32_t hint) const {
  Closest best;
  double best2 = std::numeric_limits<double>::infinity();
  const auto consider = [&](std::uint32_t i) {
    if (facing && glm::dot(glm::cross(tris_[i].e1, tris_[i].e2), *facing) <= 0.0) return;
    const glm::dvec3 q = closest_on_triangle(p, tris_[i].p0, tris_[i].e1, tris_[i].e2);
    const double d2 = glm::dot(q - p, q - p);
    // Of equally near triangles the lowest polygon wins, so the answer does not depend on the
    // order of the search (nor on a hint).
    if (d2 < best2 || (d2 == best2 && tris_[i].face < best.face)) best2 = d2, best.point = q, best.face = tris_[i].face;
  };
  // Each entry keeps its box's distance, measured when its parent was opened.
  struct Entry {
    std::uint32_t ref;
    double d2;
  };
  std::array<Entry, 128> stack;
  const auto descend = [&](Entry from) {
    std::size_t top = 0;
    stack[top++] = from;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.d2 > best2) continue;  // (a box just as near may hold a lower polygon)
      if (is_leaf(e.ref)) {
        for (std::uint32_t i = leaf_first(e.ref); i < leaf_first(e.ref) + leaf_count(e.ref); ++i) consider(i);
        continue;
      }
      const Node& n = nodes_[e.ref];
      const Entry l{n.child[0], box_distance2(n.lo[0], n.hi[0], p)};
      const Entry r{n.child[1], box_distance2(n.lo[1], n.hi[1], p)};
      // The nearer child last, so it is searched first; a child already beyond the best is not kept.
      const bool left_first = l.d2 <= r.d2;
      const Entry& near = left_first ? l : r;
      const Entry& far = left_first ? r : l;
      if (far.d2 <= best2) stack[top++] = far;
      if (near.d2 <= best2) stack[top++] = near;
    }
  };
  if (tris_.empty()) {
  } else if (std::uint32_t up = hint_up(hint); up != kNoParent) {
    // From the hint's leaf up to the root: its triangles first (the hint's among them), then at
    // each node on the way the other child's subtree unless its box lies beyond the best (every
    // triangle is searched or pruned once, as from the root; the walk down to the hint is saved).
    descend({nodes_[up >> 1].child[up & 1], 0.0});
    while (up != kNoParent) {
      const Node& n = nodes_[up >> 1];
      const std::uint32_t other = 1 - (up & 1);
      const double d2 = box_distance2(n.lo[other], n.hi[other], p);
      if (d2 <= best2) descend({n.child[other], d2});
      up = n.parent;
    }
  } else {
    descend({root_.ref, box_distance2(root_.lo, root_.hi, p)});
  }
  best.distance = std::sqrt(best2);
  return best;
}

}  // namespace sublift
