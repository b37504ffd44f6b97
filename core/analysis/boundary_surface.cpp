#include "core/analysis/boundary_surface.h"

#include <algorithm>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/base/errors.h"
#include "core/base/points.h"

namespace sublift {
namespace {

// Orients the faces of one closed cell consistently and outward. Scratch arrays are reused
// across cells; `sign[i]` (+1 keep, -1 reverse) is filled for local face i of the cell.
class CellOrienter {
 public:
  CellOrienter(const Complex& c, std::span<const double> xyz) : c_(c), xyz_(xyz) {}

  const std::vector<int>& orient(std::uint32_t cell) {
    const auto faces = c_.cell_faces.row(cell);
    const std::size_t m = faces.size();
    // Every edge of the cell with the local face using it and its direction there.
    uses_.clear();
    for (std::uint32_t i = 0; i < m; ++i) {
      const auto corners = c_.faces.row(faces[i]);
      const auto edges = c_.face_edges.row(faces[i]);
      for (std::size_t j = 0; j < edges.size(); ++j)
        uses_.push_back({edges[j], i, corners[j] == c_.edge_verts[2 * std::size_t(edges[j])]});
    }
    std::sort(uses_.begin(), uses_.end(), [](const Use& a, const Use& b) { return a.edge < b.edge; });
    // Neighbours across each edge: the two faces must run it in opposite directions.
    adj_offsets_.assign(m + 1, 0);
    for (std::size_t k = 0; k < uses_.size(); k += 2) {
      if (k + 1 >= uses_.size() || uses_[k + 1].edge != uses_[k].edge || (k + 2 < uses_.size() && uses_[k + 2].edge == uses_[k].edge))
        throw TopologyError("cell " + std::to_string(cell) + " is not closed: edge " + std::to_string(uses_[k].edge) +
                            " does not belong to exactly two of its faces");
      ++adj_offsets_[uses_[k].face + 1];
      ++adj_offsets_[uses_[k + 1].face + 1];
    }
    std::partial_sum(adj_offsets_.begin(), adj_offsets_.end(), adj_offsets_.begin());
    adj_.resize(adj_offsets_.back());
    fill_ = adj_offsets_;
    for (std::size_t k = 0; k < uses_.size(); k += 2) {
      const Use &a = uses_[k], &b = uses_[k + 1];
      const bool same = a.forward == b.forward;  // same direction: one of the two is reversed
      adj_[fill_[a.face]++] = {b.face, same};
      adj_[fill_[b.face]++] = {a.face, same};
    }
    // Walk each connected set of faces, then make its volume positive.
    sign_.assign(m, 0);
    const glm::dvec3 ref = at(xyz_, c_.faces.row(faces[0])[0]);
    for (std::uint32_t start = 0; start < m; ++start) {
      if (sign_[start]) continue;
      sign_[start] = 1;
      queue_.assign(1, start);
      for (std::size_t q = 0; q < queue_.size(); ++q) {
        const std::uint32_t i = queue_[q];
        for (std::uint32_t k = adj_offsets_[i]; k < adj_offsets_[i + 1]; ++k) {
          const int want = adj_[k].same ? -sign_[i] : sign_[i];
          int& s = sign_[adj_[k].face];
          if (!s) {
            s = want;
            queue_.push_back(adj_[k].face);
          } else if (s != want) {
            throw TopologyError("cell " + std::to_string(cell) + " is not orientable");
          }
        }
      }
      // Six times the signed volume (divergence theorem, faces as fans about a reference point).
      double volume = 0;
      for (std::uint32_t i : queue_) {
        const auto corners = c_.faces.row(faces[i]);
        const glm::dvec3 p0 = at(xyz_, corners[0]) - ref;
        double v = 0;
        for (std::size_t j = 1; j + 1 < corners.size(); ++j)
          v += glm::dot(p0, glm::cross(at(xyz_, corners[j]) - ref, at(xyz_, corners[j + 1]) - ref));
        volume += sign_[i] * v;
      }
      if (volume < 0)
        for (std::uint32_t i : queue_) sign_[i] = -sign_[i];
    }
    return sign_;
  }

 private:
  struct Use {
    std::uint32_t edge, face;
    bool forward;
  };
  struct Adj {
    std::uint32_t face;
    bool same;
  };
  const Complex& c_;
  std::span<const double> xyz_;
  std::vector<Use> uses_;
  std::vector<std::uint32_t> adj_offsets_, fill_, queue_;
  std::vector<Adj> adj_;
  std::vector<int> sign_;
};

}  // namespace

Csr boundary_faces(const Complex& c, std::span<const double> xyz, std::vector<std::uint32_t>* face_ids) {
  if (xyz.size() < 3 * std::size_t(c.num_vertices))
    throw Error("boundary_faces: " + std::to_string(xyz.size()) + " coordinates for " + std::to_string(c.num_vertices) + " vertices");
  const std::uint32_t nf = c.num_faces();
  if (c.dim < 3) {
    if (face_ids) {
      face_ids->resize(nf);
      std::iota(face_ids->begin(), face_ids->end(), 0u);
    }
    return c.faces;
  }
  // Cells per face, counted from the downward rows (no derived adjacency needed).
  std::vector<std::uint32_t> cells_of(nf, 0), owner(nf, 0);
  for (std::uint32_t k = 0; k < c.num_cells(); ++k)
    for (std::uint32_t f : c.cell_faces.row(k)) ++cells_of[f], owner[f] = k;
  std::vector<int> sign(nf, 0);  // for boundary faces: +1 keep, -1 reverse
  std::vector<char> done(c.num_cells(), 0);
  CellOrienter orienter(c, xyz);
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (cells_of[f] != 1 || done[owner[f]]) continue;
    const std::uint32_t k = owner[f];
    done[k] = 1;
    const std::vector<int>& s = orienter.orient(k);
    const auto faces = c.cell_faces.row(k);
    for (std::size_t i = 0; i < faces.size(); ++i)
      if (cells_of[faces[i]] == 1) sign[faces[i]] = s[i];
  }
  Csr out;
  if (face_ids) face_ids->clear();
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (cells_of[f] != 1) continue;
    const auto corners = c.faces.row(f);
    out.items.push_back(corners[0]);
    if (sign[f] > 0) out.items.insert(out.items.end(), corners.begin() + 1, corners.end());
    else out.items.insert(out.items.end(), corners.rbegin(), corners.rend() - 1);
    out.offsets.push_back(static_cast<std::uint32_t>(out.items.size()));
    if (face_ids) face_ids->push_back(f);
  }
  return out;
}

}  // namespace sublift
