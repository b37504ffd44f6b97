#include "render/net_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"
#include "render/render_errors.h"
#include "render/shader_program.h"

namespace sublift {
namespace {

// Shader-side depth bias (NDC units, times w) so the net wins over a surface through the same
// points, and points over edges.
constexpr float kEdgeDepthBias = 4e-4f;
constexpr float kPointDepthBias = 8e-4f;
constexpr float kGhostAlpha = 0.5f;  // x-ray: opacity of the parts behind the surface

template <typename T>
void allocate(GLuint buffer, std::size_t count, const T* data = nullptr) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(count * sizeof(T)), data, GL_DYNAMIC_DRAW);
}

template <typename T>
void upload_range(GLuint buffer, std::span<const T> values, std::uint32_t first, std::uint32_t last) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(first * sizeof(T)),
                  static_cast<GLsizeiptr>((last - first) * sizeof(T)), values.data() + first);
}

// The plane in the uploaded (centred) coordinates: n.(l + c) + d = n.l + (n.c + d).
glm::vec4 local_plane(const glm::vec4& plane, const glm::dvec3& center) {
  const glm::dvec3 n(plane);
  return glm::vec4(plane.x, plane.y, plane.z,
                   static_cast<float>(glm::dot(n, center) + static_cast<double>(plane.w)));
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> upload_ranges(std::span<const std::uint32_t> changed,
                                                                   std::uint32_t max_gap,
                                                                   std::size_t max_ranges) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges;
  if (changed.empty()) return ranges;
  std::vector<std::uint32_t> sorted(changed.begin(), changed.end());
  std::sort(sorted.begin(), sorted.end());
  for (const std::uint32_t v : sorted) {
    if (!ranges.empty() && v <= ranges.back().second + max_gap) {
      ranges.back().second = std::max(ranges.back().second, v + 1);
    } else {
      ranges.emplace_back(v, v + 1);
    }
  }
  max_ranges = std::max<std::size_t>(max_ranges, 1);
  if (ranges.size() > max_ranges) {
    // Keep the max_ranges - 1 largest gaps as splits, bridge the others.
    std::vector<std::uint32_t> gaps(ranges.size() - 1);
    for (std::size_t i = 0; i + 1 < ranges.size(); ++i) gaps[i] = ranges[i + 1].first - ranges[i].second;
    std::vector<std::uint32_t> by_size = gaps;
    std::nth_element(by_size.begin(), by_size.begin() + static_cast<std::ptrdiff_t>(max_ranges - 1),
                     by_size.end(), std::greater<>());
    const std::uint32_t threshold = by_size[max_ranges - 1];  // gaps above it split for sure
    std::size_t equal_splits = 0;  // gaps equal to the threshold that may still split
    for (std::size_t i = 0; i < max_ranges - 1; ++i) equal_splits += by_size[i] == threshold;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> merged = {ranges[0]};
    for (std::size_t i = 0; i + 1 < ranges.size(); ++i) {
      bool split = gaps[i] > threshold;
      if (!split && gaps[i] == threshold && equal_splits > 0) {
        split = true;
        --equal_splits;
      }
      if (split) {
        merged.push_back(ranges[i + 1]);
      } else {
        merged.back().second = ranges[i + 1].second;
      }
    }
    ranges = std::move(merged);
  }
  return ranges;
}

void upload_vec3_range(unsigned buffer, std::span<const double> xyz, const glm::dvec3& center,
                       std::uint32_t first, std::uint32_t last, bool normalize) {
  if (last <= first) return;
  std::vector<float> local(3 * static_cast<std::size_t>(last - first));
  for (std::uint32_t v = first; v < last; ++v) {
    glm::dvec3 p(xyz[3 * static_cast<std::size_t>(v)], xyz[3 * static_cast<std::size_t>(v) + 1],
                 xyz[3 * static_cast<std::size_t>(v) + 2]);
    if (normalize) {
      const double length = glm::length(p);
      p = length > 0.0 ? p / length : glm::dvec3(0.0);
    } else {
      p -= center;
    }
    float* out = &local[3 * static_cast<std::size_t>(v - first)];
    out[0] = static_cast<float>(p.x);
    out[1] = static_cast<float>(p.y);
    out[2] = static_cast<float>(p.z);
  }
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(first * 3 * sizeof(float)),
                  static_cast<GLsizeiptr>(local.size() * sizeof(float)), local.data());
}

Bounds point_bounds(std::span<const double> xyz) {
  Bounds b;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const glm::dvec3 p(xyz[i], xyz[i + 1], xyz[i + 2]);
    if (b.empty) {
      b.min = b.max = p;
      b.empty = false;
    } else {
      b.min = glm::min(b.min, p);
      b.max = glm::max(b.max, p);
    }
  }
  return b;
}

NetRenderer::NetRenderer() : program_(std::make_unique<ShaderProgram>("net.vert", "net.frag")) {
  glGenVertexArrays(1, &vao_);
  GLuint buffers[5];
  glGenBuffers(5, buffers);
  position_vbo_ = buffers[0];
  feature_vbo_ = buffers[1];
  state_vbo_ = buffers[2];
  weight_vbo_ = buffers[3];
  edge_ebo_ = buffers[4];
  glBindVertexArray(vao_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, edge_ebo_);
  glBindBuffer(GL_ARRAY_BUFFER, position_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, feature_vbo_);
  glEnableVertexAttribArray(1);
  glVertexAttribIPointer(1, 1, GL_UNSIGNED_BYTE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, state_vbo_);
  glEnableVertexAttribArray(2);
  glVertexAttribIPointer(2, 1, GL_UNSIGNED_BYTE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, weight_vbo_);
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

NetRenderer::~NetRenderer() {
  const GLuint buffers[] = {position_vbo_, feature_vbo_, state_vbo_, weight_vbo_, edge_ebo_};
  glDeleteBuffers(5, buffers);
  glDeleteVertexArrays(1, &vao_);
}

void NetRenderer::set_topology(std::span<const std::uint32_t> edge_pairs,
                               std::span<const std::uint8_t> edge_feature,
                               std::span<const std::uint8_t> vertex_feature, std::size_t num_vertices) {
  if (edge_pairs.size() % 2 != 0) throw TopologyError("net: edge list has an odd number of indices");
  const std::size_t num_edges = edge_pairs.size() / 2;
  if (!edge_feature.empty() && edge_feature.size() != num_edges) {
    throw TopologyError("net: " + std::to_string(edge_feature.size()) + " edge feature classes for " +
                        std::to_string(num_edges) + " edges");
  }
  if (!vertex_feature.empty() && vertex_feature.size() != num_vertices) {
    throw TopologyError("net: " + std::to_string(vertex_feature.size()) + " vertex feature classes for " +
                        std::to_string(num_vertices) + " vertices");
  }
  if (num_vertices > static_cast<std::size_t>(std::numeric_limits<GLint>::max()) ||
      edge_pairs.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max())) {
    throw RenderError("net too large to draw");
  }
  for (std::size_t i = 0; i < edge_pairs.size(); ++i) {
    if (edge_pairs[i] >= num_vertices) {
      throw TopologyError("net: edge " + std::to_string(i / 2) + " names vertex " +
                          std::to_string(edge_pairs[i]) + " of " + std::to_string(num_vertices));
    }
  }
  // Edges grouped by class (classes above 2 count as 2), stable within a class.
  std::vector<std::uint32_t> sorted(edge_pairs.size());
  std::size_t count[3] = {0, 0, 0};
  auto cls = [&](std::size_t e) { return edge_feature.empty() ? 0 : std::min<int>(edge_feature[e], 2); };
  for (std::size_t e = 0; e < num_edges; ++e) ++count[cls(e)];
  std::size_t next[3] = {0, count[0], count[0] + count[1]};
  for (int c = 0; c < 3; ++c) {
    edge_first_[c] = next[c];
    edge_count_[c] = count[c];
  }
  for (std::size_t e = 0; e < num_edges; ++e) {
    const std::size_t slot = next[cls(e)]++;
    sorted[2 * slot] = edge_pairs[2 * e];
    sorted[2 * slot + 1] = edge_pairs[2 * e + 1];
  }
  num_vertices_ = num_vertices;
  center_ = glm::dvec3(0.0);
  bounds_ = Bounds{};

  glBindVertexArray(vao_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, edge_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(sorted.size() * sizeof(std::uint32_t)),
               sorted.empty() ? nullptr : sorted.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  const std::vector<float> zero_positions(3 * num_vertices, 0.0f);
  allocate(position_vbo_, zero_positions.size(), zero_positions.data());
  std::vector<std::uint8_t> features(num_vertices, 0);
  for (std::size_t v = 0; v < vertex_feature.size(); ++v) features[v] = std::min<std::uint8_t>(vertex_feature[v], 2);
  allocate(feature_vbo_, num_vertices, features.data());
  const std::vector<std::uint8_t> zero_state(num_vertices, 0);
  allocate(state_vbo_, num_vertices, zero_state.data());
  const std::vector<float> zero_weight(num_vertices, 0.0f);
  allocate(weight_vbo_, num_vertices, zero_weight.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void NetRenderer::set_positions(std::span<const double> xyz) {
  if (xyz.size() != 3 * num_vertices_) {
    throw Error("net: " + std::to_string(xyz.size()) + " coordinates for " + std::to_string(num_vertices_) +
                " vertices");
  }
  bounds_ = point_bounds(xyz);
  center_ = bounds_.empty ? glm::dvec3(0.0) : 0.5 * (bounds_.min + bounds_.max);
  upload_vec3_range(position_vbo_, xyz, center_, 0, static_cast<std::uint32_t>(num_vertices_));
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void NetRenderer::update_positions(std::span<const double> xyz, std::span<const std::uint32_t> changed) {
  if (xyz.size() != 3 * num_vertices_) throw Error("net: update needs the full position array");
  for (const auto& [first, last] : upload_ranges(changed)) {
    if (last > num_vertices_) throw Error("net: changed vertex out of range");
    upload_vec3_range(position_vbo_, xyz, center_, first, last);
    const Bounds b = point_bounds(xyz.subspan(3 * static_cast<std::size_t>(first), 3 * static_cast<std::size_t>(last - first)));
    if (bounds_.empty) {
      bounds_ = b;
    } else if (!b.empty) {
      bounds_.min = glm::min(bounds_.min, b.min);
      bounds_.max = glm::max(bounds_.max, b.max);
    }
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void NetRenderer::set_state(std::span<const std::uint8_t> state, std::span<const float> soft_weight) {
  if ((!state.empty() && state.size() != num_vertices_) ||
      (!soft_weight.empty() && soft_weight.size() != num_vertices_)) {
    throw Error("net: state or weight array does not match the vertex count");
  }
  const std::vector<std::uint8_t> zero_state(state.empty() ? num_vertices_ : 0, 0);
  const std::vector<float> zero_weight(soft_weight.empty() ? num_vertices_ : 0, 0.0f);
  allocate(state_vbo_, num_vertices_, state.empty() ? zero_state.data() : state.data());
  allocate(weight_vbo_, num_vertices_, soft_weight.empty() ? zero_weight.data() : soft_weight.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void NetRenderer::update_state(std::span<const std::uint8_t> state, std::span<const float> soft_weight,
                               std::span<const std::uint32_t> changed) {
  if (state.size() != num_vertices_ || soft_weight.size() != num_vertices_) {
    throw Error("net: update_state needs the full state and weight arrays");
  }
  for (const auto& [first, last] : upload_ranges(changed)) {
    if (last > num_vertices_) throw Error("net: changed vertex out of range");
    upload_range(state_vbo_, state, first, last);
    upload_range(weight_vbo_, soft_weight, first, last);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void NetRenderer::draw(const OrbitCamera& camera, const NetStyle& style) const {
  if (num_vertices_ == 0 || (!style.points && !style.edges)) return;
  const glm::mat4 model_view(camera.view() * glm::translate(glm::dmat4(1.0), center_));
  const glm::mat4 projection(camera.projection());
  // Depth cue range: the eye depths of the net's bounding sphere.
  float cue_near = 0.0f, cue_far = 0.0f;
  if (style.depth_cue && !bounds_.empty) {
    const glm::dvec3 c = 0.5 * (bounds_.min + bounds_.max);
    const double r = 0.5 * glm::length(bounds_.max - bounds_.min);
    const double d = glm::dot(c - camera.eye(), camera.forward());
    cue_near = static_cast<float>(d - r);
    cue_far = static_cast<float>(d + r);
  }

  program_->use();
  program_->set("u_model_view", model_view);
  program_->set("u_projection", projection);
  // llvmpipe clips by gl_ClipDistance even with GL_CLIP_DISTANCE0 disabled: keep-all plane.
  program_->set("u_clip_plane", style.clip ? local_plane(style.clip_plane, center_) : glm::vec4(0, 0, 0, 1));
  program_->set("u_point_size", style.point_size);
  program_->set("u_depth_cue", style.depth_cue && cue_far > cue_near ? 1.0f : 0.0f);
  program_->set("u_cue_near", cue_near);
  program_->set("u_cue_far", cue_far);
  const NetColors& k = style.colors;
  program_->set("u_color_point", k.point);
  program_->set("u_color_crease", k.crease);
  program_->set("u_color_corner", k.corner);
  program_->set("u_color_selected", k.selected);
  program_->set("u_color_hover", k.hover);
  program_->set("u_color_soft", k.soft);
  program_->set("u_color_fog", k.fog);

  glBindVertexArray(vao_);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_PROGRAM_POINT_SIZE);
  if (style.clip) glEnable(GL_CLIP_DISTANCE0);

  const glm::vec4 edge_colors[3] = {k.edge, glm::vec4(k.crease, 1.0f), glm::vec4(k.corner, 1.0f)};
  auto draw_all = [&](float alpha, bool write_depth) {
    program_->set("u_alpha", alpha);
    if (style.edges) {
      // Edges do not write depth, so they never cover the points drawn after them.
      glDepthMask(GL_FALSE);
      program_->set("u_points", 0.0f);
      program_->set("u_depth_bias", kEdgeDepthBias);
      for (int c = 0; c < 3; ++c) {
        if (edge_count_[c] == 0) continue;
        program_->set("u_edge_color", edge_colors[c]);
        glDrawElements(GL_LINES, static_cast<GLsizei>(2 * edge_count_[c]), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(2 * edge_first_[c] * sizeof(std::uint32_t)));
      }
    }
    if (style.points) {
      glDepthMask(write_depth ? GL_TRUE : GL_FALSE);
      program_->set("u_points", 1.0f);
      program_->set("u_depth_bias", kPointDepthBias);
      glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(num_vertices_));
    }
  };
  if (style.xray) {
    // Ghost pass: only what lies behind the depth already drawn, without writing depth.
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_GREATER);
    draw_all(kGhostAlpha, false);
  }
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LEQUAL);
  draw_all(1.0f, true);
  glDepthMask(GL_TRUE);

  glDisable(GL_CLIP_DISTANCE0);
  glDisable(GL_PROGRAM_POINT_SIZE);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace sublift
