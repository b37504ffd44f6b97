#pragma once
// FfdScene: a model embedded in a lattice for free-form deformation (issue 6) — what
// `sublift-cli ffd` and the modeler's FFD mode share. The lattice is a Session (edited exactly as
// the modeler edits any hierarchy, with undo), its level 0 the lattice file or a box around the
// model and its finest level `extra_levels` refinements further (zero details, a smoother map).
// The model is bound once to the finest level of the undeformed lattice (core/ffd/ffd.h); after
// every lattice operation update_deformation() moves only the model vertices whose cells moved.
#include <memory>
#include <string>
#include <vector>

#include "core/ffd/ffd.h"
#include "core/multires/hierarchy.h"
#include "core/io/model/model.h"
#include "core/edit/session.h"
#include "core/complex/shape.h"

namespace sublift {

struct FfdSceneOptions {
  Scheme scheme = Scheme::Cubic;
  int extra_levels = 2;          // lattice levels above the file's (0..6)
  Outside outside = Outside::Stay;
};

struct FfdScene {
  Model model;
  std::unique_ptr<Session> lattice;
  FfdBinding binding;
  std::vector<double> deformed;  // the model's positions now (world, 3 per vertex)
  int finest() const { return lattice->finest_level(); }
};

/// A lattice file (.lattice, .ovm, .vtk) as a Shape; throws InputError when it is not a volume.
Shape read_ffd_lattice(const std::string& path);

/// A box lattice of nx x ny x nz hexahedra around the model's bounding box, `margin` times the
/// box diagonal added on every side (core/ffd/box_lattice.h).
Shape box_lattice_around(const Model& model, int nx, int ny, int nz, double margin);

/// Builds the lattice hierarchy and binds the model. Throws Error (bad options, a lattice the
/// hierarchy refuses).
FfdScene make_ffd_scene(Model model, const Shape& lattice, const FfdSceneOptions& options = {});

/// After a lattice operation (move, undo, redo, gain): recomputes the model vertices whose
/// stencils name a finest lattice vertex the operation changed; returns them (ascending).
std::vector<std::uint32_t> update_deformation(FfdScene& scene);

/// The same for a binding kept apart from its lattice session (the modeler's FFD mode), which
/// must be bound to `lattice`'s finest level.
std::vector<std::uint32_t> update_deformation(const FfdBinding& binding, const Session& lattice,
                                              std::vector<double>& deformed);

}  // namespace sublift
