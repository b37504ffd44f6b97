#pragma once
// The modeler's free-form deformation mode (issue 6): a model (glTF/OBJ/PLY/OFF, core/io/model/model.h)
// shown with the lattice being edited. While bound, the model follows every lattice operation
// (drag, undo, redo, gain) through core/ffd/ffd.h: only the vertices whose cells moved are
// recomputed. Unbinding keeps the model where it is; binding again takes its current shape as
// the new rest state against the lattice as it is now (the usual FFD workflow: bind, bend,
// unbind, reshape the lattice, bind again). GL-free: ModelerView uploads it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/ffd/ffd.h"
#include "core/io/model/model.h"

namespace sublift {

struct FfdModelState {
  Model model;
  std::vector<double> positions, normals;  // as drawn now (world, 3 per vertex)
  bool bound = false;
  Outside outside = Outside::Stay;
  FfdBinding binding;
  std::size_t last_moved = 0;    // model vertices recomputed by the last lattice operation
  double last_deform_ms = 0.0;
  std::string note;              // why the model was unbound, when it was not asked for
};

}  // namespace sublift
