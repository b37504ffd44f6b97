#include "core/anim/animation_edits.h"

#include "core/base/edit_lines.h"
#include "core/base/errors.h"
#include "core/base/file_io.h"

namespace sublift {

std::vector<AnimationEdit> parse_animation_edits(std::string_view text, const std::string& file) {
  static constexpr EditField kFields[] = {{"level", 64}, {"frame", 1 << 30}, {"point", 0xffffffffLL}};
  std::vector<AnimationEdit> edits;
  for (const EditLine& l : parse_edit_lines(text, file, kFields)) {
    AnimationEdit e;
    e.line = l.line;
    e.level = int(l.whole[0]);
    e.frame = int(l.whole[1]);
    e.point = std::uint32_t(l.whole[2]);
    for (int k = 0; k < 3; ++k) e.delta[k] = l.delta[std::size_t(k)];
    edits.push_back(e);
  }
  return edits;
}

std::vector<AnimationEdit> read_animation_edits(const std::string& path) {
  return parse_animation_edits(read_file_bytes(path, std::size_t(64) << 20), path);
}

std::uint32_t edit_vertex(const SpaceTime& st, const AnimationEdit& e, const std::string& file) {
  const int J = st.levels();
  if (e.level > J)
    throw InputError(file, e.line, "level " + std::to_string(e.level) + " is beyond the finest level " + std::to_string(J));
  const int stride = 1 << (J - e.level), frames = st.layers(J);
  if (e.frame >= frames)
    throw InputError(file, e.line, "frame " + std::to_string(e.frame) + " is beyond the last frame " + std::to_string(frames - 1));
  if (e.frame % stride != 0) {
    const int below = e.frame / stride * stride, above = below + stride;
    throw InputError(file, e.line, "level " + std::to_string(e.level) + " has layers only every " + std::to_string(stride) +
                                       " frames: frame " + std::to_string(e.frame) + " is not one (try " + std::to_string(below) +
                                       (above < frames ? " or " + std::to_string(above) : std::string()) + ")");
  }
  const std::uint32_t nvs = st.surface_vertices(e.level);
  if (e.point >= nvs)
    throw InputError(file, e.line, "point " + std::to_string(e.point) + " is not a vertex of level " + std::to_string(e.level) +
                                       " (it has " + std::to_string(nvs) + ")");
  return st.layer_vertices[std::size_t(e.level)][std::size_t(e.frame / stride) * nvs + e.point];
}

}  // namespace sublift
