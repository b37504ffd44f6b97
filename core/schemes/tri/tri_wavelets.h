#pragma once
// The wavelets of Lounsbery, DeRose & Warren (paper 004 sec. 6.2-6.3) on triangle meshes:
// for the new vertex m on coarse edge e = (a, b), with D the k-disc of e (the level-j vertices
// within k rings of a or b),
//
//     psi_m = phi_m^{j+1} - sum_{i in D} alpha_i phi_i^j                    (004 eq. 15, 16, 18)
//
// where alpha solves the local least-squares problem <psi_m, phi_i^j> = 0 for all i in D:
//
//     sum_l <phi_i^j, phi_l^j> alpha_l = <phi_i^j, phi_m^{j+1}>,   i in D.
//
// Both sides come from the exact face-by-face inner products (core/schemes/tri/tri_gram.h): the left on the
// level-j faces, the right on the level-(j+1) faces (area 1/4 each) pulled back through the
// subdivision rows, r_i = sum_c P(c, i) <phi_c^{j+1}, phi_m^{j+1}>. Then
// ||psi_m||^2 = <phi_m, phi_m> - alpha . r, in units of a level-j face.
//
// D's order (the `alpha` order of `sublift-cli coefficients`): a, b, then breadth first, each
// vertex walking its neighbours counterclockwise from the vertex it was reached from (a from b,
// b from a); core/schemes/tri/tri_local.h. The result depends only on the neighbourhood of e up to
// edge_radius() rings, so it is cached by that neighbourhood's signature; edges with no
// irregular vertex (valence != 6, boundary, feature) that close share one entry without
// computing a signature at all.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/complex/complex.h"
#include "core/schemes/tri/tri_gram.h"
#include "core/schemes/tri/tri_local.h"
#include "core/schemes/tri/tri_rules.h"

namespace sublift {

struct EdgeWavelet {
  std::vector<double> alpha;   // over D in canonical order
  double norm2 = 0;            // ||psi||^2, a level-j face has area 1
  double residual = 0;         // max_i |<psi, phi_i>| (orthogonality check)
  double self = 0;             // <phi_m, phi_m> (level-j face area 1)
};

/// The face Grams found on one mesh, kept per face (faces near many irregular edges are asked
/// often): `slot[f]` indexes `gram`, UINT32_MAX when face f has not been asked.
struct FaceGrams {
  std::vector<std::uint32_t> slot;
  std::vector<FaceGramCache::FaceGram> gram;
};

/// One level and its 1-to-4 refinement, as the wavelets of that step read them.
struct TriLevel {
  const Complex* coarse = nullptr;  // derived rows needed
  const TriRings* coarse_rings = nullptr;
  const Complex* fine = nullptr;    // refine_tri(*coarse); its derived rows and rings are built
  const TriRings* fine_rings = nullptr;  // on the first wavelet that is solved, if absent (the
                                         // rings from coarse_rings: refine_tri_rings)
  std::unique_ptr<Complex> fine_built;
  std::unique_ptr<TriRings> fine_rings_built;
  const TriStencils* stencils = nullptr;  // build_tri_stencils(*coarse, scheme)
  // Per coarse face its type (-1: not known), handed on from the coarser level's build
  // (TriWaveletBuilder::fine_face_types): a face whose type is known is looked up without a
  // signature. May be null.
  const std::vector<std::int32_t>* coarse_types = nullptr;
  FaceGrams coarse_faces, fine_faces;
};

class TriWaveletBuilder {
 public:
  TriWaveletBuilder(Scheme s, int disc);
  /// Rings of the patch an edge's wavelet is computed on.
  int edge_radius() const;
  /// Rings of the neighbourhood the wavelet depends on (its cache signature): the disc, the
  /// supports of its functions and the faces' own signatures.
  int signature_radius() const;

  /// What finds an edge's wavelet in the cache: its neighbourhood's signature (written as the
  /// compact key of local_order_and_key: a third of the bytes, the cache holds many), and its disc D
  /// as coarse vertices. Reads `level` only, so edges' keys may be taken in parallel.
  struct EdgeKey {
    std::string signature;
    std::vector<std::uint32_t> disc;
  };
  EdgeKey edge_key(const TriLevel& level, std::uint32_t e) const;
  /// The same into reused storage.
  void edge_key(const TriLevel& level, std::uint32_t e, std::vector<std::uint32_t>& disc, std::string& signature) const;
  /// The cached wavelet of a signature, or null. Only reads the cache, so keys may be looked up
  /// from several threads while nothing is added.
  const EdgeWavelet* find(const std::string& signature) const;
  /// The wavelet of the edge whose key this is: cached, or solved and cached.
  const EdgeWavelet& edge_wavelet(TriLevel& level, std::uint32_t e, EdgeKey&& key);
  /// Solves and caches the wavelets of `edges` of `level`, whose `signatures` (moved from) are
  /// pairwise distinct and not cached. Everything runs on the pool: the edges' own work, the
  /// look-ups of the faces they meet, and the face types that are new (FaceGramCache::add_types,
  /// whose types do not depend on the order they are met in). Returns the wavelets, aligned
  /// with `edges`.
  std::vector<const EdgeWavelet*> solve(TriLevel& level, std::span<const std::uint32_t> edges,
                                        std::span<std::string> signatures);

  /// The wavelet of coarse edge e of `level`. `disc_out` receives D as coarse vertices.
  /// `regular_hint`: the caller knows no irregular vertex lies within signature_radius().
  const EdgeWavelet& edge_wavelet(TriLevel& level, std::uint32_t e, std::vector<std::uint32_t>* disc_out,
                                  bool regular_hint = false);
  /// The same for one edge of a small mesh (refines it on each call: tables, tests).
  const EdgeWavelet& edge_wavelet(const Complex& c, const TriRings& r, std::uint32_t e,
                                  std::vector<std::uint32_t>* disc_out);

  std::size_t num_face_types() const { return gram_.num_types(); }
  /// The type of each face of level.fine (-1: not known), for the next level's coarse_types: a
  /// face's child types where its type is known (handed on, or looked up on this level), else
  /// the fine face's own where it was looked up. Reads the cache only.
  std::vector<std::int32_t> fine_face_types(const TriLevel& level) const;

  /// Anchored look-ups (build_tri_transition): an edge within R = signature_radius() of an
  /// irregular vertex v lies, with its whole R-neighbourhood, inside v's (2R + 1)-neighbourhood.
  /// So v's signature at that radius (its anchor type) and the labels of the edge's ends there
  /// decide the edge's signature, and with it the wavelet: one signature per irregular vertex
  /// instead of one per edge near it. `anchor_type` numbers a signature (new or known);
  /// anchored keys map to wavelets already cached.
  std::uint32_t anchor_type(const std::string& signature);
  bool knows_anchor_type(const std::string& signature) const { return anchor_types_.count(signature) != 0; }
  const EdgeWavelet* find_anchored(std::uint64_t key) const;
  void add_anchored(std::uint64_t key, const EdgeWavelet* w) { anchored_.emplace(key, w); }

 private:
  struct EdgePlan;
  void plan(const TriLevel& level, std::uint32_t e, EdgePlan& out) const;
  EdgeWavelet compute(const TriLevel& level, const EdgePlan& plan) const;

  int disc_;
  FaceGramCache gram_;
  std::unordered_map<std::string, std::unique_ptr<EdgeWavelet>, SignatureHash> edges_;
  std::unique_ptr<EdgeWavelet> regular_;
  std::unordered_map<std::string, std::uint32_t, SignatureHash> anchor_types_;
  std::unordered_map<std::uint64_t, const EdgeWavelet*> anchored_;
};

/// Per vertex: graph distance to the nearest irregular vertex (valence != 6, open fan, vertex
/// dim < 2, or on a feature edge), capped at `cap`. `nearest` (optional) receives that vertex
/// (the first found by a breadth-first search from all of them in vertex order; UINT32_MAX where
/// the distance is capped).
std::vector<std::uint8_t> distance_to_irregular(const Complex& c, const TriRings& r, int cap,
                                                std::vector<std::uint32_t>* nearest = nullptr);

/// A disc of `radius` rings around one vertex of valence n (vertex 0), every other inner
/// vertex of valence 6: n wedges of the triangular lattice. Vertex 1 is on spoke 0. `xy`
/// (optional) receives a drawing: wedge s spans the angle 2 pi s / n .. 2 pi (s + 1) / n, its
/// vertex p e_s + q e_{s+1} at p u_s + q u_{s+1}, u_s the unit vector at angle 2 pi s / n.
Complex extraordinary_disc(int valence, int radius, std::vector<double>* xy = nullptr);

}  // namespace sublift
