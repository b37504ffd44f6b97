#pragma once
// Shape: what a curve, surface or lattice file gives the engine — a base complex, its vertex
// positions (x, y, z per vertex, in the complex's vertex order, which is the file's order), the
// file's per-vertex attributes (colours, scalars), face-varying UVs and their texture, and the import report of repaired or ignored
// elements.
#include <vector>

#include "core/complex/complex.h"
#include "core/base/import_report.h"

namespace sublift {

struct Shape {
  Complex base;
  std::vector<double> positions;  // 3 per vertex
  std::vector<VertexAttribute> attributes;  // per-vertex values beside positions (surface files)
  FaceVaryingUV uv;                         // texture coordinates per corner of base.faces (surfaces)
  SurfaceTexture texture;                   // the image the UVs map (glTF), or none
  ImportReport report;
};

}  // namespace sublift
