#include "core/schemes/tri/tri_local.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "core/complex/complex_build.h"
#include "core/base/epoch_table.h"
#include "core/base/errors.h"
#include "core/base/parallel.h"

namespace sublift {

TriRings build_tri_rings(const Complex& c) {
  TriRings r;
  const std::uint32_t nv = c.num_vertices;
  r.ring.offsets.assign(nv + 1, 0);
  r.ring_edge.offsets.assign(nv + 1, 0);
  r.closed.assign(nv, 0);
  for (std::uint32_t f = 0; f < c.num_faces(); ++f)
    if (c.faces.size(f) != 3)
      throw TopologyError("face " + std::to_string(f) + " has " + std::to_string(c.faces.size(f)) +
                          " corners; the triangle schemes need triangles");
  for (std::uint32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_faces.size(e) > 2)
      throw TopologyError("edge " + std::to_string(e) + " (vertices " + std::to_string(c.edge_verts[2 * e]) + ", " +
                          std::to_string(c.edge_verts[2 * e + 1]) + ") has " + std::to_string(c.edge_faces.size(e)) +
                          " faces; the triangle schemes need a manifold surface");
  // Ring v has one entry per edge at v (checked below), so every row's place is known first and
  // the rows are filled in parallel; a fault is named for the lowest vertex that has one.
  for (std::uint32_t v = 0; v < nv; ++v)  // a vertex on no face has an empty ring
    r.ring.offsets[v + 1] = r.ring.offsets[v] + (c.vertex_faces.size(v) == 0 ? 0 : c.vertex_edges.size(v));
  r.ring_edge.offsets = r.ring.offsets;
  r.ring.items.resize(r.ring.offsets[nv]);
  r.ring_edge.items.resize(r.ring.offsets[nv]);
  struct Wedge { std::uint32_t next, prev, e_next, e_prev; };
  // Fills v's row; throws TopologyError when v's faces do not form one fan.
  const auto fill = [&](std::uint32_t v, std::vector<Wedge>& w) {
    w.clear();
    for (std::uint32_t f : c.vertex_faces.row(v)) {
      const std::uint32_t b = c.faces.offsets[f];
      for (std::uint32_t s = b; s < b + 3; ++s) {
        if (c.faces.items[s] != v) continue;
        const std::uint32_t sn = face_next_slot(c, f, s), sp = face_prev_slot(c, f, s);
        w.push_back({c.faces.items[sn], c.faces.items[sp], c.face_edges.items[s], c.face_edges.items[sp]});
      }
    }
    const auto fail = [&] {
      throw TopologyError("the faces around vertex " + std::to_string(v) +
                          " do not form one fan; the triangle schemes need a manifold surface");
    };
    if (w.empty()) return;  // isolated vertex: an empty closed ring
    // The wedge whose `next` is nobody's `prev` starts an open fan.
    std::size_t first = 0;
    bool open = false;
    for (std::size_t i = 0; i < w.size(); ++i) {
      bool has_pred = false;
      for (const Wedge& x : w) has_pred |= x.prev == w[i].next;
      if (!has_pred) {
        if (open) fail();
        open = true;
        first = i;
      }
    }
    if (w.size() + (open ? 1 : 0) != c.vertex_edges.size(v)) fail();
    std::uint32_t* out = r.ring.items.data() + r.ring.offsets[v];
    std::uint32_t* out_e = r.ring_edge.items.data() + r.ring.offsets[v];
    std::size_t cur = first;
    for (std::size_t k = 0; k < w.size(); ++k) {
      *out++ = w[cur].next;
      *out_e++ = w[cur].e_next;
      std::size_t nxt = w.size();
      for (std::size_t i = 0; i < w.size(); ++i)
        if (w[i].next == w[cur].prev) {
          if (nxt != w.size()) fail();
          nxt = i;
        }
      if (k + 1 == w.size()) {
        if (open ? nxt != w.size() : nxt != first) fail();
        if (open) {
          *out++ = w[cur].prev;
          *out_e++ = w[cur].e_prev;
        }
      } else {
        if (nxt == w.size() || nxt == first) fail();
        cur = nxt;
      }
    }
    r.closed[v] = open ? 0 : 1;
  };
  std::atomic<std::uint32_t> first_bad{UINT32_MAX};
  parallel_for(nv, 4096, [&](std::uint32_t v0, std::uint32_t v1) {
    std::vector<Wedge> w;
    for (std::uint32_t v = v0; v < v1; ++v) {
      try {
        fill(v, w);
      } catch (const TopologyError&) {
        std::uint32_t seen = first_bad.load();
        while (v < seen && !first_bad.compare_exchange_weak(seen, v)) {
        }
        break;  // later vertices of this chunk cannot be lower
      }
    }
  });
  if (first_bad != UINT32_MAX) {
    std::vector<Wedge> w;
    fill(first_bad, w);  // throws its message
  }
  return r;
}

namespace {

thread_local EpochTable table;  // vertex -> label

}  // namespace

void throw_not_a_neighbour(std::uint32_t v, std::uint32_t x) {
  throw TopologyError("vertex " + std::to_string(x) + " is not a neighbour of " + std::to_string(v));
}

TriRings refine_tri_rings(const Complex& c, const TriRings& r) {
  const std::uint32_t nv = c.num_vertices, ne = c.num_edges();
  if (c.edge_faces.rows() != ne || r.ring.rows() != nv)
    throw std::logic_error("refine_tri_rings: the coarse mesh needs its derived rows and its rings");
  TriRings out;
  out.ring.offsets.resize(std::size_t(nv) + ne + 1);
  out.ring.offsets[0] = 0;
  for (std::uint32_t v = 0; v < nv; ++v) out.ring.offsets[v + 1] = out.ring.offsets[v] + r.ring.size(v);
  for (std::uint32_t e = 0; e < ne; ++e) {
    const std::uint32_t n = c.edge_faces.size(e);  // at most 2: the rings were built
    out.ring.offsets[nv + e + 1] = out.ring.offsets[nv + e] + (n == 2 ? 6 : n == 1 ? 4 : 0);
  }
  out.ring_edge.offsets = out.ring.offsets;
  out.ring.items.resize(out.ring.offsets.back());
  out.ring_edge.items.resize(out.ring.offsets.back());
  out.closed.resize(std::size_t(nv) + ne);
  // The half of coarse edge e at its end x (refine_tri.h: 2e touches edge_verts[2e]).
  const auto half = [&](std::uint32_t e, std::uint32_t x) { return 2 * e + (c.edge_verts[2 * e] == x ? 0u : 1u); };
  parallel_for(nv, 8192, [&](std::uint32_t v0, std::uint32_t v1) {
    for (std::uint32_t v = v0; v < v1; ++v) {
      // An old vertex: the midpoints of its edges, in its coarse ring's order and from the same
      // place (its lowest face's corner triangle is its lowest fine face).
      std::uint32_t* ring = out.ring.items.data() + out.ring.offsets[v];
      std::uint32_t* ring_edge = out.ring_edge.items.data() + out.ring.offsets[v];
      for (std::uint32_t e : r.ring_edge.row(v)) *ring++ = nv + e, *ring_edge++ = half(e, v);
      out.closed[v] = r.closed[v];
    }
  });
  parallel_for(ne, 8192, [&](std::uint32_t e0, std::uint32_t e1) {
    for (std::uint32_t e = e0; e < e1; ++e) {
      // A midpoint m of e = e_k of face f (running a_k -> a_{k+1}) meets, in f, corner triangle
      // k + 1, the middle and corner triangle k: its neighbours there, counterclockwise, are
      // a_{k+1}, m_{k+1}, m_{k-1} (edges: e's half at a_{k+1}, inner i_k, inner i_{k-1}), then
      // a_k, which starts the other face's three.
      const auto faces = c.edge_faces.row(e);
      if (faces.empty()) continue;
      std::array<std::uint32_t, 6> nb, ed;
      std::uint32_t k_of[2] = {0, 0};
      for (std::size_t i = 0; i < faces.size(); ++i) {
        const std::uint32_t f = faces[i], b = c.faces.offsets[f];
        std::uint32_t k = 0;
        while (k < 3 && c.face_edges.items[b + k] != e) ++k;
        if (k == 3) throw std::logic_error("refine_tri_rings: an edge's face does not hold it");
        k_of[i] = k;
        const std::uint32_t k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        nb[3 * i] = c.faces.items[b + k1], ed[3 * i] = half(e, c.faces.items[b + k1]);
        nb[3 * i + 1] = nv + c.face_edges.items[b + k1], ed[3 * i + 1] = 2 * ne + 3 * f + k;
        nb[3 * i + 2] = nv + c.face_edges.items[b + k2], ed[3 * i + 2] = 2 * ne + 3 * f + k2;
      }
      std::uint32_t* ring = out.ring.items.data() + out.ring.offsets[nv + e];
      std::uint32_t* ring_edge = out.ring_edge.items.data() + out.ring.offsets[nv + e];
      if (faces.size() == 1) {  // open: from a_{k+1} round to a_k
        const std::uint32_t f = faces[0], b = c.faces.offsets[f];
        std::copy(nb.begin(), nb.begin() + 3, ring), std::copy(ed.begin(), ed.begin() + 3, ring_edge);
        ring[3] = c.faces.items[b + k_of[0]], ring_edge[3] = half(e, ring[3]);
        out.closed[nv + e] = 0;
        continue;
      }
      // Closed: the other face's three follow (it runs e the other way, so its first is a_k).
      // The ring starts at m's wedge in its lowest fine face: in the lower coarse face (the
      // first: edge_faces rows are sorted) at slot k, corner triangle k, whose next is m_{k-1},
      // unless k = 2, when corner triangle 0 is lower and its next is a_{k+1}.
      const std::size_t start = k_of[0] == 2 ? 0 : 2;
      for (std::size_t j = 0; j < 6; ++j) ring[j] = nb[(start + j) % 6], ring_edge[j] = ed[(start + j) % 6];
      out.closed[nv + e] = 1;
    }
  });
  return out;
}

bool all_distinct(std::span<const std::uint32_t> vs, std::uint32_t n) {
  table.begin(n);
  for (std::uint32_t v : vs) {
    if (table.has(v)) return false;
    table.mark(v);
  }
  return true;
}

LocalOrder local_order(const TriRings& r, std::span<const std::uint32_t> seeds,
                       std::span<const std::uint32_t> seed_start, int radius) {
  LocalOrder o;
  local_order(r, seeds, seed_start, radius, o);
  return o;
}

namespace {

// An order holding the seeds only (labels 0.., distance 0), the label table started with them.
void start_order(const TriRings& r, std::span<const std::uint32_t> seeds, std::span<const std::uint32_t> seed_start,
                 LocalOrder& o) {
  o.vertex.clear();
  o.dist.clear();
  o.start.clear();
  o.fan0.clear();
  table.begin(static_cast<std::uint32_t>(r.closed.size()));
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    table.set(seeds[i], static_cast<std::uint32_t>(o.vertex.size()));
    o.vertex.push_back(seeds[i]);
    o.dist.push_back(0);
    o.start.push_back(seed_start[i]);
    o.fan0.push_back(UINT32_MAX);
  }
}

// The walk every order takes (tri_local.h): the seeds labelled, then each label's fan walked
// from where it was reached, in label order, a neighbour labelled when first met by a label
// closer than `radius`. `on_label(u, d, n)` sees each label (vertex u at distance d, valence n)
// in order, before its fan; with kEntries every label's fan is read, also at `radius`, and
// `on_entry(x's label or UINT32_MAX beyond, labelled just now, the fan slot)` sees each entry.
template <bool kEntries, class OnLabel, class OnEntry>
void walk_order(const TriRings& r, std::span<const std::uint32_t> seeds, std::span<const std::uint32_t> seed_start, int radius,
                LocalOrder& o, OnLabel&& on_label, OnEntry&& on_entry) {
  start_order(r, seeds, seed_start, o);
  const std::uint32_t* const items = r.ring.items.data();
  const std::uint32_t* const offsets = r.ring.offsets.data();
  // Label order is breadth first, so every vertex within `radius` is labelled before the first
  // one at `radius` is walked: a neighbour without a label when it is read lies beyond.
  for (std::size_t l = 0; l < o.vertex.size(); ++l) {
    const std::uint32_t u = o.vertex[l];
    const std::uint8_t d = o.dist[l];
    const bool walk = d < radius;
    if (!kEntries && !walk) continue;
    const std::uint32_t begin = offsets[u], n = offsets[u + 1] - begin;
    on_label(u, d, n);
    if (n == 0) continue;
    const std::uint32_t i0 = fan_index(r, u, o.start[l]);
    if (walk) o.fan0[l] = i0;
    // The fan from i0 round to i0 - 1, without a modulo per neighbour.
    for (std::uint32_t k = 0, i = i0; k < n; ++k, i = i + 1 == n ? 0 : i + 1) {
      const std::uint32_t x = items[begin + i];
      std::uint32_t lx = table.get(x);
      const bool fresh = lx == UINT32_MAX && walk;
      if (fresh) {
        lx = static_cast<std::uint32_t>(o.vertex.size());
        table.set(x, lx);
        o.vertex.push_back(x);
        o.dist.push_back(static_cast<std::uint8_t>(d + 1));
        o.start.push_back(u);
        o.fan0.push_back(UINT32_MAX);
      }
      if constexpr (kEntries) on_entry(lx, fresh, begin + i);
    }
  }
}

}  // namespace

void local_order(const TriRings& r, std::span<const std::uint32_t> seeds, std::span<const std::uint32_t> seed_start,
                 int radius, LocalOrder& o) {
  walk_order<false>(r, seeds, seed_start, radius, o, [](std::uint32_t, std::uint8_t, std::uint32_t) {},
                    [](std::uint32_t, bool, std::uint32_t) {});
}

namespace {

// A signature's numbers are 16-bit when every one fits (nearly always), else 32-bit, after a
// byte that says which: 'h' or 'w'.
template <class T>
void write_signature(const Complex& c, const TriRings& r, const LocalOrder& o, int radius, std::size_t count,
                     std::string& out) {
  thread_local std::vector<T> buffer;  // reused: no allocation per signature
  if (buffer.size() < count) buffer.resize(count);
  // Plain pointers in the loop: the table's and the buffer's are thread-locals.
  T* w = buffer.data();
  const EpochTable::Slot* const slot = table.slot.data();
  const std::uint32_t epoch = table.epoch;
  const std::uint32_t* const items = r.ring.items.data();
  const std::uint32_t* const edges = r.ring_edge.items.data();
  for (std::uint32_t l = 0; l < o.vertex.size(); ++l) {
    if (o.dist[l] > radius) continue;
    const std::uint32_t u = o.vertex[l];
    const std::uint32_t begin = r.ring.offsets[u], n = r.ring.offsets[u + 1] - begin;
    *w++ = static_cast<T>(-1000 - o.dist[l]);
    *w++ = static_cast<T>(r.closed[u]);
    *w++ = static_cast<T>(n);
    *w++ = static_cast<T>(c.vertex_dim.empty() ? 2 : c.vertex_dim[u]);
    if (n == 0) continue;
    const std::uint32_t i0 = l < o.fan0.size() && o.fan0[l] != UINT32_MAX ? o.fan0[l] : fan_index(r, u, o.start[l]);
    for (std::uint32_t k = 0, i = i0; k < n; ++k, i = i + 1 == n ? 0 : i + 1) {
      const std::uint32_t x = items[begin + i];
      *w++ = slot[x].stamp == epoch ? static_cast<T>(slot[x].value) : T(-1);
      *w++ = static_cast<T>(c.edge_dim.empty() ? 2 : c.edge_dim[edges[begin + i]]);
    }
  }
  out.resize(1 + count * sizeof(T));
  out[0] = sizeof(T) == sizeof(std::int16_t) ? 'h' : 'w';
  std::memcpy(out.data() + 1, buffer.data(), count * sizeof(T));
}

}  // namespace

std::string local_signature(const Complex& c, const TriRings& r, const LocalOrder& o, int radius) {
  table.begin(c.num_vertices);
  std::size_t count = 0;  // 4 numbers per label and 2 per fan entry
  std::uint32_t labels = 0, max_valence = 0;
  for (std::uint32_t l = 0; l < o.vertex.size(); ++l)
    if (o.dist[l] <= radius) {
      table.set(o.vertex[l], l);
      ++labels;
      max_valence = std::max(max_valence, r.ring.size(o.vertex[l]));
      count += 4 + 2 * std::size_t(r.ring.size(o.vertex[l]));
    }
  std::string out;
  if (labels <= std::uint32_t(INT16_MAX) + 1 && max_valence <= INT16_MAX) write_signature<std::int16_t>(c, r, o, radius, count, out);
  else write_signature<std::int32_t>(c, r, o, radius, count, out);
  return out;
}

namespace {

thread_local std::vector<std::int16_t> narrow_buffer;  // reused by local_order_and_signature

}  // namespace

void local_order_and_signature(const Complex& c, const TriRings& r, std::span<const std::uint32_t> seeds,
                               std::span<const std::uint32_t> seed_start, int radius, LocalOrder& o, std::string& out) {
  // Written straight as 16-bit numbers (every one fits unless a valence or a label passes
  // 32767); otherwise the order is finished here and local_signature writes the 32-bit form.
  std::vector<std::int16_t>& s = narrow_buffer;
  std::size_t used = 0;
  std::int16_t* w = nullptr;
  bool narrow = true;
  const std::uint32_t* const edges = r.ring_edge.items.data();
  const std::uint8_t* const edge_dim = c.edge_dim.empty() ? nullptr : c.edge_dim.data();
  walk_order<true>(
      r, seeds, seed_start, radius, o,
      [&](std::uint32_t u, std::uint8_t d, std::uint32_t n) {
        narrow &= n <= INT16_MAX;
        if (s.size() < used + 4 + 2 * std::size_t(n)) s.resize(2 * (used + 4 + 2 * std::size_t(n)));
        w = s.data() + used;
        *w++ = static_cast<std::int16_t>(-1000 - d);
        *w++ = static_cast<std::int16_t>(r.closed[u]);
        *w++ = static_cast<std::int16_t>(n);
        *w++ = static_cast<std::int16_t>(c.vertex_dim.empty() ? 2 : c.vertex_dim[u]);
        used += 4 + 2 * std::size_t(n);
      },
      [&](std::uint32_t lx, bool, std::uint32_t slot) {
        narrow &= lx == UINT32_MAX || lx <= INT16_MAX;
        *w++ = lx == UINT32_MAX ? std::int16_t(-1) : static_cast<std::int16_t>(lx);
        *w++ = static_cast<std::int16_t>(edge_dim ? edge_dim[edges[slot]] : 2);
      });
  if (!narrow) {
    out = local_signature(c, r, o, radius);
    return;
  }
  out.resize(1 + used * sizeof(std::int16_t));
  out[0] = 'h';
  std::memcpy(out.data() + 1, s.data(), used * sizeof(std::int16_t));
}

namespace {

thread_local std::vector<char> key_buffer;  // reused by local_order_and_key

// Appends v in 7-bit groups, low first, the high bit set on every byte but the last.
inline char* put_varint(char* w, std::uint64_t v) {
  while (v >= 0x80) {
    *w++ = static_cast<char>(v | 0x80);
    v >>= 7;
  }
  *w++ = static_cast<char>(v);
  return w;
}

}  // namespace

void local_order_and_key(const Complex& c, const TriRings& r, std::span<const std::uint32_t> seeds,
                         std::span<const std::uint32_t> seed_start, int radius, LocalOrder& o, std::string& out) {
  std::vector<char>& buf = key_buffer;
  char* w = buf.data();
  const std::uint32_t* const edges = r.ring_edge.items.data();
  const std::uint8_t* const edge_dim = c.edge_dim.empty() ? nullptr : c.edge_dim.data();
  const std::uint8_t* const vertex_dim = c.vertex_dim.empty() ? nullptr : c.vertex_dim.data();
  // What it writes is decodable, so equal keys are equal signatures (see the header).
  walk_order<true>(
      r, seeds, seed_start, radius, o,
      [&](std::uint32_t u, std::uint8_t d, std::uint32_t n) {
        const auto used = static_cast<std::size_t>(w - buf.data());
        const std::size_t most = 1 + 10 + 10 * std::size_t(n);  // varints of at most 64 bits
        if (buf.size() < used + most) buf.resize(2 * (used + most));
        w = buf.data() + used;
        *w++ = static_cast<char>(d);
        w = put_varint(w, (std::uint64_t(n) << 1 | r.closed[u]) << 2 | (vertex_dim ? vertex_dim[u] : 2));
      },
      [&](std::uint32_t lx, bool fresh, std::uint32_t slot) {
        // 0: labelled here (the next label), 1: beyond, else its label + 2.
        const std::uint64_t token = fresh ? 0 : lx == UINT32_MAX ? 1 : std::uint64_t(lx) + 2;
        w = put_varint(w, token << 2 | (edge_dim ? edge_dim[edges[slot]] : 2));
      });
  out.assign(buf.data(), static_cast<std::size_t>(w - buf.data()));
}

std::size_t SignatureHash::operator()(std::string_view s) const {
  // Four independent lanes of 8 bytes (one chain of multiplies was latency-bound: a butterfly
  // level hashes thousands of 3 kB signatures), folded into one.
  std::uint64_t lane[4] = {0x9e3779b97f4a7c15ull ^ s.size(), 0xc2b2ae3d27d4eb4full, 0x165667b19e3779f9ull,
                           0x27d4eb2f165667c5ull};
  std::size_t i = 0;
  for (; i + 32 <= s.size(); i += 32)
    for (int k = 0; k < 4; ++k) {
      std::uint64_t w;
      std::memcpy(&w, s.data() + i + 8 * k, 8);
      lane[k] = (lane[k] ^ w) * 0xff51afd7ed558ccdull;
      lane[k] ^= lane[k] >> 29;
    }
  std::uint64_t h = lane[0];
  for (int k = 1; k < 4; ++k) {
    h = (h ^ lane[k]) * 0xff51afd7ed558ccdull;
    h ^= h >> 29;
  }
  for (; i + 8 <= s.size(); i += 8) {
    std::uint64_t w;
    std::memcpy(&w, s.data() + i, 8);
    h = (h ^ w) * 0xff51afd7ed558ccdull;
    h ^= h >> 29;
  }
  for (; i < s.size(); ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 0x100000001b3ull;
  return static_cast<std::size_t>(h ^ (h >> 32));
}

namespace {

// Gives each extra arc of faces around a patch vertex its own copy of the vertex (appended after
// the labels; `source` maps every patch vertex to its label). Only rim vertices (at the order's
// radius) can have several arcs: closer ones carry their whole fan. Where the surface meets
// itself within the radius (a thin part, a coarse mesh), its rim touches itself there; split,
// the patch is a manifold cover of the neighbourhood, the same as the surface everywhere a
// subdivided step reads it.
void split_rim_arcs(Csr& faces, const LocalOrder& o, std::vector<std::uint32_t>& source) {
  const std::uint32_t num_labels = static_cast<std::uint32_t>(o.vertex.size());
  source.resize(num_labels);
  for (std::uint32_t l = 0; l < num_labels; ++l) source[l] = l;
  if (num_labels == 0) return;
  const std::uint8_t rim = *std::max_element(o.dist.begin(), o.dist.end());
  // Rim labels' corner slots, grouped by label (the rim's labels are the last: breadth first),
  // slots increasing; in per-thread scratch, as face types make millions of patches.
  const std::uint32_t first_rim = rim == 0 ? 0 : labels_within(o, rim - 1);
  thread_local std::vector<std::uint32_t> at, slots, parent, copy;
  thread_local std::vector<std::pair<std::uint32_t, std::uint32_t>> by_neighbour;  // (neighbour, corner index)
  at.assign(num_labels - first_rim + 1, 0);
  for (std::uint32_t x : faces.items)
    if (x >= first_rim) ++at[x - first_rim + 1];
  for (std::size_t i = 1; i < at.size(); ++i) at[i] += at[i - 1];
  slots.resize(at.back());
  for (std::uint32_t s = 0; s < faces.items.size(); ++s)
    if (faces.items[s] >= first_rim) slots[at[faces.items[s] - first_rim]++] = s;
  // (`at` now holds each group's end)
  const auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::uint32_t l = first_rim; l < num_labels; ++l) {
    const std::uint32_t begin = l == first_rim ? 0 : at[l - first_rim - 1];
    const std::span<const std::uint32_t> cs(slots.data() + begin, at[l - first_rim] - begin);
    if (cs.size() < 2) continue;
    // Two faces around l are in one arc when they share an edge (l, x): the same neighbour.
    parent.resize(cs.size());
    for (std::uint32_t i = 0; i < cs.size(); ++i) parent[i] = i;
    by_neighbour.clear();
    for (std::uint32_t i = 0; i < cs.size(); ++i) {
      const std::uint32_t f = cs[i] / 3, k = cs[i] % 3;
      for (std::uint32_t d : {1u, 2u}) {
        const std::uint32_t x = faces.items[3 * f + (k + d) % 3];
        const auto it = std::find_if(by_neighbour.begin(), by_neighbour.end(), [&](const auto& p) { return p.first == x; });
        if (it == by_neighbour.end()) by_neighbour.emplace_back(x, i);
        else parent[find(i)] = find(it->second);
      }
    }
    // The arc of the first corner keeps the label; every other arc gets a copy.
    copy.assign(cs.size(), UINT32_MAX);
    const std::uint32_t first_arc = find(0);
    for (std::uint32_t i = 0; i < cs.size(); ++i) {
      const std::uint32_t arc = find(i);
      if (arc == first_arc) continue;
      if (copy[arc] == UINT32_MAX) {
        copy[arc] = static_cast<std::uint32_t>(source.size());
        source.push_back(l);
      }
      faces.items[cs[i]] = copy[arc];
    }
  }
}

}  // namespace

Complex local_patch(const Complex& c, const TriRings& r, const LocalOrder& o) {
  table.begin(c.num_vertices);  // vertex -> label
  for (std::uint32_t l = 0; l < o.vertex.size(); ++l) table.set(o.vertex[l], l);
  thread_local std::vector<std::array<std::uint32_t, 3>> tris;
  tris.clear();
  for (std::uint32_t l = 0; l < o.vertex.size(); ++l) {
    // The faces around v are (v, ring[i], ring[i + 1]), the way round they run.
    const auto ring = r.ring.row(o.vertex[l]);
    const std::size_t n = ring.size(), faces = n == 0 ? 0 : r.closed[o.vertex[l]] ? n : n - 1;
    for (std::size_t i = 0; i < faces; ++i) {
      std::array<std::uint32_t, 3> tri{l, table.get(ring[i]), table.get(ring[(i + 1) % n])};
      // Each face once: from its lowest label's corner (it is in every corner's ring).
      if (tri[1] == UINT32_MAX || tri[2] == UINT32_MAX || std::min(tri[1], tri[2]) < l) continue;
      // Lowest label first (the same way round), faces sorted: the patch, its subdivision and
      // its stencils depend on the labelled neighbourhood only, not on the mesh's numbering, so
      // every face of a type gives it the same matrices, bit for bit.
      tris.push_back(tri);
    }
  }
  std::sort(tris.begin(), tris.end());
  Csr faces;
  faces.items.reserve(3 * tris.size());
  faces.offsets.reserve(tris.size() + 1);
  for (const auto& tri : tris) {
    faces.items.insert(faces.items.end(), tri.begin(), tri.end());
    faces.offsets.push_back(static_cast<std::uint32_t>(faces.items.size()));
  }
  thread_local std::vector<std::uint32_t> source;
  split_rim_arcs(faces, o, source);
  Complex p = complex_from_polygons(static_cast<std::uint32_t>(source.size()), faces);
  // Original dims: the patch's own rim is not a feature of the surface.
  for (std::uint32_t v = 0; v < source.size(); ++v) p.vertex_dim[v] = c.vertex_dim[o.vertex[source[v]]];
  for (std::uint32_t e = 0; e < p.num_edges(); ++e) {
    const std::uint32_t a = o.vertex[source[p.edge_verts[2 * e]]], b = o.vertex[source[p.edge_verts[2 * e + 1]]];
    const auto ring = r.ring.row(a);
    for (std::size_t i = 0; i < ring.size(); ++i)
      if (ring[i] == b) p.edge_dim[e] = c.edge_dim[r.ring_edge.row(a)[i]];
  }
  return p;
}

}  // namespace sublift
