#pragma once
// The one scheme type. Its facts live in the registry (registry.h); this header is the type
// alone, so scheme builders and analyses can name a scheme without the table.
#include <cstdint>

namespace sublift {

// Linear, Cubic: Bertram's lifted wavelets on 1-to-2^dim splits of any polyhedral complex.
// Sqrt2: Wang & Ma's interpolatory sqrt(2) wavelets.
// LinearTri, Butterfly, Loop: the triangle-mesh schemes of Lounsbery, DeRose & Warren (paper
// 004) on the 1-to-4 triangle split (refine_tri.h), wavelets on the edge midpoints [v | e].
enum class Scheme : std::uint8_t { Linear, Cubic, Sqrt2, LinearTri, Butterfly, Loop };

}  // namespace sublift
