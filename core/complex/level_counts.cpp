#include "core/complex/level_counts.h"

#include <algorithm>

namespace sublift {

namespace {

// Counts of levels 0..levels: vertices (what = 0) or faces (what = 1).
std::vector<double> predicted_counts(const Complex& c, int levels, int what) {
  double V = c.num_vertices, E = c.num_edges(), F = c.num_faces(), C = c.num_cells();
  double SF = static_cast<double>(c.faces.items.size()), CF = static_cast<double>(c.cell_faces.items.size());
  double CE = 0, CV = 0;
  std::vector<std::uint32_t> tmp;
  for (std::uint32_t k = 0; k < c.num_cells(); ++k) {
    for (int pass = 0; pass < 2; ++pass) {
      tmp.clear();
      for (std::uint32_t f : c.cell_faces.row(k)) {
        const auto r = pass == 0 ? c.faces.row(f) : c.face_edges.row(f);
        tmp.insert(tmp.end(), r.begin(), r.end());
      }
      std::sort(tmp.begin(), tmp.end());
      const double n = static_cast<double>(std::unique(tmp.begin(), tmp.end()) - tmp.begin());
      (pass == 0 ? CV : CE) += n;
    }
  }
  std::vector<double> out{what == 0 ? V : F};
  for (int j = 0; j < levels; ++j) {
    const double V2 = V + E + F + C, E2 = 2 * E + SF + CF, F2 = SF + CE, C2 = CV;
    const double SF2 = 4 * F2, CF2 = 4 * CE, CE2 = 8 * CE, CV2 = 2 * CV + 4 * CE;
    V = V2, E = E2, F = F2, C = C2, SF = SF2, CF = CF2, CE = CE2, CV = CV2;
    out.push_back(what == 0 ? V : F);
  }
  return out;
}

}  // namespace

std::vector<double> predicted_vertex_counts(const Complex& c, int levels) { return predicted_counts(c, levels, 0); }
std::vector<double> predicted_face_counts(const Complex& c, int levels) { return predicted_counts(c, levels, 1); }

}  // namespace sublift
