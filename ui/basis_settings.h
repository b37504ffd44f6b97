#pragma once
// The basis-function mode's settings (issue 5): which function — core's BasisRequest, as it is —
// and how the modeler shows it. The one struct that carries a basis request from the Basis
// panel (ui/modeler_panels.h) through ModelerState and app/modeler/basis_view_state.h to core's
// basis_function(). Plain data: no GL, no ImGui.
#include "core/multires/basis.h"

namespace sublift {

struct BasisSettings {
  bool on = false;
  // The function. request.level: j; -1: the edit level (ModelerState stores the level it used).
  // request.extra_levels: K; -1: core's default, capped at kModelerBasisVertices
  // (app/modeler/basis_view_state.h). request.index: level-j vertex (scaling) or e/f/c vertex of level
  // j+1 (wavelet).
  BasisRequest request{.level = -1};
  bool follow = false;        // a click on the net picks the function there (basis_target_at)
  bool height = false;        // displace as a height field (surfaces, curves)
  double height_scale = 0.2;  // times the bounding-box diagonal at max|value|
  int slice_axis = -1;        // lattices: a slice plane normal to x, y or z (0, 1, 2); -1 none
  double slice_pos = 0.5;     // where along that axis, as a fraction of the bounds
  bool iso = false;           // lattices: iso-surfaces at +-iso_level * max|value|
  double iso_level = 0.3;
};

}  // namespace sublift
