#pragma once
// Local neighbourhoods of a triangle mesh, labelled canonically: the machinery behind the exact
// inner products (core/schemes/tri/tri_gram.h) and the per-edge wavelets (core/schemes/tri/tri_wavelets.h) of paper 004.
//
// Two neighbourhoods that are the same up to an orientation-preserving isomorphism (same
// valences, boundaries and feature dims, the same way round) get the same labels and the same
// signature, so everything computed from a neighbourhood can be cached by its signature and
// moved to another place of the same kind through the labels.
//
// Canonical order: breadth first from seed vertices (a face's corners in cycle order, an edge's
// two ends), each visited vertex walking its fan counterclockwise starting at the vertex it was
// reached from (a seed at the next seed). Topology alone decides the order.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/complex/complex.h"

namespace sublift {

/// Every vertex's neighbours counterclockwise (as the faces run). An open fan (a boundary
/// vertex) starts at the neighbour across its first boundary edge.
struct TriRings {
  Csr ring;                        // neighbours per vertex
  Csr ring_edge;                   // the edge to each neighbour (aligned with ring)
  std::vector<std::uint8_t> closed;  // 1 when the fan closes (interior vertex)
};

/// Throws TopologyError for a non-triangle face, an edge with more than two faces, or a vertex
/// whose faces do not form one fan. `c` needs its derived rows.
TriRings build_tri_rings(const Complex& c);

/// The rings of refine_tri(c), from c's rings without searching the fine mesh: equal to
/// build_tri_rings(refine_tri(c)) entry for entry. `c` needs its derived rows; `r` its rings.
TriRings refine_tri_rings(const Complex& c, const TriRings& r);

/// Canonical labelling of the vertices within graph distance `radius` of the seeds.
struct LocalOrder {
  std::vector<std::uint32_t> vertex;  // label -> mesh vertex
  std::vector<std::uint8_t> dist;     // label -> distance to the seeds
  std::vector<std::uint32_t> start;   // label -> the neighbour its fan walk starts at
  std::vector<std::uint32_t> fan0;    // label -> start's place in its fan (UINT32_MAX: not walked)
};

/// How many labels lie within `radius` of the seeds: labels are breadth first, so they are the
/// first ones.
inline std::uint32_t labels_within(const LocalOrder& o, int radius) {
  std::uint32_t n = 0;
  while (n < o.dist.size() && o.dist[n] <= radius) ++n;
  return n;
}

[[noreturn]] void throw_not_a_neighbour(std::uint32_t v, std::uint32_t x);
/// Position of neighbour `x` in v's fan; throws TopologyError when x is not a neighbour. Inline:
/// the row templates' walks ask it for every label.
inline std::uint32_t fan_index(const TriRings& r, std::uint32_t v, std::uint32_t x) {
  const std::uint32_t* row = r.ring.items.data() + r.ring.offsets[v];
  const std::uint32_t n = r.ring.offsets[v + 1] - r.ring.offsets[v];
  for (std::uint32_t i = 0; i < n; ++i)
    if (row[i] == x) return i;
  throw_not_a_neighbour(v, x);
}

/// Whether the vertices `vs` (of a mesh of n vertices) are pairwise distinct: the same per-thread
/// table local_order labels with, so no sort and no allocation.
bool all_distinct(std::span<const std::uint32_t> vs, std::uint32_t n);

/// `seed_start[i]` is the neighbour seed i's walk starts at (it must be a neighbour).
LocalOrder local_order(const TriRings& r, std::span<const std::uint32_t> seeds,
                       std::span<const std::uint32_t> seed_start, int radius);
/// The same into `o`, reusing its storage (hot loops take millions of small orders).
void local_order(const TriRings& r, std::span<const std::uint32_t> seeds, std::span<const std::uint32_t> seed_start,
                 int radius, LocalOrder& o);

/// The signature of the labelled neighbourhood up to distance `radius` (<= the order's): per
/// label its distance, fan closure, valence, vertex dim, and its fan as labels (-1 beyond) with
/// the edges' dims. Equal signatures <=> isomorphic labelled neighbourhoods. Stored as 16-bit
/// numbers when every one fits (nearly always), else 32-bit, after a byte that says which.
std::string local_signature(const Complex& c, const TriRings& r, const LocalOrder& o, int radius);

/// local_order(r, seeds, seed_start, radius, o) and local_signature(c, r, o, radius, out) in
/// one pass: each vertex's fan is walked once, labelling and writing together. The same order
/// and the same signature as the two calls.
void local_order_and_signature(const Complex& c, const TriRings& r, std::span<const std::uint32_t> seeds,
                               std::span<const std::uint32_t> seed_start, int radius, LocalOrder& o, std::string& out);

/// The same order, and a key instead of the signature: the same facts, written compactly (per
/// label its distance as a byte, then a varint of valence, closure and dim, then per fan entry a
/// varint of the neighbour as "labelled here" (the next label, so not written), "beyond" or its
/// label, with the edge's dim), about a third of the signature's bytes. The key can be decoded
/// back into the signature, so equal keys <=> equal signatures; but keys and signatures are
/// different strings, and only keys compare with keys. For caches keyed by the neighbourhood
/// alone (the edges' wavelets: a 1 M fit keeps a quarter of a million).
void local_order_and_key(const Complex& c, const TriRings& r, std::span<const std::uint32_t> seeds,
                         std::span<const std::uint32_t> seed_start, int radius, LocalOrder& o, std::string& out);

/// A hash for signatures that reads them 8 bytes at a time (they are kilobytes long and looked
/// up once per irregular edge and face; equality is still checked in full).
///
/// Deliberately not noexcept: libstdc++ keeps a node's hash code only when the hasher may throw
/// (or is known to be slow), and without it every look-up rehashes the kilobyte keys it walks
/// past in its bucket and every rehash all of them (half the hashing, which was 15 % of the main
/// thread's time in a Loop hierarchy's setup on a fitted base, perf).
struct SignatureHash {
  std::size_t operator()(std::string_view s) const;
  std::size_t operator()(const std::string& s) const { return (*this)(std::string_view(s)); }
};

/// The sub-mesh of the faces whose corners all carry labels, vertices numbered by label, faces
/// listed canonically (each from its lowest label, sorted: nothing of the mesh's numbering), with
/// the original vertex and edge dims (so the fans of labels closer than the order's radius are
/// complete copies). A rim vertex whose faces there form several arcs (the surface meets itself
/// within the radius) gets a copy per extra arc, numbered after the labels: the patch is always
/// a manifold. Derived rows built. Reads c's dims and its rings `r` only (not its derived rows).
Complex local_patch(const Complex& c, const TriRings& r, const LocalOrder& o);

}  // namespace sublift
