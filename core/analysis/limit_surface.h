#pragma once
// The finest level's limit surface, as the modeler draws and exports it and `sublift-cli
// synthesize --limit` writes it: limit positions of every finest vertex (limit stencils,
// core/multires/limit.h), the display faces (a surface's own faces, a lattice's outward boundary
// faces, none for a curve) and unit normals from the limit tangents (zero without faces).
#include <span>
#include <vector>

#include "core/base/csr.h"
#include "core/multires/hierarchy.h"
#include "core/multires/limit.h"

namespace sublift {

struct LimitSurface {
  LimitStencils stencils;                 // kept by the modeler for local updates after edits
  std::vector<double> positions, normals; // 3 per finest vertex
  Csr faces;                              // display faces over the finest vertices
};

/// The limit surface of h's finest level, whose control net is `finest` (3 per vertex).
LimitSurface finest_limit_surface(const Hierarchy& h, std::span<const double> finest);

}  // namespace sublift
