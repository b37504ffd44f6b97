#include "core/analysis/limit_surface.h"

#include "core/analysis/boundary_surface.h"
#include "core/base/errors.h"

namespace sublift {

LimitSurface finest_limit_surface(const Hierarchy& h, std::span<const double> finest) {
  const int J = h.finest_level();
  const std::size_t n = h.num_vertices(J);
  if (finest.size() != 3 * n) throw Error("finest_limit_surface: the net has " + std::to_string(finest.size() / 3) +
                                          " points for " + std::to_string(n) + " finest vertices");
  LimitSurface s;
  s.stencils = build_limit_stencils(h);
  s.positions.assign(n * 3, 0.0);
  s.normals.assign(n * 3, 0.0);
  eval_limit(s.stencils, finest.data(), s.positions.data());
  const Complex& c = h.levels[static_cast<std::size_t>(J)];
  if (c.dim >= 2) s.faces = boundary_faces(c, s.positions);
  if (s.faces.rows() > 0) {
    limit_normals(s.stencils, s.faces, finest.data(), s.positions.data(), s.normals.data());
    orient_tangents(s.stencils, s.faces, finest.data(), s.positions.data());
  }
  return s;
}

}  // namespace sublift
