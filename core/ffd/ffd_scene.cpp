#include "core/ffd/ffd_scene.h"

#include "core/ffd/box_lattice.h"
#include "core/base/errors.h"
#include "core/io/lattice/shape_io.h"

namespace sublift {

Shape read_ffd_lattice(const std::string& path) {
  Shape s = read_shape(path);
  if (s.base.dim != 3) {
    throw InputError(path, 0, "not a volume lattice (a " + std::string(s.base.dim == 1 ? "curve" : "surface") +
                                  "); FFD needs cells (.lattice, .ovm or .vtk)");
  }
  s.report.note_attributes_not_kept(s.attributes);  // a deforming lattice is its positions
  return s;
}

Shape box_lattice_around(const Model& model, int nx, int ny, int nz, double margin) {
  if (model.num_vertices() == 0) throw Error("box lattice: the model has no vertices");
  const auto box = bounding_box(model.positions.data(), model.num_vertices());
  return make_box_lattice(box[0], box[1], nx, ny, nz, margin);
}

FfdScene make_ffd_scene(Model model, const Shape& lattice, const FfdSceneOptions& options) {
  if (options.extra_levels < 0 || options.extra_levels > 6) {
    throw Error("FFD: extra lattice levels must be 0..6, got " + std::to_string(options.extra_levels));
  }
  if (lattice.base.dim != 3) throw Error("FFD: the lattice is not a volume");
  Hierarchy h = make_hierarchy(lattice.base, options.extra_levels, options.scheme, 3);
  set_base(h, lattice.positions);
  FfdScene scene;
  scene.lattice = std::make_unique<Session>(std::move(h));
  const int J = scene.lattice->finest_level();
  FfdOptions bind;
  bind.outside = options.outside;
  scene.binding = bind_model(scene.lattice->hierarchy().levels[static_cast<std::size_t>(J)],
                             scene.lattice->positions(J), model.positions, bind);
  scene.deformed = model.positions;
  scene.model = std::move(model);
  return scene;
}

std::vector<std::uint32_t> update_deformation(FfdScene& scene) {
  return update_deformation(scene.binding, *scene.lattice, scene.deformed);
}

std::vector<std::uint32_t> update_deformation(const FfdBinding& binding, const Session& lattice,
                                              std::vector<double>& deformed) {
  const int J = lattice.finest_level();
  std::vector<std::uint32_t> touched;
  deform_changed(binding, lattice.positions(J), lattice.changed(J), deformed, &touched);
  return touched;
}

}  // namespace sublift
