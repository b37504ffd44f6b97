#include "core/complex/complex_build.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "core/base/edge_key.h"
#include "core/base/errors.h"
#include "core/base/text_lines.h"
#include "core/complex/face_loop.h"

namespace sublift {
namespace {

// Finds or creates edges while faces are added; keeps first-seen orientation. Open addressing
// in one flat array: a node-based map allocated once per edge, which dominated building the
// many small patches of the triangle schemes' face types (perf).
class EdgeTable {
 public:
  /// `expected`: about how many edges will be made (the table grows past it).
  EdgeTable(Complex& c, std::size_t expected) : c_(c) { rehash(std::max<std::size_t>(16, 2 * expected)); }
  std::uint32_t get(std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = edge_key(a, b);
    for (std::size_t i = slot_of(key);; i = (i + 1) & mask_) {
      if (slots_[i].key == key) return slots_[i].edge;
      if (slots_[i].key != kEmpty) continue;
      const std::uint32_t e = c_.num_edges();
      slots_[i] = {key, e};
      c_.edge_verts.push_back(a);
      c_.edge_verts.push_back(b);
      if (2 * (std::size_t(e) + 1) > slots_.size()) rehash(2 * slots_.size());
      return e;
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = UINT64_MAX;  // no edge has it: vertex numbers are below UINT32_MAX
  struct Slot {
    std::uint64_t key = kEmpty;
    std::uint32_t edge = 0;
  };
  std::size_t slot_of(std::uint64_t key) const { return static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ull) >> shift_); }
  void rehash(std::size_t at_least) {
    std::size_t n = 16;
    int bits = 4;
    while (n < at_least) {
      n *= 2;
      ++bits;
    }
    std::vector<Slot> old(n);
    old.swap(slots_);
    mask_ = n - 1;
    shift_ = 64 - bits;
    for (const Slot& s : old)
      if (s.key != kEmpty) {
        std::size_t i = slot_of(s.key);
        while (slots_[i].key != kEmpty) i = (i + 1) & mask_;
        slots_[i] = s;
      }
  }
  Complex& c_;
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  int shift_ = 64;
};

// `face`: the input's number for the loop, named in errors (the message is made only then).
void add_face_loop(Complex& c, EdgeTable& edges, std::span<const std::uint32_t> loop, std::size_t face) {
  const auto what = [&] { return "face " + std::to_string(face); };
  if (loop.size() < 3) throw TopologyError(what() + " has fewer than 3 vertices");
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (loop[i] >= c.num_vertices) throw TopologyError(what() + " names missing vertex " + std::to_string(loop[i]));
    for (std::size_t j = i + 1; j < loop.size(); ++j)
      if (loop[i] == loop[j]) throw TopologyError(what() + " repeats vertex " + std::to_string(loop[i]));
  }
  c.faces.items.insert(c.faces.items.end(), loop.begin(), loop.end());
  c.faces.offsets.push_back(static_cast<std::uint32_t>(c.faces.items.size()));
  for (std::size_t i = 0; i < loop.size(); ++i)
    c.face_edges.items.push_back(edges.get(loop[i], loop[(i + 1) % loop.size()]));
  c.face_edges.offsets.push_back(static_cast<std::uint32_t>(c.face_edges.items.size()));
}

}  // namespace

std::uint8_t untagged_face_dim(const Complex& c, std::uint32_t f) {
  // In a volume, boundary and non-manifold faces (not between exactly two cells) are surfaces.
  return c.dim == 3 && c.face_cells.size(f) == 2 ? 3 : 2;
}

std::uint8_t untagged_edge_dim(const Complex& c, std::uint32_t e) {
  // Curve features where the surface an edge lies in ends or branches.
  if (c.dim == 1) return 1;
  if (c.dim == 2) return c.edge_faces.size(e) == 2 ? 2 : 1;
  int surface_faces = 0;
  for (std::uint32_t f : c.edge_faces.row(e)) surface_faces += c.face_dim[f] == 2;
  return surface_faces == 0 ? 3 : surface_faces == 2 ? 2 : 1;
}

std::uint8_t untagged_vertex_dim(const Complex& c, std::uint32_t v) {
  // Two curve edges put a vertex on the curve, three or more make a cusp, one alone is a dart
  // (curve end inside a surface: the vertex stays smooth) or, with nothing else around, the end
  // of an open curve (a cusp).
  int curve_edges = 0;
  std::uint8_t higher = 0;  // lowest dim >= 2 among incident edges (0 if none)
  for (std::uint32_t e : c.vertex_edges.row(v)) {
    if (c.edge_dim[e] == 1) ++curve_edges;
    else if (higher == 0 || c.edge_dim[e] < higher) higher = c.edge_dim[e];
  }
  return curve_edges >= 3 ? 0 : curve_edges == 2 ? 1 : higher;
}

Complex inherit_sharpness(const Complex& p, Complex c, bool adjacency) {
  if (p.edge_sharpness.empty() && p.vertex_sharpness.empty()) {
    if (adjacency) build_adjacency(c);
    return c;
  }
  const auto less = [](float s) { return s > 1.0f ? s - 1.0f : 0.0f; };  // inf stays inf
  const std::uint32_t ne = p.num_edges(), nv = p.num_vertices;
  c.edge_sharpness.assign(c.edge_dim.size(), 0.0f);
  for (std::uint32_t e = 0; e < ne && e < p.edge_sharpness.size(); ++e) c.edge_sharpness[2 * e] = c.edge_sharpness[2 * e + 1] = less(p.edge_sharpness[e]);
  c.vertex_sharpness.assign(c.num_vertices, 0.0f);
  for (std::uint32_t v = 0; v < nv && v < p.vertex_sharpness.size(); ++v) c.vertex_sharpness[v] = less(p.vertex_sharpness[v]);
  build_adjacency(c);
  apply_sharpness(c);
  if (adjacency) return c;
  Complex bare;  // what the caller asked for: the derived rows left empty
  bare.dim = c.dim;
  bare.num_vertices = c.num_vertices;
  bare.edge_verts = std::move(c.edge_verts);
  bare.faces = std::move(c.faces);
  bare.face_edges = std::move(c.face_edges);
  bare.cell_faces = std::move(c.cell_faces);
  bare.vertex_dim = std::move(c.vertex_dim);
  bare.edge_dim = std::move(c.edge_dim);
  bare.face_dim = std::move(c.face_dim);
  bare.edge_sharpness = std::move(c.edge_sharpness);
  bare.vertex_sharpness = std::move(c.vertex_sharpness);
  return bare;
}

void apply_sharpness(Complex& c) {
  if (c.edge_sharpness.empty() && c.vertex_sharpness.empty()) return;
  c.edge_sharpness.resize(c.num_edges(), 0.0f);
  c.vertex_sharpness.resize(c.num_vertices, 0.0f);
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) c.edge_dim[e] = c.edge_sharpness[e] >= 1.0f ? 1 : untagged_edge_dim(c, e);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) c.vertex_dim[v] = c.vertex_sharpness[v] >= 1.0f ? 0 : untagged_vertex_dim(c, v);
}

void assign_feature_dims(Complex& c, const FeatureTags& tags) {
  build_adjacency(c);
  c.edge_sharpness.clear();  // from these tags alone
  c.vertex_sharpness.clear();
  std::vector<char> crease(c.num_edges(), 0);
  const bool semi = std::any_of(tags.crease_sharpness.begin(), tags.crease_sharpness.end(), [](float s) { return std::isfinite(s); }) ||
                    std::any_of(tags.corner_sharpness.begin(), tags.corner_sharpness.end(), [](float s) { return std::isfinite(s); });
  if (semi && c.dim == 2) {  // per level (lattices and curves keep every tag sharp)
    c.edge_sharpness.assign(c.num_edges(), 0.0f);
    c.vertex_sharpness.assign(c.num_vertices, 0.0f);
  }
  std::size_t tag = 0;
  for (auto [a, b] : tags.crease_edges) {
    const float s = tag < tags.crease_sharpness.size() ? tags.crease_sharpness[tag] : INFINITY;
    ++tag;
    std::uint32_t found = UINT32_MAX;
    if (a < c.num_vertices && b < c.num_vertices)
      for (std::uint32_t e : c.vertex_edges.row(a))
        if (c.edge_verts[2 * e] == b || c.edge_verts[2 * e + 1] == b) found = e;
    if (found == UINT32_MAX)
      throw TopologyError("crease tag names vertices " + std::to_string(a) + " and " + std::to_string(b) +
                          ", which share no edge");
    if (!c.edge_sharpness.empty()) c.edge_sharpness[found] = std::max(c.edge_sharpness[found], s);
    crease[found] = !c.edge_sharpness.empty() ? c.edge_sharpness[found] >= 1.0f : 1;
  }
  std::vector<char> feature_face(c.num_faces(), 0);
  if (!tags.feature_faces.empty()) {
    std::map<std::vector<std::uint32_t>, std::uint32_t> face_of;
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) face_of[canonical_loop(c.faces.row(f))] = f;
    for (const auto& loop : tags.feature_faces) {
      auto it = face_of.find(canonical_loop(loop));
      if (it == face_of.end()) throw TopologyError("feature-face tag names a vertex loop that is no face of the lattice");
      feature_face[it->second] = 1;
    }
  }
  // Each class from topology and the class below it, lowered by tags (docs/features.md).
  c.face_dim.resize(c.num_faces());
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) c.face_dim[f] = feature_face[f] ? 2 : untagged_face_dim(c, f);
  c.edge_dim.resize(c.num_edges());
  for (std::uint32_t e = 0; e < c.num_edges(); ++e) c.edge_dim[e] = crease[e] ? 1 : untagged_edge_dim(c, e);
  c.vertex_dim.resize(c.num_vertices);
  for (std::uint32_t v = 0; v < c.num_vertices; ++v) c.vertex_dim[v] = untagged_vertex_dim(c, v);
  for (std::size_t k = 0; k < tags.corner_vertices.size(); ++k) {
    const std::uint32_t v = tags.corner_vertices[k];
    if (v >= c.num_vertices) throw TopologyError("corner tag names missing vertex " + std::to_string(v));
    const float s = k < tags.corner_sharpness.size() ? tags.corner_sharpness[k] : INFINITY;
    if (!c.vertex_sharpness.empty()) c.vertex_sharpness[v] = std::max(c.vertex_sharpness[v], s);
    if (c.vertex_sharpness.empty() || c.vertex_sharpness[v] >= 1.0f) c.vertex_dim[v] = 0;
  }
}

FeatureTags feature_tags_from_obj(const std::vector<MeshTag>& tags, ImportReport& report) {
  FeatureTags out;
  for (const MeshTag& t : tags) {
    const bool crease = t.name == "crease", corner = t.name == "corner";
    if (!crease && !corner) {
      report.add("tag '" + printable(t.name) + "' ignored (only crease and corner are used)", t.line);
      continue;
    }
    const std::size_t n = t.ints.size();
    const std::size_t items = crease ? (n >= 2 ? n - 1 : 0) : n;
    if (items == 0 || (t.floats.size() != 1 && t.floats.size() != items)) {
      report.add(t.name + " tag ignored: needs vertices and one sharpness or one per item", t.line);
      continue;
    }
    for (std::size_t i = 0; i < items; ++i) {
      const double s = t.floats.size() == 1 ? t.floats[0] : t.floats[i];
      if (!(s > 0)) {
        report.add(t.name + " with sharpness 0 ignored", t.line);
        continue;
      }
      // OpenSubdiv: 10 and above is infinitely sharp; below, the feature softens after s levels
      // (docs/features.md). Its blend of a fractional part is not modelled: said once per tag.
      const float sharp = s >= 10.0 ? INFINITY : float(s);
      if (s < 10.0 && s != std::floor(s))
        report.add("semi-sharp " + t.name + " tags with a fractional sharpness: sharp for floor(s) levels, the fraction not blended",
                   t.line);
      if (s < 10.0)
        report.add("semi-sharp " + t.name + " tags: sharp for s levels (sqrt2: at every level)",
                   t.line);
      if (crease) {
        out.crease_edges.emplace_back(static_cast<std::uint32_t>(t.ints[i]), static_cast<std::uint32_t>(t.ints[i + 1]));
        out.crease_sharpness.push_back(sharp);
      } else {
        out.corner_vertices.push_back(static_cast<std::uint32_t>(t.ints[i]));
        out.corner_sharpness.push_back(sharp);
      }
    }
  }
  return out;
}

Complex complex_from_polygons(std::uint32_t num_vertices, const Csr& faces, const FeatureTags& tags) {
  Complex c;
  c.dim = 2;
  c.num_vertices = num_vertices;
  EdgeTable edges(c, faces.items.size() / 2 + 1);  // a closed surface has one edge per two corners
  c.edge_verts.reserve(faces.items.size());
  for (std::size_t f = 0; f < faces.rows(); ++f) add_face_loop(c, edges, faces.row(f), f);
  if (c.num_faces() == 0) throw TopologyError("a surface needs at least one face");
  assign_feature_dims(c, tags);
  return c;
}

Complex complex_from_surface_mesh(const SurfaceMesh& mesh, ImportReport* report) {
  ImportReport local;
  const FeatureTags tags = feature_tags_from_obj(mesh.tags, report ? *report : local);
  Csr faces;
  faces.offsets = mesh.face_offsets;
  faces.items = mesh.face_indices;
  return complex_from_polygons(static_cast<std::uint32_t>(mesh.num_vertices()), faces, tags);
}

Complex complex_from_polylines(std::uint32_t num_vertices, const Csr& polylines, const FeatureTags& tags) {
  Complex c;
  c.dim = 1;
  c.num_vertices = num_vertices;
  EdgeTable edges(c, polylines.items.size());
  for (std::size_t l = 0; l < polylines.rows(); ++l) {
    const auto p = polylines.row(l);
    if (p.size() < 2) throw TopologyError("polyline " + std::to_string(l) + " has fewer than 2 vertices");
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      if (p[i] >= num_vertices || p[i + 1] >= num_vertices)
        throw TopologyError("polyline " + std::to_string(l) + " names a missing vertex");
      if (p[i] == p[i + 1]) throw TopologyError("polyline " + std::to_string(l) + " repeats vertex " + std::to_string(p[i]));
      const std::uint32_t before = c.num_edges();
      edges.get(p[i], p[i + 1]);
      if (c.num_edges() == before)
        throw TopologyError("polyline " + std::to_string(l) + " reuses the segment " + std::to_string(p[i]) + "-" +
                            std::to_string(p[i + 1]));
    }
  }
  if (c.num_edges() == 0) throw TopologyError("a curve needs at least one segment");
  assign_feature_dims(c, tags);
  return c;
}

Complex complex_from_cells(std::uint32_t num_vertices, const Csr& face_loops, const Csr& cell_faces,
                           const FeatureTags& tags) {
  Complex c;
  c.dim = 3;
  c.num_vertices = num_vertices;
  EdgeTable edges(c, face_loops.items.size() / 2 + 1);
  std::map<std::vector<std::uint32_t>, std::uint32_t> face_of;
  std::vector<std::uint32_t> loop_face(face_loops.rows());
  for (std::size_t l = 0; l < face_loops.rows(); ++l) {
    const auto loop = face_loops.row(l);
    if (loop.size() < 3) throw TopologyError("face " + std::to_string(l) + " has fewer than 3 vertices");
    auto key = canonical_loop(loop);
    auto [it, inserted] = face_of.try_emplace(std::move(key), c.num_faces());
    if (inserted) add_face_loop(c, edges, loop, l);
    loop_face[l] = it->second;
  }
  for (std::size_t k = 0; k < cell_faces.rows(); ++k) {
    const std::string name = "cell " + std::to_string(k);
    std::vector<std::uint32_t> fs;
    for (std::uint32_t l : cell_faces.row(k)) {
      if (l >= face_loops.rows()) throw TopologyError(name + " names missing face " + std::to_string(l));
      fs.push_back(loop_face[l]);
    }
    std::vector<std::uint32_t> sorted = fs;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw TopologyError(name + " lists the same face twice");
    if (fs.size() < 4) throw TopologyError(name + " has fewer than 4 faces");
    std::map<std::uint32_t, int> uses;
    for (std::uint32_t f : fs)
      for (std::uint32_t e : c.face_edges.row(f)) ++uses[e];
    for (auto [e, n] : uses)
      if (n != 2)
        throw TopologyError(name + " is not closed: edge " + std::to_string(c.edge_verts[2 * e]) + "-" +
                            std::to_string(c.edge_verts[2 * e + 1]) + " is used by " + std::to_string(n) +
                            " of its faces (a closed cell uses each edge twice)");
    c.cell_faces.items.insert(c.cell_faces.items.end(), fs.begin(), fs.end());
    c.cell_faces.offsets.push_back(static_cast<std::uint32_t>(c.cell_faces.items.size()));
  }
  if (c.num_cells() == 0) throw TopologyError("a lattice needs at least one cell");
  assign_feature_dims(c, tags);
  return c;
}

}  // namespace sublift
