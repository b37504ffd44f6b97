#pragma once
// Queries against a mesh's polygons, fan-triangulated: every intersection of a ray (sphere
// resampling keeps the farthest and counts multiple hits, so it cannot stop at the first) and the
// closest point (fitting attracts each level to the input and measures distances both ways). A
// bounding volume hierarchy: median splits, leaves of at most 4 triangles, inner nodes in
// depth-first order, each holding its children's boxes; about log(n) box tests per query, fewer
// from a hint (a search climbs from the hint's leaf). Built once (refit moves it), queried
// concurrently (the queries are const and allocation-free apart from the caller's buffer).
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "core/base/csr.h"
#include "core/base/default_init.h"
#include "core/base/surface_mesh.h"

namespace sublift {

class TriangleBvh {
 public:
  /// Over every face of `mesh` (faces of k corners give k-2 triangles).
  explicit TriangleBvh(const SurfaceMesh& mesh);
  /// The same from faces over positions (3 per vertex).
  TriangleBvh(std::span<const double> positions, const Csr& faces);

  /// Appends to `hits` the parameter t >= 0 of every triangle the ray origin + t * dir meets
  /// (dir need not be unit; unsorted; one entry per triangle, so shared edges give duplicates).
  /// Rays parallel to a triangle's plane miss it.
  /// `faces`, when given, gets the polygon of each hit (aligned with `hits`).
  void all_hits(const glm::dvec3& origin, const glm::dvec3& dir, std::vector<double>& hits,
                std::vector<std::uint32_t>* faces = nullptr) const;

  /// The smallest t in [0, t_max] at which origin + t * dir meets a triangle facing `facing`
  /// (normal . facing > 0), or infinity: boxes beyond the best hit so far are not entered.
  /// `hint` (a polygon near the origin, say its closest): the search starts at its leaf and
  /// climbs, which saves the walk down from the root on a short ray; the same answer.
  double nearest_hit(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& facing, double t_max,
                     std::uint32_t hint = UINT32_MAX) const;

  /// nearest_hit along dir and along -dir (the same facing, bound and hint) from one walk of the
  /// tree: {forward, backward}, each bit for bit what its own call returns.
  std::pair<double, double> nearest_hits(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& facing,
                                         double t_max, std::uint32_t hint = UINT32_MAX) const;

  /// The closest point of the triangles to p and its distance (infinite with no triangles).
  struct Closest {
    glm::dvec3 point{0.0};
    double distance = 0.0;
    std::uint32_t face = UINT32_MAX;  // the polygon the point lies on (of equally near ones, the lowest)
  };
  Closest closest(const glm::dvec3& p) const;
  /// The same over the triangles facing `facing` (normal . facing > 0): the nearest point of the
  /// surface's side that faces that way (fitting keeps a thin part's two sides apart).
  Closest closest(const glm::dvec3& p, const glm::dvec3& facing) const;
  /// Either of the two (`facing` null: any side), searched from polygon `hint` first (an answer
  /// for a point near p, say on a surface that has moved a little since): its distance bounds
  /// the search, so far fewer boxes are opened. The same answer as without it: of equally near
  /// polygons the lowest numbered is named, however the search went. A hint that is no polygon
  /// is ignored.
  Closest closest(const glm::dvec3& p, const glm::dvec3* facing, std::uint32_t hint) const;

  /// The same polygons at new positions (3 per vertex, as many vertices as built with): the
  /// tree is kept and its boxes recomputed from the leaves up, a fraction of a build. Closest
  /// points come out exactly as from a fresh build (any boxes that hold their triangles do);
  /// a ray's hits may come in another order. Fitting moves a net a little per round.
  void refit(std::span<const double> positions);

  std::size_t num_triangles() const { return tris_.size(); }
  /// Diagonal of the triangles' bounding box.
  double diagonal() const { return diagonal_; }

 private:
  // The facing tests take the normal, cross(e1, e2), as they go: a stored one made a leaf's four
  // triangles two cache lines longer, and the queries wait on memory, not on arithmetic.
  struct Tri {
    glm::dvec3 p0, e1, e2;
    std::uint32_t face;  // (no initialiser: an array of them is sized unzeroed, UninitVector)
  };
  // An inner node holds its two children's boxes (floats rounded outwards, so a box still
  // holds its triangles and its distance is still a lower bound) and references: opening a node
  // reads one cache line. A reference is a node index, or, with kLeaf set, a leaf: up to
  // kLeafSize triangles tris_[first, first + count), count in bits 28-30.
  // `parent`: where the node hangs (see kNoParent), in the same cache line as the boxes, so a
  // search climbing from a leaf reads one line per level.
  struct alignas(64) Node {
    std::array<float, 3> lo[2], hi[2];
    std::uint32_t child[2] = {0, 0};
    std::uint32_t parent = UINT32_MAX;
  };
  static constexpr std::uint32_t kLeaf = 1u << 31;
  static constexpr std::uint32_t kMaxLeafFirst = (1u << 28) - 1;
  static bool is_leaf(std::uint32_t ref) { return (ref & kLeaf) != 0; }
  static std::uint32_t leaf_first(std::uint32_t ref) { return ref & kMaxLeafFirst; }
  static std::uint32_t leaf_count(std::uint32_t ref) { return (ref >> 28) & 7u; }
  // A subtree as built: its reference and its padded box.
  struct Built {
    std::uint32_t ref = 0;
    glm::dvec3 lo{0.0}, hi{0.0};
  };
  // Calls visit(triangle index) for the triangles of every leaf whose box the ray meets within
  // the interval limit() = {t0, t1} (asked again at each node, so a search can shrink it), leaves in
  // depth-first order, left child first.
  // From polygon `hint`'s leaf up instead of from the root when it is one (leaves in another
  // order then).
  template <class Limit, class Visit>
  void walk_ray(const glm::dvec3& origin, const glm::dvec3& dir, Limit limit, Visit visit, std::uint32_t hint = UINT32_MAX) const;
  // Appends the inner nodes of the subtree of order[begin, end) to `nodes` (depth first, left
  // subtree first) and returns it; `split` is the median split it makes at every inner node.
  // Leaves' boxes from the triangles' corners (3 per triangle, as built) over positions p.
  Built build(std::vector<Node>& nodes, std::vector<std::uint32_t>& order, std::span<const glm::dvec3> centers,
              std::span<const double> p, std::span<const std::uint32_t> corners, std::uint32_t begin, std::uint32_t end) const;
  // Splits order[begin, end) at its middle along the centres' longest axis (centres all alike:
  // as it lies); false (nothing moved) when the range is a leaf: kLeafSize triangles or fewer.
  // (Leaves of 2 took a hinted query from a 2 M-triangle torus's own faces 15 % less time, but
  // queries from farther points no less, cold ones and builds more: kept at 4.)
  static constexpr std::uint32_t kLeafSize = 4;
  static bool split(std::vector<std::uint32_t>& order, std::span<const glm::dvec3> centers, std::uint32_t begin,
                    std::uint32_t end, std::uint32_t& mid);
  static void set_child(Node& n, int k, const Built& b);
  // Triangle (a, b, c) of polygon `face`, as every build and refit makes it.
  static Tri make_tri(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, std::uint32_t face);
  // Grows the box [lo, hi] by t's corners.
  static void grow(const Tri& t, glm::dvec3& lo, glm::dvec3& hi);
  // Where a search from polygon `hint` starts: up_ of its first triangle; kNoParent when the
  // hint is no polygon, has no triangle, or the whole tree is one leaf.
  std::uint32_t hint_up(std::uint32_t hint) const;

  UninitVector<Tri> tris_;
  std::vector<Node> nodes_;
  Built root_;  // the whole tree (unused when tris_ is empty)
  // Node -> its parent (Node::parent), triangle -> the node holding its leaf (up_): index << 1 |
  // side (1: right), kNoParent for the root (and for every triangle when the root is a leaf).
  static constexpr std::uint32_t kNoParent = UINT32_MAX;
  std::vector<std::uint32_t> up_;
  UninitVector<std::uint32_t> corners_;  // per triangle (tris_ order) its three vertices, for refit
  std::size_t num_vertices_ = 0;
  Csr face_tris_;  // the triangles (indices into tris_) of each polygon
  double diagonal_ = 0.0;
  double pad_ = 0.0;
};

}  // namespace sublift
