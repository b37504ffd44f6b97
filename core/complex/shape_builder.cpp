#include "core/complex/shape_builder.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_set>

#include "core/base/edge_key.h"
#include "core/complex/complex_build.h"
#include "core/base/errors.h"
#include "core/complex/face_loop.h"

namespace sublift {

std::size_t ShapeBuilder::add_loop(std::span<const std::int64_t> loop, std::size_t line) {
  loop_items_.insert(loop_items_.end(), loop.begin(), loop.end());
  loop_offsets_.push_back(loop_items_.size());
  loop_lines_.push_back(line);
  return loop_lines_.size() - 1;
}

void ShapeBuilder::begin_cell(std::size_t line, std::string label) {
  cells_.push_back({loop_lines_.size(), loop_lines_.size(), line, std::move(label)});
}

void ShapeBuilder::add_cell_face(std::span<const std::int64_t> loop, std::size_t line) {
  add_loop(loop, line);
  cells_.back().end_loop = loop_lines_.size();
}

void ShapeBuilder::add_polygon(std::span<const std::int64_t> loop, std::size_t line, std::string label) {
  const std::size_t i = add_loop(loop, line);
  polygons_.push_back({i, i + 1, line, std::move(label)});
}

void ShapeBuilder::add_polyline(std::span<const std::int64_t> chain, std::size_t line, std::string label) {
  const std::size_t i = add_loop(chain, line);
  polylines_.push_back({i, i + 1, line, std::move(label)});
}

void ShapeBuilder::add_corner(std::int64_t v, std::size_t line) {
  tag_items_.push_back(v);
  corners_.push_back({tag_items_.size() - 1, tag_items_.size(), line});
}

void ShapeBuilder::add_crease(std::span<const std::int64_t> chain, std::size_t line) {
  const std::size_t first = tag_items_.size();
  tag_items_.insert(tag_items_.end(), chain.begin(), chain.end());
  creases_.push_back({first, tag_items_.size(), line});
}

void ShapeBuilder::add_feature_face(std::span<const std::int64_t> loop, std::size_t line) {
  const std::size_t first = tag_items_.size();
  tag_items_.insert(tag_items_.end(), loop.begin(), loop.end());
  feature_faces_.push_back({first, tag_items_.size(), line});
}

void ShapeBuilder::build(const std::string& file, std::uint32_t nv, std::span<const std::size_t> vertex_lines,
                         TagPolicy policy, Shape& shape) const {
  auto loop = [&](std::size_t i) {
    return std::span<const std::int64_t>(loop_items_.data() + loop_offsets_[i], loop_offsets_[i + 1] - loop_offsets_[i]);
  };
  auto check_range = [&](std::span<const std::int64_t> items, std::size_t line, const std::string& what) {
    for (std::int64_t v : items)
      if (v < 0 || v >= static_cast<std::int64_t>(nv))
        throw InputError(file, line, what + " names vertex " + std::to_string(v) + ", but the vertices are 0.." +
                                         std::to_string(static_cast<std::int64_t>(nv) - 1) + " (0-based)");
  };
  // A polygon or cell face: at least 3 vertices, in range, none twice.
  auto check_polygon = [&](std::span<const std::int64_t> f, std::size_t line, const std::string& what) {
    if (f.size() < 3) throw InputError(file, line, what + " has fewer than 3 vertices");
    check_range(f, line, what);
    std::vector<std::int64_t> s(f.begin(), f.end());
    std::sort(s.begin(), s.end());
    if (auto it = std::adjacent_find(s.begin(), s.end()); it != s.end())
      throw InputError(file, line, what + " repeats vertex " + std::to_string(*it));
  };

  const int dim = !cells_.empty() ? 3 : !polygons_.empty() ? 2 : !polylines_.empty() ? 1 : 0;
  if (dim == 0) throw InputError(file, 0, nv == 0 ? "no vertices and no cells" : "no cells, polygons or polylines");

  // Edges and faces of the shape, for checking tags and (below) reported vertex use.
  std::unordered_set<std::uint64_t> edges;
  std::set<std::vector<std::uint32_t>> faces;
  std::vector<char> used(nv, 0);
  Csr loops, cells;
  if (dim == 3) {
    // A solid: no cell twice, no face between more than two cells (docs/file_formats.md).
    std::map<std::vector<std::uint32_t>, std::size_t> cell_with_vertices;
    struct FaceUse { std::size_t cell; bool forward; };  // forward: listed as its canonical loop runs
    std::map<std::vector<std::uint32_t>, std::vector<FaceUse>> face_uses;
    std::vector<std::size_t> misoriented;  // cells whose own faces disagree on orientation
    for (std::size_t ci = 0; ci < cells_.size(); ++ci) {
      const Element& c = cells_[ci];
      const std::size_t nf = c.end_loop - c.first_loop;
      std::map<std::uint64_t, int> uses;
      std::set<std::uint64_t> directed;  // a -> b edges of the faces as listed
      bool consistent = true;
      std::set<std::vector<std::uint32_t>> own;
      for (std::size_t i = c.first_loop; i < c.end_loop; ++i) {
        const auto f = loop(i);
        const std::size_t line = loop_lines_[i] ? loop_lines_[i] : c.line;
        check_polygon(f, line, c.label + ", face " + std::to_string(i - c.first_loop));
        if (!own.insert(canonical_loop(f)).second)
          throw InputError(file, line, c.label + " lists the same face twice (face " + std::to_string(i - c.first_loop) + ")");
        for (std::size_t k = 0; k < f.size(); ++k) {
          ++uses[edge_key(f[k], f[(k + 1) % f.size()])];
          if (!directed.insert(std::uint64_t(f[k]) << 32 | std::uint64_t(f[(k + 1) % f.size()])).second) consistent = false;
        }
        cells.items.push_back(static_cast<std::uint32_t>(loops.rows()));
        loops.items.insert(loops.items.end(), f.begin(), f.end());
        loops.offsets.push_back(static_cast<std::uint32_t>(loops.items.size()));
      }
      if (nf < 4) throw InputError(file, c.line, c.label + " has " + std::to_string(nf) + " faces (a closed cell needs at least 4)");
      for (auto [e, n] : uses)
        if (n != 2)
          throw InputError(file, c.line,
                           c.label + " is not closed: edge " + std::to_string(e >> 32) + "-" +
                               std::to_string(e & 0xffffffffu) + " is used by " + std::to_string(n) +
                               " of its faces (each edge of a closed cell belongs to exactly two of its faces)");
      cells.offsets.push_back(static_cast<std::uint32_t>(cells.items.size()));
      std::vector<std::uint32_t> vertices;
      for (std::size_t i = c.first_loop; i < c.end_loop; ++i) vertices.insert(vertices.end(), loop(i).begin(), loop(i).end());
      std::sort(vertices.begin(), vertices.end());
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      if (const auto [it, fresh] = cell_with_vertices.emplace(vertices, ci); !fresh) {
        const Element& first = cells_[it->second];
        throw InputError(file, c.line, c.label + " has the same vertices as " + first.label + " on line " +
                                           std::to_string(first.line) + ": a cell listed twice");
      }
      if (!consistent) misoriented.push_back(ci);
      for (std::size_t i = c.first_loop; i < c.end_loop; ++i) {
        const auto f = loop(i);
        std::vector<std::uint32_t> key = canonical_loop(f);
        const auto m = std::min_element(f.begin(), f.end()) - f.begin();
        const bool forward = f[static_cast<std::size_t>(m + 1) % f.size()] == key[1];
        std::vector<FaceUse>& users = face_uses[key];
        users.push_back({ci, forward});
        if (users.size() > 2) {
          std::string names, verts;
          for (std::uint32_t v : key) verts.append(verts.empty() ? "" : " ").append(std::to_string(v));
          for (const FaceUse& u : users)
            names.append(names.empty() ? "" : ", ").append(cells_[u.cell].label).append(" on line ").append(std::to_string(cells_[u.cell].line));
          throw InputError(file, c.line, "face " + verts + " is shared by " + std::to_string(users.size()) + " cells: " + names +
                                             " (a face of a solid bounds at most two cells)");
        }
      }
      for (auto [e, n] : uses) edges.insert(e);
      for (auto& f : own) faces.insert(f);
    }
    // Orientation is not kept (cells are oriented from their geometry where it matters,
    // cell_shapes.h), so faces listed against the others are a repair, not an error.
    std::vector<std::size_t> against_neighbour;  // consistent cells listing a shared face as their neighbour does
    for (const auto& [key, users] : face_uses)
      if (users.size() == 2 && users[0].forward == users[1].forward) {
        for (const FaceUse& u : users)
          if (!std::binary_search(misoriented.begin(), misoriented.end(), u.cell)) against_neighbour.push_back(u.cell);
      }
    std::sort(against_neighbour.begin(), against_neighbour.end());
    against_neighbour.erase(std::unique(against_neighbour.begin(), against_neighbour.end()), against_neighbour.end());
    auto warn_cells = [&](const std::vector<std::size_t>& which, const std::string& what) {
      if (which.empty()) return;
      ImportWarning w{what + ": ", which.size(), {}};
      for (std::size_t i = 0; i < which.size() && i < ImportReport::kMaxLines; ++i) {
        w.what += (i ? ", " : "") + cells_[which[i]].label;
        if (cells_[which[i]].line) w.first_lines.push_back(cells_[which[i]].line);
      }
      if (which.size() > ImportReport::kMaxLines) w.what += ", ...";
      shape.report.warnings.push_back(std::move(w));
    };
    warn_cells(misoriented, "cells whose faces are not consistently oriented (kept: Sublift orients cells from their geometry)");
    warn_cells(against_neighbour,
               "cells listing a shared face in the same direction as their neighbour (kept: Sublift orients cells from their geometry)");
  } else if (dim == 2) {
    for (const Element& p : polygons_) {
      const auto f = loop(p.first_loop);
      check_polygon(f, p.line, p.label);
      if (!faces.insert(canonical_loop(f)).second)
        throw InputError(file, p.line, p.label + " repeats an earlier polygon (same vertices, either orientation)");
      for (std::size_t k = 0; k < f.size(); ++k) edges.insert(edge_key(f[k], f[(k + 1) % f.size()]));
      loops.items.insert(loops.items.end(), f.begin(), f.end());
      loops.offsets.push_back(static_cast<std::uint32_t>(loops.items.size()));
    }
  } else {
    for (const Element& p : polylines_) {
      const auto c = loop(p.first_loop);
      if (c.size() < 2) throw InputError(file, p.line, p.label + " has fewer than 2 vertices");
      check_range(c, p.line, p.label);
      for (std::size_t k = 0; k + 1 < c.size(); ++k) {
        if (c[k] == c[k + 1]) throw InputError(file, p.line, p.label + " repeats vertex " + std::to_string(c[k]) + " in a row");
        if (!edges.insert(edge_key(c[k], c[k + 1])).second)
          throw InputError(file, p.line, p.label + " uses the segment " + std::to_string(c[k]) + "-" +
                                             std::to_string(c[k + 1]) + " a second time");
      }
      loops.items.insert(loops.items.end(), c.begin(), c.end());
      loops.offsets.push_back(static_cast<std::uint32_t>(loops.items.size()));
    }
  }
  for (std::uint32_t v : loops.items) used[v] = 1;

  // Tags, including lower-dimensional elements of a higher-dimensional shape.
  FeatureTags tags;
  std::map<std::string, std::vector<std::size_t>> dropped;
  auto reject = [&](std::size_t line, const std::string& why) {
    if (policy == TagPolicy::Strict) throw InputError(file, line, why);
    dropped[why].push_back(line);
  };
  auto in_range = [&](std::span<const std::int64_t> items) {
    return std::all_of(items.begin(), items.end(), [&](std::int64_t v) { return v >= 0 && v < static_cast<std::int64_t>(nv); });
  };
  auto add_face_tag = [&](std::span<const std::int64_t> f, std::size_t line, const char* what) {
    if (f.size() < 3 || !in_range(f)) return reject(line, std::string(what) + " names a vertex out of range or has fewer than 3 vertices");
    if (!faces.count(canonical_loop(f))) return reject(line, std::string(what) + " is no face of the shape");
    tags.feature_faces.emplace_back(f.begin(), f.end());
  };
  auto add_crease_tag = [&](std::span<const std::int64_t> c, std::size_t line, const char* what) {
    if (c.size() < 2 || !in_range(c)) return reject(line, std::string(what) + " names a vertex out of range or has fewer than 2 vertices");
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      if (!edges.count(edge_key(c[k], c[k + 1]))) {
        reject(line, std::string(what) + " names two vertices that share no edge");
        continue;
      }
      tags.crease_edges.emplace_back(static_cast<std::uint32_t>(c[k]), static_cast<std::uint32_t>(c[k + 1]));
    }
  };
  for (const Tag& t : feature_faces_)
    add_face_tag({tag_items_.data() + t.first, t.end - t.first}, t.line, "feature_face");
  for (const Tag& t : creases_) add_crease_tag({tag_items_.data() + t.first, t.end - t.first}, t.line, "crease");
  for (const Tag& t : corners_) {
    const std::int64_t v = tag_items_[t.first];
    if (v < 0 || v >= static_cast<std::int64_t>(nv)) reject(t.line, "corner names a vertex out of range");
    else tags.corner_vertices.push_back(static_cast<std::uint32_t>(v)), used[v] = 1;
  }
  if (dim == 3)
    for (const Element& p : polygons_) add_face_tag(loop(p.first_loop), p.line, "polygon (a feature-face tag in a volume)");
  if (dim >= 2)
    for (const Element& p : polylines_) add_crease_tag(loop(p.first_loop), p.line, "polyline (a crease tag)");
  for (auto& [why, lines] : dropped)
    for (std::size_t l : lines) shape.report.add("tag ignored: " + why, l);

  try {
    if (dim == 3) shape.base = complex_from_cells(nv, loops, cells, tags);
    else if (dim == 2) shape.base = complex_from_polygons(nv, loops, tags);
    else shape.base = complex_from_polylines(nv, loops, tags);
  } catch (const TopologyError& e) {
    throw InputError(file, 0, e.what());
  }
  const char* what = dim == 3 ? "vertex used by no cell (kept; numbering unchanged)"
                     : dim == 2 ? "vertex used by no polygon (kept; numbering unchanged)"
                                : "vertex used by no polyline (kept; numbering unchanged)";
  for (std::uint32_t v = 0; v < nv; ++v)
    if (!used[v]) shape.report.add(what, v < vertex_lines.size() ? vertex_lines[v] : 0);
}

}  // namespace sublift
