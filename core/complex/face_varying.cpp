#include "core/complex/face_varying.h"

#include "core/base/errors.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace sublift {
namespace {

// Appends UV points while a level is refined: the mean of two (shared by every face whose corner
// pair is the same two points) or a new point per face.
struct UvBuilder {
  FaceVaryingUV out;
  std::unordered_map<std::uint64_t, std::uint32_t> mid;

  explicit UvBuilder(const FaceVaryingUV& in, std::size_t corners) {
    out.points = in.points;
    out.corners.reserve(corners);
  }
  std::uint32_t midpoint(std::uint32_t a, std::uint32_t b) {
    if (a == b) return a;
    if (a > b) std::swap(a, b);
    const auto [it, added] = mid.try_emplace((std::uint64_t(a) << 32) | b, std::uint32_t(out.num_points()));
    if (added)
      out.points.insert(out.points.end(), {0.5 * (out.points[2 * a] + out.points[2 * b]),
                                           0.5 * (out.points[2 * a + 1] + out.points[2 * b + 1])});
    return it->second;
  }
};

}  // namespace

std::string uv_problem(const Complex& c, const FaceVaryingUV& uv) {
  if (c.dim != 2) return "texture coordinates need a surface";
  return uv_problem(c.faces.items.size(), uv);
}

UvVertexSplit split_at_uv_seams(const Csr& faces, const FaceVaryingUV& uv, std::size_t num_vertices) {
  UvVertexSplit out;
  out.faces.offsets = faces.offsets;
  out.faces.items.resize(faces.items.size());
  out.source.resize(num_vertices);
  out.texcoords.assign(2 * num_vertices, 0.0);
  std::vector<std::uint32_t> first_uv(num_vertices, 0xffffffffu);  // the UV point of vertex v's own copy
  std::unordered_map<std::uint64_t, std::uint32_t> extra;           // (vertex, UV point) -> a further copy
  for (std::uint32_t v = 0; v < num_vertices; ++v) out.source[v] = v;
  for (std::size_t k = 0; k < faces.items.size(); ++k) {
    const std::uint32_t v = faces.items[k], t = uv.corners[k];
    if (first_uv[v] == 0xffffffffu || first_uv[v] == t) {
      if (first_uv[v] == 0xffffffffu) {
        first_uv[v] = t;
        out.texcoords[2 * v] = uv.points[2 * t], out.texcoords[2 * v + 1] = uv.points[2 * t + 1];
      }
      out.faces.items[k] = v;
      continue;
    }
    const auto [it, added] = extra.try_emplace((std::uint64_t(v) << 32) | t, std::uint32_t(out.source.size()));
    if (added) {
      out.source.push_back(v);
      out.texcoords.insert(out.texcoords.end(), {uv.points[2 * t], uv.points[2 * t + 1]});
    }
    out.faces.items[k] = it->second;
  }
  return out;
}

std::vector<double> at_split_vertices(const UvVertexSplit& split, std::span<const double> values, std::size_t width) {
  std::vector<double> out(width * split.source.size());
  for (std::size_t i = 0; i < split.source.size(); ++i) std::copy_n(&values[width * split.source[i]], width, &out[width * i]);
  return out;
}

FaceVaryingUV uv_for_faces(const Csr& from, const FaceVaryingUV& uv, const Csr& to) {
  std::unordered_map<std::uint64_t, std::uint32_t> slot_of;  // oriented edge a -> b: the corner slot of a
  slot_of.reserve(from.items.size());
  for (std::uint32_t f = 0; f < from.rows(); ++f) {
    const std::uint32_t first = from.offsets[f], n = from.offsets[f + 1] - first;
    for (std::uint32_t i = 0; i < n; ++i)
      slot_of.emplace((std::uint64_t(from.items[first + i]) << 32) | from.items[first + (i + 1) % n], first + i);
  }
  const auto face_of_slot = [&](std::uint32_t slot) {
    return std::uint32_t(std::upper_bound(from.offsets.begin(), from.offsets.end(), slot) - from.offsets.begin() - 1);
  };
  FaceVaryingUV out;
  out.points = uv.points;
  out.corners.resize(to.items.size());
  for (std::uint32_t g = 0; g < to.rows(); ++g) {
    const std::uint32_t first = to.offsets[g], n = to.offsets[g + 1] - first;
    const std::uint32_t a = to.items[first], b = to.items[first + 1 % n];
    bool backwards = false;
    auto it = slot_of.find((std::uint64_t(a) << 32) | b);
    if (it == slot_of.end()) backwards = true, it = slot_of.find((std::uint64_t(b) << 32) | a);
    const std::uint32_t f = it == slot_of.end() ? 0 : face_of_slot(it->second);
    if (it == slot_of.end() || from.offsets[f + 1] - from.offsets[f] != n)
      throw TopologyError("face " + std::to_string(g) + " is not among the faces the UVs are given for");
    const std::uint32_t base = from.offsets[f], at = it->second - base + (backwards ? 1 : 0);
    for (std::uint32_t j = 0; j < n; ++j) {
      const std::uint32_t k = base + (backwards ? (at + n - j % n) % n : (at + j) % n);
      if (from.items[k] != to.items[first + j]) throw TopologyError("face " + std::to_string(g) + " is not among the faces the UVs are given for");
      out.corners[first + j] = uv.corners[k];
    }
  }
  return out;
}

FaceVaryingUV refine_uv_split(const Complex& c, const FaceVaryingUV& uv) {
  UvBuilder b(uv, 4 * c.faces.items.size());
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
    const std::uint32_t first = c.faces.offsets[f], n = c.faces.offsets[f + 1] - first;
    // The face point: the mean of the corners' UVs (one new point per face).
    double u = 0.0, v = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) u += uv.points[2 * uv.corners[first + i]], v += uv.points[2 * uv.corners[first + i] + 1];
    const auto centre = std::uint32_t(b.out.num_points());
    b.out.points.insert(b.out.points.end(), {u / n, v / n});
    // Child b + i is (v_i, mid(i, i+1), centre, mid(i-1, i)), as refine() numbers it.
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t here = uv.corners[first + i], next = uv.corners[first + (i + 1) % n],
                          prev = uv.corners[first + (i + n - 1) % n];
      const std::uint32_t m_next = b.midpoint(here, next), m_prev = b.midpoint(prev, here);
      b.out.corners.insert(b.out.corners.end(), {here, m_next, centre, m_prev});
    }
  }
  return std::move(b.out);
}

FaceVaryingUV refine_uv_tri(const Complex& c, const FaceVaryingUV& uv) {
  UvBuilder b(uv, 4 * c.faces.items.size());
  for (std::uint32_t f = 0; f < c.num_faces(); ++f) {
    const std::uint32_t* a = &uv.corners[c.faces.offsets[f]];
    const std::uint32_t m[3] = {b.midpoint(a[0], a[1]), b.midpoint(a[1], a[2]), b.midpoint(a[2], a[0])};
    // 4f + k = (a_k, m_k, m_{k-1}); 4f + 3 = (m0, m1, m2), as refine_tri() numbers them.
    for (int k = 0; k < 3; ++k) b.out.corners.insert(b.out.corners.end(), {a[k], m[k], m[(k + 2) % 3]});
    b.out.corners.insert(b.out.corners.end(), {m[0], m[1], m[2]});
  }
  return std::move(b.out);
}

}  // namespace sublift
