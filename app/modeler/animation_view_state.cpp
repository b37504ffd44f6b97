#include "app/modeler/animation_view_state.h"

#include <algorithm>

namespace sublift {

double AnimationViewState::fps() const {
  const std::vector<double>& t = anim.times;
  return t.size() >= 2 && t[1] > t[0] ? 1.0 / (t[1] - t[0]) : 24.0;
}

void refresh_animation_layer(AnimationViewState& a, int level) {
  const SpaceTime& st = a.anim.st;
  a.layer = nearest_layer(st, level, a.frame);
  const std::uint32_t nvs = st.surface_vertices(level);
  const auto& lv = st.layer_vertices[std::size_t(level)];
  a.on_layer.assign(st.lattice.num_vertices(level), 0);
  const std::size_t first = std::size_t(a.layer) * nvs;
  for (std::uint32_t p = 0; p < nvs; ++p) a.on_layer[lv[first + p]] = 1;
  const Complex& s = st.surface_levels.levels[std::size_t(level)];
  a.net_edges.resize(s.edge_verts.size());
  for (std::size_t i = 0; i < s.edge_verts.size(); ++i) a.net_edges[i] = lv[first + s.edge_verts[i]];
}

void refresh_ghosts(AnimationViewState& a, std::span<const double> finest, int level) {
  a.ghost_edges.clear();
  a.ghost_positions.clear();
  const SpaceTime& st = a.anim.st;
  const int J = st.levels(), n = a.frames(), stride = 1 << (J - level);
  // A coarse wireframe (level 1 of the surface at most) keeps ghosts legible.
  const int g = std::min(J, 1);
  const Complex& s = st.surface_levels.levels[std::size_t(g)];
  const std::uint32_t nvs = s.num_vertices;
  std::uint32_t count = 0;
  for (int k = -a.ghosts; k <= a.ghosts; ++k) {
    if (k == 0) continue;
    const double f = a.frame + double(k) * stride;
    if (!st.cyclic && (f < 0 || f > n - 1)) continue;
    const std::vector<double> x = frame_positions(st, finest, f);
    a.ghost_positions.insert(a.ghost_positions.end(), x.begin(), x.begin() + 3 * std::size_t(nvs));
    for (std::uint32_t v : s.edge_verts) a.ghost_edges.push_back(count * nvs + v);
    ++count;
  }
}

}  // namespace sublift
