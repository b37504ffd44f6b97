// sublift-cli render FILE -o PNG [--size WxH] [--colour L] [--json]
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "app/cli/cli_commands.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "app/cli/cli_hierarchy.h"
#include "core/analysis/boundary_surface.h"
#include "core/analysis/limit_surface.h"
#include "core/analysis/wavelet_colour.h"
#include "core/edit/level_ops.h"
#include "core/base/text_lines.h"
#include "core/io/lattice/shape_io.h"
#include "core/io/mesh/mesh_import.h"
#include "core/io/project/project_io.h"
#ifdef SUBLIFT_HAVE_RENDER
#include "render/headless_render.h"
#include "render/offscreen_target.h"
#endif
#include "core/complex/face_varying.h"
#include "core/complex/polygon_normal.h"

namespace sublift::cli {

namespace {

SurfaceMesh surface_of(std::span<const double> xyz, const Csr& faces) {
  SurfaceMesh m;
  for (std::size_t v = 0; v + 2 < xyz.size(); v += 3) m.positions.emplace_back(xyz[v], xyz[v + 1], xyz[v + 2]);
  for (std::size_t f = 0; f < faces.rows(); ++f) m.add_face(faces.row(f));
  return m;
}

// What the modeler shows of FILE: a project's finest limit surface (gains applied), a lattice's
// outward boundary, a mesh as it is.
// A project's limit surface of `level` (-1: the finest), gains applied: the hierarchy cut there.
LimitSurface project_limit(const std::string& file, Hierarchy h, const ProjectExtras& extras, int level) {
  apply_gains(h, extras.gains);
  if (h.channels != 3) throw Error(file + ": a project of " + std::to_string(h.channels) + " channels has no shape to render");
  if (level > h.finest_level())
    throw UsageError("--level " + std::to_string(level) + " is beyond the project's finest level " + std::to_string(h.finest_level()));
  if (level >= 0 && level < h.finest_level()) h = delete_higher(h, level);
  return finest_limit_surface(h, synthesize_in_range(h, h.finest_level()));
}

[[maybe_unused]] SurfaceMesh mesh_to_render(const std::string& file, int level) {  // with the renderer only
  if (is_project_path(file)) {
    ProjectExtras extras;
    Hierarchy h = read_project(file, &extras);
    const LimitSurface s = project_limit(file, std::move(h), extras, level);
    if (s.faces.rows() == 0) throw Error(file + ": a curve has no surface to render");
    return surface_of(s.positions, s.faces);
  }
  const std::string ext = file_extension(file);
  if (ext == "lattice" || ext == "ovm" || ext == "vtk" || ext == "gltf" || ext == "glb") {
    const Shape shape = read_shape(file);
    std::cerr << shape.report.format(file);
    if (shape.base.dim != 3) {
      if (shape.base.dim < 2) throw Error(file + ": a curve has no surface to render");
      return surface_of(shape.positions, shape.base.faces);
    }
    return surface_of(shape.positions, boundary_faces(shape.base, shape.positions));
  }
  const LoadedMesh loaded = import_surface_mesh(file);
  std::cerr << loaded.report.format(file);
  return loaded.mesh;
}

#ifdef SUBLIFT_HAVE_RENDER
// FILE's surface drawn with its texture: its UVs (OBJ vt, glTF TEXCOORD_0) split at seams into
// per-vertex texture coordinates, the image its glTF material names or `image_path` (any
// PNG/JPEG), normals area-weighted over the faces (smooth across UV seams).
Image render_textured(const std::string& file, const std::optional<std::string>& image_path, int w, int h, bool flat) {
  const Shape shape = read_shape(file);
  std::cerr << shape.report.format(file);
  if (shape.base.dim != 2) throw Error(file + ": --textured needs a surface");
  if (shape.uv.empty()) throw Error(file + ": --textured needs texture coordinates (OBJ vt or glTF TEXCOORD_0); the file has none");
  std::string bytes = image_path ? read_file_bytes(*image_path) : shape.texture.bytes;
  if (bytes.empty()) throw Error(file + ": no texture to draw (the file's material names none): give one with --texture IMAGE");
  const std::optional<Image> texture = decode_image(bytes);
  if (!texture) throw InputError(image_path ? *image_path : file, 0, "texture image cannot be decoded (PNG or JPEG expected)");
  const std::vector<double> normals = area_weighted_normals(shape.base.faces, shape.positions);
  const UvVertexSplit split = split_at_uv_seams(shape.base.faces, shape.uv, shape.base.num_vertices);
  const std::vector<double> xyz = at_split_vertices(split, shape.positions, 3), nrm = at_split_vertices(split, normals, 3);
  const std::vector<float> uv(split.texcoords.begin(), split.texcoords.end());
  const bool own = !image_path;  // the file's sampler wraps as it says; a given image repeats
  HeadlessRenderSettings settings;
  settings.display.wireframe = false;  // the texture is what is looked at
  settings.smooth = !flat;
  return render_textured_surface_headless(xyz, nrm, split.faces, uv, *texture, w, h, settings, own ? shape.texture.wrap_s : 10497,
                                          own ? shape.texture.wrap_t : 10497);
}
#endif

}  // namespace

int run_render(int argc, char** argv) {
  const Args a = parse_args(argc, argv, 2, {"-o", "--size", "--colour", "--color", "--level", "--texture"}, {"--json", "--help", "--textured", "--flat"});
  if (a.has("--help")) {
    std::cout << "usage: sublift-cli render FILE -o PNG [--size WxH] [--level L] [--colour L] [--textured [--texture IMAGE] [--flat]] [--json]\n"
                 "  Renders FILE shaded with its wireframe from the default 3/4 view, without a\n"
                 "  display (EGL surfaceless), and writes a PNG. Default size 800x600. FILE: a mesh\n"
                 "  (.obj .off .ply .gltf .glb), a lattice (.lattice .ovm .vtk: its outward boundary) or a .sublift\n"
                 "  project (its finest limit surface with the saved gains, as the modeler shows it).\n"
                 "  --level L   a project's limit surface of level L instead of the finest (the modeler's\n"
                 "              viewport level)\n"
                 "  --colour L  a project's surface coloured by the magnitude of level L's wavelets\n"
                 "              (viridis, as the modeler's Colour by |w| of level)\n"
                 "  --textured  a surface with UVs (OBJ vt, glTF TEXCOORD_0) drawn with its glTF material's\n"
                 "              base-colour texture, or with --texture IMAGE (PNG or JPEG); --flat shades\n"
                 "              each face flat (normals averaged over a box's corners bend its light)\n";
    return 0;
  }
  if (a.positional.size() != 1) throw UsageError("expected exactly one FILE");
  const auto out = a.value("-o");
  if (!out) throw UsageError("missing -o PNG");
  if (file_extension(*out) != "png") throw UsageError("output must be a .png file, got '" + *out + "'");
  int w = 800, h = 600;
  if (auto s = a.value("--size")) parse_size(*s, w, h);
  int view_level = -1;
  if (const auto l = a.value("--level")) {
    const auto v = parse_int(*l);
    if (!v || *v < 0) throw UsageError("--level must be a non-negative level number, got '" + *l + "'");
    if (!is_project_path(a.positional[0])) throw UsageError("--level needs a .sublift project, got '" + a.positional[0] + "'");
    view_level = static_cast<int>(*v);
  }
  std::optional<std::string> colour = a.value("--colour");
  if (!colour) colour = a.value("--color");
#ifdef SUBLIFT_HAVE_RENDER
  Image img;
  const bool textured = a.has("--textured") || a.value("--texture");
  if (textured && (colour || view_level >= 0)) throw UsageError("--textured draws a mesh file as it is; it does not take --colour or --level");
  if (textured) {
    img = render_textured(a.positional[0], a.value("--texture"), w, h, a.has("--flat"));
  } else if (colour) {
    const std::string& in = a.positional[0];
    if (!is_project_path(in)) throw UsageError("--colour needs a .sublift project (its wavelets), got '" + in + "'");
    const auto l = parse_int(*colour);
    if (!l) throw UsageError("--colour must be a level number, got '" + *colour + "'");
    ProjectExtras extras;
    Hierarchy hier = read_project(in, &extras);
    if (*l < 0 || *l >= hier.finest_level())
      throw UsageError("--colour " + *colour + " is outside the project's wavelet levels 0.." + std::to_string(hier.finest_level() - 1));
    std::vector<float> field = wavelet_magnitude_field(hier, extras.gains, static_cast<int>(*l));
    const LimitSurface s = project_limit(in, std::move(hier), extras, view_level);
    if (s.faces.rows() == 0) throw Error(in + ": a curve has no surface to render");
    field.resize(s.positions.size() / 3);  // a coarser level's vertices come first
    img = render_coloured_surface_headless(s.positions, s.normals, s.faces, field, w, h);  // one value per finest vertex
  } else {
    img = render_mesh_headless(mesh_to_render(a.positional[0], view_level), w, h);
  }
  write_png(*out, img.width, img.height, img.rgba);
  if (a.has("--json"))
    std::cout << nlohmann::json{{"input", a.positional[0]}, {"output", *out}, {"width", w}, {"height", h},
                                {"colour_level", colour ? nlohmann::json(std::stoi(*colour)) : nlohmann::json(nullptr)},
                                {"textured", textured}}
                     .dump(2)
              << "\n";
  return 0;
#else
  (void)view_level;  // the options were checked all the same
  throw Error("this build has no renderer (configured with SUBLIFT_WITH_GUI=OFF)");
#endif
}

}  // namespace sublift::cli
