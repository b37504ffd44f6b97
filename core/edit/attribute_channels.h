#pragma once
// Attribute channels beside an editing session (issue 20: "positions move, attributes stay"):
// the session edits x, y, z; a project's other channels (colours, scalars) are kept as a
// hierarchy of their own over the same levels and merged back when the session is saved. The
// transform runs each channel on its own, so splitting and merging are exact.
#include <optional>
#include <string>

#include "core/multires/hierarchy.h"

namespace sublift {

/// Channels [first, first + count) of `h` as a hierarchy of their own (same levels and tables).
Hierarchy channel_range(const Hierarchy& h, int first, int count);

/// `a`'s channels then `b`'s, per vertex; both must have the same levels (same vertex counts).
/// Throws Error otherwise.
Hierarchy merge_channels(const Hierarchy& a, const Hierarchy& b);

/// `attributes` (a hierarchy of attribute channels) made to fit `target`'s levels: the same base
/// (vertex count and faces) is required; other features or a scheme of the same refinement are
/// taken by analysing the attributes' finest values again on the target's base and scheme;
/// missing finest levels are added with zero detail (a subdivide), extra ones cut (Delete
/// Higher). Empty, with `*why`, when the base differs or the refinement changed.
std::optional<Hierarchy> attributes_for(const Hierarchy& attributes, const Hierarchy& target, std::string* why = nullptr);

}  // namespace sublift
