#include "core/anim/animation_edits.h"

#include "core/base/errors.h"
#include "core/base/file_io.h"
#include "core/base/text_lines.h"

namespace sublift {

std::vector<AnimationEdit> parse_animation_edits(std::string_view text, const std::string& file) {
  LineReader lines(text, file, 1 << 16);
  std::vector<AnimationEdit> edits;
  std::vector<std::string_view> tokens;
  const char* names[3] = {"level", "frame", "point"};
  while (next_tokens(lines, tokens)) {
    const std::size_t line = lines.line_number();
    if (tokens.size() != 6)
      throw InputError(file, line, "expected 'level frame point dx dy dz', got " + std::to_string(tokens.size()) + " fields");
    AnimationEdit e;
    e.line = line;
    long long whole[3];
    for (int k = 0; k < 3; ++k) {
      const auto v = parse_int(tokens[std::size_t(k)]);
      if (!v || *v < 0 || *v > 0xffffffffLL)
        throw InputError(file, line, std::string(names[k]) + " must be a non-negative integer, got '" + printable(tokens[std::size_t(k)]) + "'");
      whole[k] = *v;
    }
    if (whole[0] > 64) throw InputError(file, line, "level " + std::to_string(whole[0]) + " is not a level");
    if (whole[1] > 1 << 30) throw InputError(file, line, "frame " + std::to_string(whole[1]) + " is not a frame");
    e.level = int(whole[0]);
    e.frame = int(whole[1]);
    e.point = std::uint32_t(whole[2]);
    for (int k = 0; k < 3; ++k) {
      const auto d = parse_double(tokens[std::size_t(3 + k)]);
      if (!d)
        throw InputError(file, line, std::string("d") + char('x' + k) + " must be a finite number, got '" +
                                         printable(tokens[std::size_t(3 + k)]) + "'");
      e.delta[k] = *d;
    }
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
