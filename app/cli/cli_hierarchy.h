#pragma once
// Shared pieces of the hierarchy commands (subdivide, analyze, synthesize, info on projects):
// option parsing with range checks, the output-size guard and JSON forms of complexes.
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/cli_args.h"
#include "core/base/channels.h"
#include "core/complex/complex.h"
#include "core/complex/shape.h"
#include "core/io/project/project_io.h"
#include "core/multires/hierarchy.h"

namespace sublift::cli {

/// Largest finest level a command builds (vertices); more is refused before allocating.
inline constexpr double kMaxOutputVertices = 50e6;

/// `--levels N`, required, 0..max_levels(scheme). Throws UsageError.
int levels_option(const Args& a, Scheme scheme);

/// `--scheme linear|cubic|sqrt2`, required. Throws UsageError.
Scheme scheme_option(const Args& a);

/// Throws UsageError when `levels` refinements of `base` would exceed kMaxOutputVertices, or
/// when the scheme cannot refine this kind of complex (sqrt2 takes surfaces only).
/// --disc K of the triangle schemes (default 2); refused for the other schemes.
int disc_option(const Args& a, Scheme scheme);
void check_refined_size(const Complex& base, int levels, Scheme scheme);

/// The output path `-o OUT`, required; UsageError when missing or when `dim` cannot be written
/// to its extension (an empty `dim` check when dim is 0).
std::string output_option(const Args& a, int dim);

/// Whether `path` names a .sublift project (case-insensitive extension).
bool is_project_path(const std::string& path);


/// Writes the control net `x` of level L (`channels` per vertex) to `out`; in the vertex and
/// face order of the file the project was rebuilt from when `order` is of that level. Channels
/// 3.. are the attributes `names` (ProjectExtras::attributes), written where the format can.
/// `base_uv` (ProjectExtras::uv) gives the level its texture coordinates by the linear rule; a
/// scheme that cannot carry them is named in the notes.
std::vector<std::string> write_level(const std::string& out, const Hierarchy& h, int L, std::span<const double> x,
                                     int channels, const InputOrder& order, std::span<const VertexAttribute> names = {},
                                     const FaceVaryingUV* base_uv = nullptr);

/// The base UVs of a project analysed from `fine` (its finest level): FINE's UVs carried to the
/// finest level's faces (through `engine_vertex`, file vertex -> engine vertex, when the file is
/// in its own order) and coarsened (level_uv.h). What cannot be kept (the scheme, UVs that are not
/// a linear refinement, the texture image) is added to `not_kept`.
FaceVaryingUV project_uv(const Hierarchy& h, const Shape& fine, const std::vector<std::uint32_t>* engine_vertex,
                         std::vector<std::string>& not_kept);

/// [{"name": ..., "type": ...}, ...] for --json.
nlohmann::json attribute_list_json(std::span<const VertexAttribute> attributes);

/// Counts of a complex: dim, vertices, edges, faces, cells.
nlohmann::json complex_counts_json(const Complex& c);

}  // namespace sublift::cli
