#include "core/fit/closest_point.h"

#include <algorithm>
#include <cmath>

namespace sublift {

namespace {

constexpr std::uint32_t kLeaf = 8;

double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
void closest_on_triangle(const double* p, const double* a, const double* b, const double* c, double* out) {
  double ab[3], ac[3], ap[3];
  for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = p[k] - a[k];
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto set = [&](double u, double v) {  // a + u ab + v ac
    for (int k = 0; k < 3; ++k) out[k] = a[k] + u * ab[k] + v * ac[k];
  };
  if (d1 <= 0 && d2 <= 0) return set(0, 0);
  double bp[3];
  for (int k = 0; k < 3; ++k) bp[k] = p[k] - b[k];
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return set(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return set(d1 / (d1 - d3), 0);
  double cp[3];
  for (int k = 0; k < 3; ++k) cp[k] = p[k] - c[k];
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return set(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return set(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return set(1 - w, w);
  }
  const double denom = 1 / (va + vb + vc);
  set(vb * denom, vc * denom);
}

double box_distance2(const double* lo, const double* hi, const double* p) {
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = p[k] < lo[k] ? lo[k] - p[k] : p[k] > hi[k] ? p[k] - hi[k] : 0.0;
    d += e * e;
  }
  return d;
}

}  // namespace

TriangleIndex::TriangleIndex(std::span<const double> positions, const Csr& faces) : p_(positions) {
  for (std::size_t f = 0; f < faces.rows(); ++f) {
    const auto q = faces.row(f);
    for (std::size_t k = 1; k + 1 < q.size(); ++k) tri_.insert(tri_.end(), {q[0], q[k], q[k + 1]});
  }
  const auto n = static_cast<std::uint32_t>(tri_.size() / 3);
  order_.resize(n);
  centre_.resize(3 * std::size_t(n));
  for (std::uint32_t t = 0; t < n; ++t) {
    order_[t] = t;
    for (int k = 0; k < 3; ++k)
      centre_[3 * std::size_t(t) + k] = (p_[3 * tri_[3 * t] + k] + p_[3 * tri_[3 * t + 1] + k] + p_[3 * tri_[3 * t + 2] + k]) / 3;
  }
  nodes_.reserve(2 * std::size_t(n / kLeaf + 1));
  nodes_.push_back({});
  if (n) build(0, 0, n);
}

void TriangleIndex::build(std::uint32_t node, std::uint32_t begin, std::uint32_t end) {
  Node nd{};
  for (int k = 0; k < 3; ++k) nd.lo[k] = HUGE_VAL, nd.hi[k] = -HUGE_VAL;
  for (std::uint32_t i = begin; i < end; ++i)
    for (int c = 0; c < 3; ++c) {
      const double* v = &p_[3 * std::size_t(tri_[3 * std::size_t(order_[i]) + c])];
      for (int k = 0; k < 3; ++k) nd.lo[k] = std::min(nd.lo[k], v[k]), nd.hi[k] = std::max(nd.hi[k], v[k]);
    }
  if (end - begin <= kLeaf) {
    nd.leaf = true, nd.first = begin, nd.count = end - begin;
    nodes_[node] = nd;
    return;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (nd.hi[k] - nd.lo[k] > nd.hi[axis] - nd.lo[axis]) axis = k;
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) { return centre_[3 * std::size_t(a) + axis] < centre_[3 * std::size_t(b) + axis]; });
  nd.leaf = false;
  nd.first = static_cast<std::uint32_t>(nodes_.size());
  nd.count = 0;
  nodes_.push_back({});
  nodes_.push_back({});
  nodes_[node] = nd;
  build(nd.first, begin, mid);
  build(nd.first + 1, mid, end);
}

TriangleIndex::Hit TriangleIndex::closest(const double p[3]) const {
  Hit best;
  double best2 = HUGE_VAL;
  std::uint32_t stack[128];
  int top = 0;
  if (!order_.empty()) stack[top++] = 0;
  while (top > 0) {
    const Node& nd = nodes_[stack[--top]];
    if (box_distance2(nd.lo, nd.hi, p) >= best2) continue;
    if (nd.leaf) {
      for (std::uint32_t i = nd.first; i < nd.first + nd.count; ++i) {
        const std::uint32_t t = order_[i];
        double q[3];
        closest_on_triangle(p, &p_[3 * std::size_t(tri_[3 * t])], &p_[3 * std::size_t(tri_[3 * t + 1])], &p_[3 * std::size_t(tri_[3 * t + 2])], q);
        const double d2 = (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]);
        if (d2 < best2) best2 = d2, best.triangle = t, std::copy(q, q + 3, best.point);
      }
      continue;
    }
    // Nearer child last, so it is taken first.
    const Node& a = nodes_[nd.first];
    const Node& b = nodes_[nd.first + 1];
    const bool a_first = box_distance2(a.lo, a.hi, p) <= box_distance2(b.lo, b.hi, p);
    if (top + 2 > 128) continue;  // depth is log2(n / 8): never near 64 levels
    stack[top++] = a_first ? nd.first + 1 : nd.first;
    stack[top++] = a_first ? nd.first : nd.first + 1;
  }
  best.distance = std::sqrt(best2);
  return best;
}

void TriangleIndex::normal(std::uint32_t t, double n[3]) const {
  const double* a = &p_[3 * std::size_t(tri_[3 * t])];
  const double* b = &p_[3 * std::size_t(tri_[3 * t + 1])];
  const double* c = &p_[3 * std::size_t(tri_[3 * t + 2])];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
  const double l = std::sqrt(dot(n, n));
  for (int k = 0; k < 3; ++k) n[k] = l > 0 ? n[k] / l : 0.0;
}

}  // namespace sublift
