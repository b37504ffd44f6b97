#pragma once
// The sublift-cli commands. Each returns the process exit code (0 ok); they throw
// cli::UsageError for bad usage and sublift::Error for bad input.
#include <string>

namespace sublift::cli {

int run_info(int argc, char** argv);
int run_render(int argc, char** argv);
int run_convert(int argc, char** argv);
int run_subdivide(int argc, char** argv);
int run_analyze(int argc, char** argv);
/// `rebuild`: the levels of a mesh another tool subdivided (docs/rebuild.md); also `analyze` without --base.
int run_rebuild(int argc, char** argv);
/// `fit`: a base and fitted levels for any triangle mesh (docs/fit.md; a first version).
int run_fit(int argc, char** argv);
int run_synthesize(int argc, char** argv);
int run_edit(int argc, char** argv);
/// `set`: a project's scheme, levels, gains, frames and edit level, as the modeler's panel sets them.
int run_set(int argc, char** argv);
int run_basis(int argc, char** argv);
int run_ffd(int argc, char** argv);
int run_animation(int argc, char** argv);
int run_coefficients(int argc, char** argv);
/// `experiment noise|fit|compress`: the papers' experiments (docs/experiments.md).
int run_experiment(int argc, char** argv);
/// `resample-sphere`: a star-shaped mesh sampled onto a subdivided octahedron (docs/resample_sphere.md).
int run_resample_sphere(int argc, char** argv);
/// `compress`: drop the smallest wavelets of a project (docs/compression.md).
int run_compress(int argc, char** argv);

/// `info` on a .sublift project (levels, per-level wavelet statistics).
int info_project(const std::string& file, bool json);
/// `info` on a lattice (.lattice, .ovm, .vtk): counts, cell sizes, feature dims, bounding box.
int info_shape(const std::string& file, bool json);

}  // namespace sublift::cli
