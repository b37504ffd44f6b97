#include "core/complex/face_builder.h"

#include <algorithm>
#include <unordered_set>

#include "core/base/edge_key.h"
#include "core/base/errors.h"
#include "core/complex/face_loop.h"

namespace sublift {

void FaceBuilder::add(std::span<const std::int64_t> corners, std::size_t line, std::span<const std::int64_t> uvs) {
  // UV indices are stored only once a corner has one (a file without vt costs nothing here).
  const bool any = !uvs.empty() && uvs.size() == corners.size();  // callers pass UVs only when a corner has one
  if (any || !uvs_.empty()) {
    uvs_.resize(indices_.size(), -1);
    if (any)
      uvs_.insert(uvs_.end(), uvs.begin(), uvs.end());
    else
      uvs_.insert(uvs_.end(), corners.size(), -1);
  }
  indices_.insert(indices_.end(), corners.begin(), corners.end());
  offsets_.push_back(indices_.size());
  lines_.push_back(line);
}

void FaceBuilder::add_unreadable(std::size_t line, ImportReport& report, const char* reason) {
  report.add(std::string("face dropped: ") + reason, line);
}

void FaceBuilder::finish(SurfaceMesh& mesh, ImportReport& report) const {
  const auto nv = static_cast<std::int64_t>(mesh.num_vertices());
  std::vector<char> unusable(mesh.num_vertices(), 0);
  for (std::size_t v : unusable_)
    if (v < unusable.size()) unusable[v] = 1;
  // Pass 1: validate and repair each face into flat arrays (no allocation per face: hostile
  // files have hundreds of thousands of faces); remember each face's canonical loop.
  std::vector<std::uint32_t> kept, canon;
  std::vector<std::int64_t> kept_uv;  // parallel to kept
  std::vector<std::size_t> kept_offsets{0}, kept_lines;
  std::vector<std::uint32_t> face, sorted;
  std::vector<std::int64_t> face_uv;
  for (std::size_t f = 0; f < lines_.size(); ++f) {
    const std::size_t line = lines_[f];
    std::span<const std::int64_t> raw(indices_.data() + offsets_[f], offsets_[f + 1] - offsets_[f]);
    if (raw.size() < 3) {
      report.add("face dropped: fewer than 3 vertices", line);
      continue;
    }
    if (std::any_of(raw.begin(), raw.end(), [&](std::int64_t i) { return i < 0 || i >= nv; })) {
      report.add("face dropped: vertex index out of range", line);
      continue;
    }
    if (std::any_of(raw.begin(), raw.end(), [&](std::int64_t i) { return unusable[i] != 0; })) {
      report.add("face dropped: uses an unreadable vertex", line);
      continue;
    }
    // A vertex written twice in a row (1 2 2 3) is a harmless export artefact: collapse it (the
    // first copy's UV is kept).
    const std::size_t before = raw.size();
    if (uvs_.empty()) {
      face.assign(raw.begin(), raw.end());
      face.erase(std::unique(face.begin(), face.end()), face.end());
      while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    } else {
      face.clear();
      face_uv.clear();
      for (std::size_t k = 0; k < raw.size(); ++k)
        if (face.empty() || face.back() != std::uint32_t(raw[k])) {
          face.push_back(std::uint32_t(raw[k]));
          face_uv.push_back(uvs_[offsets_[f] + k]);
        }
      while (face.size() > 1 && face.front() == face.back()) face.pop_back(), face_uv.pop_back();
    }
    if (face.size() < 3) {
      report.add("face dropped: fewer than 3 distinct vertices", line);
      continue;
    }
    sorted.assign(face.begin(), face.end());
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      report.add("face dropped: a vertex occurs twice (non-simple polygon)", line);
      continue;
    }
    if (face.size() != before) report.add("face repaired: repeated consecutive vertex removed", line);
    kept.insert(kept.end(), face.begin(), face.end());
    if (!uvs_.empty()) kept_uv.insert(kept_uv.end(), face_uv.begin(), face_uv.end());
    append_canonical_loop(face, canon);
    kept_offsets.push_back(kept.size());
    kept_lines.push_back(line);
  }
  // Pass 2: duplicates (same loop, either orientation). Faces are sorted by a 64-bit hash of
  // their canonical loop (integer compares only: fast even under sanitizers), then equal-hash
  // runs are compared element by element; the first in file order is kept.
  const std::size_t n = kept_lines.size();
  auto key_of = [&](std::size_t i) {
    return std::span<const std::uint32_t>(canon.data() + kept_offsets[i], kept_offsets[i + 1] - kept_offsets[i]);
  };
  struct Entry {
    std::uint64_t hash;
    std::uint32_t index;
  };
  std::vector<Entry> entries(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t h = 1469598103934665603ull ^ (kept_offsets[i + 1] - kept_offsets[i]);
    for (std::uint32_t v : key_of(i)) h = (h ^ v) * 1099511628211ull;  // FNV-1a over the loop
    entries[i] = {h, static_cast<std::uint32_t>(i)};
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& x, const Entry& y) { return x.hash != y.hash ? x.hash < y.hash : x.index < y.index; });
  std::vector<char> duplicate(n, 0);
  for (std::size_t run = 0; run < n;) {
    std::size_t end = run + 1;
    while (end < n && entries[end].hash == entries[run].hash) ++end;
    for (std::size_t k = run + 1; k < end; ++k)
      for (std::size_t j = run; j < k; ++j) {
        if (duplicate[entries[j].index]) continue;
        const auto a = key_of(entries[j].index), b = key_of(entries[k].index);
        if (std::equal(a.begin(), a.end(), b.begin(), b.end())) {
          duplicate[entries[k].index] = 1;
          break;
        }
      }
    run = end;
  }
  const bool with_uv = !mesh.uv.points.empty();
  const auto num_uv = static_cast<std::int64_t>(mesh.uv.num_points());
  std::size_t uv_fault_line = 0;
  const char* uv_fault = nullptr;
  for (std::size_t i = 0; i < n; ++i) {
    if (duplicate[i]) {
      report.add("face dropped: duplicate of an earlier face (same vertices, either orientation)", kept_lines[i]);
      continue;
    }
    mesh.add_face(std::span<const std::uint32_t>(kept.data() + kept_offsets[i], kept_offsets[i + 1] - kept_offsets[i]));
    if (!with_uv || uv_fault) continue;
    for (std::size_t k = kept_offsets[i]; k < kept_offsets[i + 1] && !uv_fault; ++k) {
      if (kept_uv.empty() || kept_uv[k] < 0) uv_fault = "a face without them";
      else if (kept_uv[k] >= num_uv) uv_fault = "a texture-coordinate index out of range";
      else mesh.uv.corners.push_back(std::uint32_t(kept_uv[k]));
    }
    if (uv_fault) uv_fault_line = kept_lines[i];
  }
  if (uv_fault) {
    report.not_kept.push_back({std::string("texture coordinates (vt): ") + uv_fault + " (a UV set must cover every face corner)", 1, {uv_fault_line}});
    mesh.uv = {};
  }
}

void PolylineBuilder::add(std::span<const std::int64_t> vertices, std::size_t line) {
  indices_.insert(indices_.end(), vertices.begin(), vertices.end());
  offsets_.push_back(indices_.size());
  lines_.push_back(line);
}

void PolylineBuilder::finish(SurfaceMesh& mesh, std::span<const std::size_t> unusable_list,
                             ImportReport& report) const {
  const auto nv = static_cast<std::int64_t>(mesh.num_vertices());
  std::vector<char> unusable(mesh.num_vertices(), 0);
  for (std::size_t v : unusable_list)
    if (v < unusable.size()) unusable[v] = 1;
  std::unordered_set<std::uint64_t> segments;  // of the polylines kept so far
  std::vector<std::uint32_t> poly;
  std::vector<std::uint64_t> own;
  for (std::size_t l = 0; l < lines_.size(); ++l) {
    const std::size_t line = lines_[l];
    std::span<const std::int64_t> raw(indices_.data() + offsets_[l], offsets_[l + 1] - offsets_[l]);
    if (raw.size() < 2) {
      report.add("polyline dropped: fewer than 2 vertices", line);
      continue;
    }
    if (std::any_of(raw.begin(), raw.end(), [&](std::int64_t i) { return i < 0 || i >= nv; })) {
      report.add("polyline dropped: vertex index out of range", line);
      continue;
    }
    if (std::any_of(raw.begin(), raw.end(), [&](std::int64_t i) { return unusable[i] != 0; })) {
      report.add("polyline dropped: uses an unreadable vertex", line);
      continue;
    }
    poly.assign(raw.begin(), raw.end());
    const std::size_t before = poly.size();
    poly.erase(std::unique(poly.begin(), poly.end()), poly.end());
    if (poly.size() < 2) {
      report.add("polyline dropped: fewer than 2 distinct vertices", line);
      continue;
    }
    own.clear();
    bool repeated = false;
    for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
      own.push_back(edge_key(poly[i], poly[i + 1]));
      repeated = repeated || segments.count(own.back());
    }
    std::vector<std::uint64_t> sorted = own;
    std::sort(sorted.begin(), sorted.end());
    if (repeated || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      report.add("polyline dropped: a segment occurs twice (in it or in an earlier polyline)", line);
      continue;
    }
    if (poly.size() != before) report.add("polyline repaired: repeated consecutive vertex removed", line);
    segments.insert(own.begin(), own.end());
    mesh.add_polyline(poly);
  }
}

void check_imported_mesh(const std::string& file, const SurfaceMesh& mesh,
                         std::span<const std::size_t> vertex_lines, ImportReport& report) {
  if (mesh.num_faces() == 0 && mesh.num_polylines() == 0) {
    std::string why;
    if (mesh.num_vertices() == 0) why = "no vertices and no faces";
    else if (report.empty()) why = std::to_string(mesh.num_vertices()) + " vertices but no faces or polylines (a point cloud, not a surface or curve)";
    else why = "no usable face or polyline left after dropping bad elements:\n" + report.format(file);
    throw InputError(file, 0, why);
  }
  std::vector<char> used(mesh.num_vertices(), 0);
  for (std::uint32_t v : mesh.face_indices) used[v] = 1;
  for (std::uint32_t v : mesh.line_indices) used[v] = 1;
  const char* what = mesh.num_polylines() == 0  ? "vertex used by no face (kept; numbering unchanged)"
                     : mesh.num_faces() == 0    ? "vertex used by no polyline (kept; numbering unchanged)"
                                                : "vertex used by no face or polyline (kept; numbering unchanged)";
  for (std::size_t v = 0; v < used.size(); ++v)
    if (!used[v]) report.add(what, v < vertex_lines.size() ? vertex_lines[v] : 0);
}

}  // namespace sublift
