#pragma once
// The --png picture of `sublift-cli basis` (headless EGL rendering); only in builds with the
// renderer (SUBLIFT_HAVE_RENDER).
#include <span>
#include <string>

#include "core/multires/basis.h"

namespace sublift::cli {

/// Renders basis function `b` (finest limit positions `xyz`, 3 per vertex) to a width x height
/// PNG at `path`, coloured by value through the viewer's viridis map:
///   surfaces: the limit surface displaced along its normals by value (the largest |value| a
///     quarter of the support's diagonal), turned so the mean normal of the support points up,
///     cropped to the support plus a margin and seen from above-front;
///   curves: the displaced curve as a ribbon over the undisplaced one (grey-free, value 0 colour);
///   lattices: the boundary surface behind the plane z = z(peak) plus the slice of finest faces
///     lying on that plane.
/// `symmetric`: the map is centred on 0 (+-max|value| -> 1/0; wavelets, dual functions); else
/// [min(0, min), max] -> [0, 1]. Throws RenderError when headless GL is unavailable.
void write_basis_png(const std::string& path, const BasisFunction& b, std::span<const double> xyz, bool symmetric,
                     int width, int height);

}  // namespace sublift::cli
