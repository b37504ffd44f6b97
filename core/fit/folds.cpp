#include "core/fit/folds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <Eigen/Dense>
#include <glm/geometric.hpp>

#include "core/base/parallel.h"
#include "core/base/points.h"
#include "core/complex/polygon_normal.h"

namespace sublift {

namespace {

// Whether any face of v's star is turned against the input.
bool star_turned(const Complex& c, std::uint32_t v, std::span<const double> x, const std::vector<glm::dvec3>& facing) {
  for (std::uint32_t f : c.vertex_faces.row(v))
    if (turned(c.faces, f, x, facing[f])) return true;
  return false;
}

// The least of v's faces' areas along the input's way there (negative: a face is folded).
double star_score(const Complex& c, std::uint32_t v, std::span<const double> x, const std::vector<glm::dvec3>& facing) {
  double worst = INFINITY;
  for (std::uint32_t f : c.vertex_faces.row(v)) {
    double a[3] = {0, 0, 0};
    polygon_area_vector(c.faces.row(f), x.data(), a);
    const double l = glm::length(facing[f]);
    worst = std::min(worst, l > 0 ? (a[0] * facing[f].x + a[1] * facing[f].y + a[2] * facing[f].z) / l : 0.0);
  }
  return worst;
}

// A point where every face of v's star faces its way: the centroid of the star's kernel (the
// half-planes left of each face's edge opposite v, in the plane across v square to the faces'
// mean facing), or none when the kernel is empty (no position of v alone unfolds its faces).
std::optional<glm::dvec3> star_kernel_point(const Complex& c, std::uint32_t v, std::span<const double> x,
                                            const std::vector<glm::dvec3>& facing) {
  glm::dvec3 n(0.0);
  for (std::uint32_t f : c.vertex_faces.row(v))
    if (glm::dot(facing[f], facing[f]) > 0) n += glm::normalize(facing[f]);
  if (!(glm::dot(n, n) > 0)) return std::nullopt;
  n = glm::normalize(n);
  const glm::dvec3 e1 = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0)) : glm::cross(n, glm::dvec3(0, 1, 0)));
  const glm::dvec3 e2 = glm::cross(n, e1), o = at(x, v);
  using P2 = std::array<double, 2>;
  const auto flat = [&](std::uint32_t w) {
    const glm::dvec3 d = at(x, w) - o;
    return P2{glm::dot(d, e1), glm::dot(d, e2)};
  };
  double size = 0;
  for (std::uint32_t e : c.vertex_edges.row(v))
    size = std::max(size, glm::distance(o, at(x, edge_other_end(c, e, v))));
  if (!(size > 0)) return std::nullopt;
  std::vector<P2> poly = {P2{-4 * size, -4 * size}, P2{4 * size, -4 * size}, P2{4 * size, 4 * size}, P2{-4 * size, 4 * size}}, next;
  for (std::uint32_t f : c.vertex_faces.row(v)) {
    std::uint32_t slot = c.faces.offsets[f];
    while (c.faces.items[slot] != v) ++slot;
    const P2 a = flat(c.faces.items[face_next_slot(c, f, slot)]), b = flat(c.faces.items[face_prev_slot(c, f, slot)]);
    // Left of a -> b, by a margin of a thousandth of the star's size (a point on the line folds flat).
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    const auto side = [&](const P2& p) { return ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / len - 1e-3 * size; };
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const P2 &p = poly[i], &q = poly[(i + 1) % poly.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) next.push_back(p);
      if ((sp >= 0) != (sq >= 0)) {
        const double t = sp / (sp - sq);
        next.push_back(P2{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
      }
    }
    poly.swap(next);
    if (poly.size() < 3 || !(len > 0)) return std::nullopt;
  }
  double area = 0, cx = 0, cy = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2 &p = poly[i], &q = poly[(i + 1) % poly.size()];
    const double w = p[0] * q[1] - q[0] * p[1];
    area += w, cx += (p[0] + q[0]) * w, cy += (p[1] + q[1]) * w;
  }
  if (!(area > 1e-12 * size * size)) return std::nullopt;
  return o + (cx / (3 * area)) * e1 + (cy / (3 * area)) * e2;
}

}  // namespace

bool turned(const Csr& faces, std::size_t f, std::span<const double> x, const glm::dvec3& facing) {
  double a[3] = {0, 0, 0};
  polygon_area_vector(faces.row(f), x.data(), a);
  return a[0] * facing.x + a[1] * facing.y + a[2] * facing.z <= 0.0;
}

std::vector<std::uint8_t> turned_faces(const Csr& faces, std::span<const double> x, const std::vector<glm::dvec3>& facing) {
  std::vector<std::uint8_t> out(faces.rows());
  parallel_for(static_cast<std::uint32_t>(faces.rows()), 4096, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t f = b; f < e; ++f) out[f] = turned(faces, f, x, facing[f]);
  });
  return out;
}

std::size_t count_turned(const Csr& faces, std::span<const double> x, const std::vector<glm::dvec3>& facing) {
  const std::vector<std::uint8_t> t = turned_faces(faces, x, facing);
  return static_cast<std::size_t>(std::count(t.begin(), t.end(), std::uint8_t(1)));
}

void keep_unfolded(const Csr& faces, const std::vector<glm::dvec3>& facing, std::span<const double> before, std::vector<double>& after) {
  const std::vector<std::uint8_t> was_folded = turned_faces(faces, before, facing);
  // Most calls fold nothing new: then the walk below would change nothing (checked in parallel).
  {
    const std::vector<std::uint8_t> now = turned_faces(faces, after, facing);
    bool any = false;
    for (std::size_t f = 0; f < faces.rows() && !any; ++f) any = now[f] && !was_folded[f];
    if (!any) return;
  }
  for (int round = 0;; ++round) {
    bool again = false;
    for (std::size_t f = 0; f < faces.rows(); ++f) {
      if (was_folded[f] || !turned(faces, f, after, facing[f])) continue;
      for (std::uint32_t v : faces.row(f))
        for (int k = 0; k < 3; ++k) {
          double& y = after[3 * std::size_t(v) + k];
          const double b = before[3 * std::size_t(v) + k];
          again |= y != b;
          y = round < 4 ? 0.5 * (y + b) : b;
        }
    }
    if (!again) break;
  }
}

void untangle(const Complex& c, const ProjectFn& project, const FeatureLines& lines, const std::vector<glm::dvec3>& facing,
              std::vector<double>& x, int rounds) {
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::uint32_t> moving;
    const std::vector<std::uint8_t> folded = turned_faces(c.faces, x, facing);
    for (std::size_t f = 0; f < c.faces.rows(); ++f)
      if (folded[f])
        for (std::uint32_t v : c.faces.row(f))
          if (c.vertex_dim.empty() || c.vertex_dim[v] > 0) moving.push_back(v);
    if (moving.empty()) return;
    std::sort(moving.begin(), moving.end());
    moving.erase(std::unique(moving.begin(), moving.end()), moving.end());
    const std::vector<double> normal = area_weighted_normals(c.faces, x);
    std::vector<double> next = x;
    for (std::uint32_t v : moving) {  // one at a time, each seeing the moves before it
      const std::optional<glm::dvec3> k = star_kernel_point(c, v, next, facing);
      if (!k) {
        // No kernel in the plane (a star bent over a crease): the best of a few points towards
        // the neighbours, by the least facing area of the star.
        const glm::dvec3 before = at(next, v);
        glm::dvec3 best = before;
        double best_score = star_score(c, v, next, facing);
        for (std::uint32_t e : c.vertex_edges.row(v)) {
          const glm::dvec3 w = at(next, edge_other_end(c, e, v));
          for (double t : {0.25, 0.5}) {
            put(next, v, before + t * (w - before));
            if (const double sc = star_score(c, v, next, facing); sc > best_score) best_score = sc, best = at(next, v);
          }
        }
        put(next, v, best);
        continue;
      }
      const bool on_line = !c.vertex_dim.empty() && c.vertex_dim[v] == 1;
      // Onto the input (a line point: onto its line, at the kernel's point or, failing that, at
      // its line neighbours' mean); else the kernel's point itself, a little off the input.
      std::vector<glm::dvec3> tries;
      if (on_line) {
        glm::dvec3 mean(0.0);
        int count = 0;
        for (std::uint32_t e : c.vertex_edges.row(v))
          if (c.edge_dim[e] == 1) mean += at(next, edge_other_end(c, e, v)), ++count;
        if (!lines.empty()) tries.push_back(lines.closest(*k));
        if (count && !lines.empty()) tries.push_back(lines.closest(mean / double(count)));
      } else {
        tries.push_back(project(*k, at(normal, v), 2 * glm::distance(at(next, v), *k) + 1e-12));
      }
      // The kernel's point itself only a quarter of the star's longest edge off the input (or
      // line) at most: a fold is a defect, and so is a point far off the surface.
      double edge = 0;
      for (std::uint32_t e : c.vertex_edges.row(v))
        edge = std::max(edge, glm::distance(at(next, c.edge_verts[2 * e]), at(next, c.edge_verts[2 * e + 1])));
      if (!tries.empty() && glm::distance(*k, tries.front()) <= 0.25 * edge) tries.push_back(*k);
      // The first that unfolds the star; failing all, the best of them or none.
      const glm::dvec3 before = at(next, v);
      glm::dvec3 best = before;
      double best_score = star_score(c, v, next, facing);
      bool unfolded = false;
      for (const glm::dvec3& t : tries) {
        put(next, v, t);
        if (!star_turned(c, v, next, facing)) {
          unfolded = true;
          break;
        }
        if (const double sc = star_score(c, v, next, facing); sc > best_score) best_score = sc, best = t;
      }
      if (!unfolded) put(next, v, best);
    }
    keep_unfolded(c.faces, facing, x, next);
    if (next == x) return;  // every move would fold another face
    x.swap(next);
  }
}

void untangle_limit(const Complex& c, const LimitStencils& ls, const ProjectFn& project, const FeatureLines& lines, const FacingFn& facing_of,
                    std::vector<double>& x, std::vector<glm::dvec3>* net_facing, int rounds) {
  // Each fold count also gives the input's way at the limit surface's faces, for the next round:
  // finding it is a closest-point query per face, most of an untangling's time.
  const auto folds = [&](std::span<const double> p, const std::vector<glm::dvec3>& facing) { return count_turned(c.faces, p, facing); };
  // Folds of the limit surface L net and of the net; lim = L net, and the facings of both.
  const auto both = [&](const std::vector<double>& net, std::vector<double>& lim, std::vector<glm::dvec3>& lim_facing,
                        std::vector<glm::dvec3>& facing) {
    eval_limit(ls, net.data(), lim.data());
    lim_facing = facing_of(lim);
    facing = facing_of(net);
    return folds(lim, lim_facing) + folds(net, facing);
  };
  std::vector<double> y(x.size()), y_kept(x.size());
  std::vector<glm::dvec3> facing_y, facing_kept, facing_x, facing_next;
  std::size_t before = both(x, y, facing_y, facing_x);
  for (int round = 0; round < rounds && before > 0; ++round) {
    std::vector<double> moved = y;
    untangle(c, project, lines, facing_y, moved);
    // The moved limit points in clusters (sharing a face): each cluster's control change is
    // kept only when fewer faces fold around it, so one stubborn corner spoils no other.
    std::vector<std::uint32_t> cluster(c.num_vertices, UINT32_MAX);
    std::vector<std::vector<std::uint32_t>> clusters;
    for (std::uint32_t v0 = 0; v0 < c.num_vertices; ++v0) {
      if (cluster[v0] != UINT32_MAX || at(moved, v0) == at(y, v0)) continue;
      clusters.emplace_back();
      std::vector<std::uint32_t> stack = {v0};
      cluster[v0] = static_cast<std::uint32_t>(clusters.size() - 1);
      while (!stack.empty()) {
        const std::uint32_t v = stack.back();
        stack.pop_back();
        clusters.back().push_back(v);
        for (std::uint32_t f : c.vertex_faces.row(v))
          for (std::uint32_t w : c.faces.row(f))
            if (cluster[w] == UINT32_MAX && at(moved, w) != at(y, w)) cluster[w] = cluster[v], stack.push_back(w);
      }
    }
    if (clusters.empty()) break;
    std::vector<double> next = x, y_next = y;
    for (const std::vector<std::uint32_t>& k : clusters) {
      std::vector<std::uint32_t> controls;
      for (std::uint32_t v : k) {
        controls.push_back(v);
        for (std::uint32_t e : c.vertex_edges.row(v)) controls.push_back(edge_other_end(c, e, v));
      }
      std::sort(controls.begin(), controls.end());
      controls.erase(std::unique(controls.begin(), controls.end()), controls.end());
      if (controls.size() > 500) continue;  // a dense solve: untangling is for a few faces
      std::vector<std::uint32_t> reached, local_faces;
      for (std::uint32_t u : controls)
        for (std::uint32_t r : ls.users.row(u)) reached.push_back(r);
      std::sort(reached.begin(), reached.end());
      reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
      for (std::uint32_t r : reached)
        for (std::uint32_t f : c.vertex_faces.row(r)) local_faces.push_back(f);
      std::sort(local_faces.begin(), local_faces.end());
      local_faces.erase(std::unique(local_faces.begin(), local_faces.end()), local_faces.end());
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(Eigen::Index(reached.size()), Eigen::Index(controls.size()));
      Eigen::MatrixXd b(Eigen::Index(reached.size()), 3);
      for (std::size_t i = 0; i < reached.size(); ++i) {
        const std::uint32_t r = reached[i];
        for (std::uint32_t s = ls.rows.offsets[r]; s < ls.rows.offsets[r + 1]; ++s) {
          const auto it = std::lower_bound(controls.begin(), controls.end(), ls.rows.items[s]);
          if (it != controls.end() && *it == ls.rows.items[s]) A(Eigen::Index(i), it - controls.begin()) = ls.weights[s];
        }
        for (int d = 0; d < 3; ++d) b(Eigen::Index(i), d) = moved[3 * std::size_t(r) + d] - y[3 * std::size_t(r) + d];
      }
      const Eigen::MatrixXd dx = A.colPivHouseholderQr().solve(b);
      // Here the limit surface alone: the net under it is untangled after every cluster.
      const auto local_folds = [&](std::span<const double>, std::span<const double> lim) {
        std::size_t n = 0;
        for (std::uint32_t f : local_faces) n += turned(c.faces, f, lim, facing_y[f]);
        return n;
      };
      std::vector<double> trial = next, y_trial = y_next;
      for (std::size_t j = 0; j < controls.size(); ++j)
        for (int d = 0; d < 3; ++d) trial[3 * std::size_t(controls[j]) + d] += dx(Eigen::Index(j), d);
      for (std::uint32_t r : reached) {
        glm::dvec3 p(0.0);
        for (std::uint32_t s = ls.rows.offsets[r]; s < ls.rows.offsets[r + 1]; ++s) p += ls.weights[s] * at(trial, ls.rows.items[s]);
        put(y_trial, r, p);
      }
      if (local_folds(trial, y_trial) < local_folds(next, y_next)) next.swap(trial), y_next.swap(y_trial);
    }
    // The net under the moved limit points, as far as it comes right; the round stays when fewer
    // faces fold in all (a limit surface can come right only with its net folded under it).
    untangle(c, project, lines, facing_of(next), next);
    const std::size_t after = both(next, y_kept, facing_kept, facing_next);
    if (after >= before) break;
    x.swap(next), y.swap(y_kept), facing_y.swap(facing_kept), facing_x.swap(facing_next);
    before = after;
  }
  if (net_facing) net_facing->swap(facing_x);
}

}  // namespace sublift
