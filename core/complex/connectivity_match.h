#pragma once
// Does a finest-level shape read from a file have the connectivity of a refined base? The
// analysis of a file is only meaningful when its vertex i is the engine's vertex i; this is the
// check `sublift-cli analyze` runs before analysing.
#include <string>

#include "core/complex/complex.h"

namespace sublift {

/// Empty when `got` has `expected`'s dimension, vertex count and the same edges (curves),
/// faces (surfaces, lattices; either orientation, any order) and cells (as vertex sets);
/// else a sentence naming the first difference in vertex indices. Uses downward rows only.
std::string connectivity_mismatch(const Complex& expected, const Complex& got);

}  // namespace sublift
