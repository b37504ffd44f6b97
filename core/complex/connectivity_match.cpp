#include "core/complex/connectivity_match.h"
#include "core/complex/face_loop.h"

#include <algorithm>
#include <vector>

namespace sublift {
namespace {

using Item = std::vector<std::uint32_t>;

std::vector<Item> items(const Complex& c, int kind) {
  std::vector<Item> out;
  if (kind == 1) {
    for (std::uint32_t e = 0; e < c.num_edges(); ++e)
      out.push_back({std::min(c.edge_verts[2 * e], c.edge_verts[2 * e + 1]), std::max(c.edge_verts[2 * e], c.edge_verts[2 * e + 1])});
  } else if (kind == 2) {
    for (std::uint32_t f = 0; f < c.num_faces(); ++f) out.push_back(canonical_loop(c.faces.row(f)));
  } else {
    for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
      Item v;
      for (std::uint32_t f : c.cell_faces.row(k)) v.insert(v.end(), c.faces.row(f).begin(), c.faces.row(f).end());
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
      out.push_back(std::move(v));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string show(const Item& x) {
  std::string s;
  for (std::uint32_t v : x) {
    if (!s.empty()) s += ' ';
    s += std::to_string(v);
  }
  return s;
}

}  // namespace

std::string connectivity_mismatch(const Complex& expected, const Complex& got) {
  if (expected.dim != got.dim)
    return "it is of dimension " + std::to_string(got.dim) + ", the refined base of dimension " + std::to_string(expected.dim);
  if (expected.num_vertices != got.num_vertices)
    return "it has " + std::to_string(got.num_vertices) + " vertices, the refined base " + std::to_string(expected.num_vertices);
  const char* names[] = {"", "edge", "face", "cell"};
  for (int kind = expected.dim == 1 ? 1 : 2; kind <= expected.dim; ++kind) {
    const std::vector<Item> a = items(expected, kind), b = items(got, kind);
    if (a == b) continue;
    if (a.size() != b.size())
      return "it has " + std::to_string(b.size()) + " " + names[kind] + "s, the refined base " + std::to_string(a.size());
    const auto [ia, ib] = std::mismatch(a.begin(), a.end(), b.begin());
    const bool missing = *ia < *ib;
    std::string why = missing ? "the refined base has the " : "it has the ";
    why += names[kind];
    why += " (" + show(missing ? *ia : *ib) + "), which ";
    why += missing ? "the file lacks" : "the refined base lacks";
    why += " (vertex numbers differ from the engine's order?)";
    return why;
  }
  return "";
}

}  // namespace sublift
