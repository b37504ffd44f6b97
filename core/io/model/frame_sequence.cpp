// Frame sequences (animation.h): numbered OBJ/PLY/OFF files of one connectivity, read through the
// validating mesh importer; and FrameSet's frame accessor.
#include <cmath>
#include <filesystem>
#include <map>
#include <utility>

#include "core/base/errors.h"
#include "core/base/memory_budget.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/model/animation.h"

namespace sublift {
namespace {

std::string corners(std::span<const std::uint32_t> face) {
  std::string s;
  for (std::uint32_t v : face) s += (s.empty() ? "" : " ") + std::to_string(v);
  return s;
}

// How a message names the first file from another: its file name when both share a folder.
std::string name_from(const std::string& first, const std::string& other) {
  const std::filesystem::path a(first), b(other);
  return a.parent_path() == b.parent_path() ? a.filename().string() : first;
}

// Throws unless `m` (read from `path`) has frame 0's vertex count and faces, corner for corner.
void check_connectivity(const SurfaceMesh& m, const std::string& path, const SurfaceMesh& m0, const std::string& first) {
  const std::string in = " in " + name_from(first, path);
  if (m.num_vertices() != m0.num_vertices())
    throw InputError(path, 0, std::to_string(m.num_vertices()) + " vertices here but " + std::to_string(m0.num_vertices()) + in);
  const std::size_t nf = std::min(m.num_faces(), m0.num_faces());
  for (std::size_t f = 0; f < nf; ++f) {
    const auto a = m.face(f), b = m0.face(f);
    if (!std::equal(a.begin(), a.end(), b.begin(), b.end()))
      throw InputError(path, 0, "face " + std::to_string(f) + " is " + corners(a) + " here but " + corners(b) + in +
                                    " (a frame sequence keeps one connectivity; vertices numbered from 0)");
  }
  if (m.num_faces() != m0.num_faces())
    throw InputError(path, 0, std::to_string(m.num_faces()) + " faces here but " + std::to_string(m0.num_faces()) + in);
}

}  // namespace

std::span<const double> FrameSet::frame(std::size_t f) const {
  const std::size_t n = 3 * std::size_t(num_vertices);
  return {positions.data() + f * n, n};
}

FrameSet read_frame_sequence(std::span<const std::string> paths, double fps) {
  const std::string first = paths.empty() ? std::string("frame sequence") : paths.front();
  if (paths.size() < 2)
    throw InputError(first, 0, "a frame sequence needs at least 2 files, not " + std::to_string(paths.size()));
  if (!std::isfinite(fps) || !(fps > 0)) throw InputError(first, 0, "frames per second must be finite and > 0, not " + std::to_string(fps));
  FrameSet fs;
  fs.source = first;
  const LoadedMesh m0 = import_surface_mesh(first);
  if (m0.mesh.num_faces() == 0) throw InputError(first, 0, "no faces: a frame sequence animates a surface");
  const std::size_t nv = m0.mesh.num_vertices();
  check_memory(double(paths.size()) * double(nv) * 3 * sizeof(double), "reading " + std::to_string(paths.size()) + " frames from " + first);
  fs.num_vertices = static_cast<std::uint32_t>(nv);
  fs.faces.offsets = m0.mesh.face_offsets;
  fs.faces.items = m0.mesh.face_indices;
  fs.positions.reserve(paths.size() * 3 * nv);
  std::map<std::string, std::pair<std::string, std::size_t>> not_kept;  // what -> (first file, files)
  std::vector<std::string> order;
  auto not_kept_in = [&](const std::string& what, const std::string& path) {
    auto [it, fresh] = not_kept.emplace(what, std::make_pair(path, std::size_t(0)));
    if (fresh) order.push_back(what);
    ++it->second.second;
  };
  for (std::size_t i = 0; i < paths.size(); ++i) {
    LoadedMesh read;
    if (i > 0) read = import_surface_mesh(paths[i]);
    const LoadedMesh& m = i == 0 ? m0 : read;
    if (i > 0) check_connectivity(m.mesh, paths[i], m0.mesh, first);
    for (const glm::dvec3& p : m.mesh.positions) fs.positions.insert(fs.positions.end(), {p.x, p.y, p.z});
    fs.times.push_back(double(i) / fps);
    // The importer's repairs, by file (they may differ from frame to frame).
    const std::string warnings = m.report.format(paths[i]);
    for (std::size_t at = 0, end; at < warnings.size(); at = end + 1) {
      end = warnings.find('\n', at);
      if (end == std::string::npos) end = warnings.size();
      if (end > at) fs.notes.push_back(warnings.substr(at, end - at));
    }
    ImportReport kept = m.report;
    kept.note_attributes_not_kept(m.mesh.attributes);
    for (const ImportWarning& w : kept.not_kept) not_kept_in(w.what, paths[i]);
    if (m.mesh.num_polylines() > 0) not_kept_in("polylines (l)", paths[i]);
    if (!m.mesh.tags.empty()) not_kept_in("tags (t crease, t corner, ...)", paths[i]);
  }
  for (std::size_t i = 1; i < fs.times.size(); ++i)
    if (!(fs.times[i] > fs.times[i - 1]))
      throw InputError(first, 0, std::to_string(paths.size()) + " frames at " + std::to_string(fps) + " per second are closer than double precision");
  fs.rest_positions.assign(fs.positions.begin(), fs.positions.begin() + std::ptrdiff_t(3 * nv));
  for (const std::string& what : order) {
    const auto& [file, files] = not_kept.at(what);
    fs.notes.push_back(file + (files > 1 ? " and " + std::to_string(files - 1) + " other files" : std::string()) + ": not kept: " + what);
  }
  return fs;
}

}  // namespace sublift
