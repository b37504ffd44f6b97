#pragma once
// Exact inner products of the triangle schemes' scaling functions on any triangle mesh
// (paper 004 sec. 5), assembled face by face.
//
// <phi_a, phi_b> = sum over faces f of the integral over f of phi_a phi_b. On face f only the
// functions of N(f), the vertices within `support_rings` of f's corners, are non-zero, so face f
// contributes one small symmetric matrix G_f (rows and columns N(f) in canonical order,
// core/schemes/tri/tri_local.h). Subdividing f into its four children gives the recurrence
//
//     G_f = 1/4 sum_k S_k^T G_{child k} S_k        (004 eq. 10 restricted to f; 1/4 = area)
//
// with S_k the subdivision rows of N(child k) over N(f). G_f depends only on the neighbourhood
// of f, so it is cached by the neighbourhood's signature (its "type"). Types close under
// subdivision: a regular face's children are regular, the corner child of a face at an
// isolated extraordinary vertex has the type of its parent (the self-similarity of sec. 5.2), and
// faces near several extraordinary vertices reach such types after a few steps. The cached
// types form a finite system G = T(G), solved by sweeps with every G_f rescaled to the area of
// its face (its entries sum to 1: the functions sum to 1 on f). A type's matrices depend on its
// labelled neighbourhood only (local_patch is canonical), so the cache does not depend on which
// face met a type first, nor on the thread count. The sweeps contract by the
// scheme's subdominant eigenvalue over 4 per step or better; they stop at 1e-16.
//
// Units: a face's area is 1 on its own level (level-j faces of a hierarchy have area 4^-j
// times that of a base face).
#include <array>
#include <deque>
#include <span>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "core/complex/complex.h"
#include "core/schemes/tri/tri_local.h"
#include "core/schemes/tri/tri_rules.h"

namespace sublift {

struct TriGramRadii {
  int support = 1;    // N(f): vertices within this many rings of f's corners
  int signature = 3;  // the neighbourhood that decides a type
  int patch = 4;      // the patch copied around a face to subdivide it
};
TriGramRadii tri_gram_radii(Scheme s);

class FaceGramCache {
 public:
  explicit FaceGramCache(Scheme s);
  Scheme scheme() const { return scheme_; }
  const TriGramRadii& radii() const { return radii_; }

  /// The Gram block of face f of `c` (rings `r` of c): `verts` are N(f) as vertices of c, G
  /// their integrals over f. Solves new types on first use.
  struct FaceGram {
    std::vector<std::uint32_t> verts;
    const Eigen::MatrixXd* G = nullptr;
    int type = -1;
  };
  FaceGram face_gram(const Complex& c, const TriRings& r, std::uint32_t f);
  /// The same when f's type is known already, else false. Only reads the cache, so faces may
  /// be looked up from several threads while nothing is added.
  bool find(const Complex& c, const TriRings& r, std::uint32_t f, FaceGram& out) const;
  /// The same when f's type is known to be `type`: the child type (child_type) of f's parent
  /// face in the coarser mesh c refines. Orders f's neighbourhood to the support radius only,
  /// not to the signature's, and searches no cache. False when the type is not solved.
  bool from_type(const Complex& c, const TriRings& r, std::uint32_t f, int type, FaceGram& out) const;
  /// The type of child k (refine_tri's face 4 g + k) of a face g of type t. A child's type is
  /// the one its signature has in the refined mesh: it is taken in the parent's subdivided
  /// patch, which holds the child's whole signature neighbourhood (TriGramRadii).
  int child_type(int t, int k) const {
    return types_[static_cast<std::size_t>(t)].child[static_cast<std::size_t>(k)];
  }

  /// A face of a mesh, with the mesh's rings.
  struct FaceRef {
    const Complex* mesh = nullptr;
    const TriRings* rings = nullptr;
    std::uint32_t face = 0;
  };
  /// Makes and solves the types of `faces` that are not cached yet, with every type they lead to
  /// (their children's, and so on). The patches are built and subdivided on the pool, wave by
  /// wave (the faces, then the new children, ...) in chunks of faces; types are numbered in
  /// that order, so the cache comes out the same whatever the thread count.
  void add_types(std::span<const FaceRef> faces);

  std::size_t num_types() const { return types_.size(); }
  /// Largest change of the last solve's final sweep.
  double last_change() const { return last_change_; }

 private:
  struct Type {
    int n = 0;                       // |N(f)|
    std::array<int, 4> child{};      // child types
    // Rows N(child k), cols N(f): subdivision stencils, a few entries per row, so sparse (the
    // dense triple products were the most of a new type's cost).
    std::array<Eigen::SparseMatrix<double>, 4> S;
    Eigen::MatrixXd G;
    bool solved = false;
  };
  struct Made;
  // What a new type is made of: its patch from `order` (around face f of c) subdivided.
  Made make_type(const Complex& c, const TriRings& r, const LocalOrder& order, std::uint32_t f) const;
  void solve_pending();

  Scheme scheme_;
  TriGramRadii radii_;
  std::unordered_map<std::string, int, SignatureHash> index_;
  std::deque<Type> types_;  // stable addresses: FaceGram points into it
  std::vector<const std::string*> signature_;  // per type, its key in index_
  std::vector<int> pending_;
  double last_change_ = 0;
};

/// Seeds for a face's canonical order: its corners in cycle order, each walking from the next.
void face_seeds(const Complex& c, std::uint32_t f, std::uint32_t seeds[3], std::uint32_t starts[3]);

}  // namespace sublift
