#pragma once
// Colouring by wavelet magnitude (the modeler's "Colour by |w| of level" and `sublift-cli
// render --colour L`): the level-l wavelets live on the e/f/c vertices of level l+1; each such
// vertex gets |w| times the level's gain (Euclidean norm; 0 on the v-class vertices, which carry
// no level-l wavelet), the values are carried to the finest level by linear refinement (an
// edge/face/cell child takes the mean of its parent's corners) and divided by the largest, so
// 0..1 maps onto viridis.
#include <span>
#include <vector>

#include "core/multires/hierarchy.h"

namespace sublift {

/// One value in 0..1 per finest vertex; `gains` per level (empty: all 1). Throws Error when
/// `level` is outside 0..J-1 or the hierarchy has fewer than 3 channels.
std::vector<float> wavelet_magnitude_field(const Hierarchy& h, std::span<const double> gains, int level);

}  // namespace sublift
