#include "render/limit_surface_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/base/errors.h"
#include "render/net_renderer.h"
#include "render/render_errors.h"
#include "render/shader_program.h"

namespace sublift {
namespace {

// The same clay as MeshRenderer, so the modeler and the viewer look alike.
constexpr glm::vec3 kClayColor{0.82f, 0.71f, 0.60f};
constexpr glm::vec3 kBackColor{0.55f, 0.60f, 0.72f};
constexpr glm::vec4 kWireColor{0.08f, 0.08f, 0.10f, 0.75f};
// Wire opacity ramps from kMinWireFade at kFadeStartPixels-long edges to 1 at kFadeEndPixels.
constexpr double kFadeStartPixels = 1.5;
constexpr double kFadeEndPixels = 12.0;
constexpr double kMinWireFade = 0.10;
constexpr std::size_t kEdgeSample = 4096;

float wire_fade(double edge_pixels) {
  const double t = (edge_pixels - kFadeStartPixels) / (kFadeEndPixels - kFadeStartPixels);
  return static_cast<float>(std::clamp(t, kMinWireFade, 1.0));
}

glm::vec4 local_plane(const glm::vec4& plane, const glm::dvec3& center) {
  return glm::vec4(plane.x, plane.y, plane.z,
                   static_cast<float>(glm::dot(glm::dvec3(plane), center) + static_cast<double>(plane.w)));
}

}  // namespace

LimitSurfaceRenderer::LimitSurfaceRenderer()
    : program_(std::make_unique<ShaderProgram>("limit.vert", "limit.frag")) {
  GLuint buffers[5];
  glGenBuffers(5, buffers);
  position_vbo_ = buffers[0];
  normal_vbo_ = buffers[1];
  scalar_vbo_ = buffers[2];
  triangle_ebo_ = buffers[3];
  edge_ebo_ = buffers[4];
  glGenBuffers(1, &texcoord_vbo_);
  glGenVertexArrays(1, &fill_vao_);
  glGenVertexArrays(1, &wire_vao_);
  for (const GLuint vao : {fill_vao_, wire_vao_}) {
    glBindVertexArray(vao);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, vao == fill_vao_ ? triangle_ebo_ : edge_ebo_);
    glBindBuffer(GL_ARRAY_BUFFER, position_vbo_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, normal_vbo_);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, scalar_vbo_);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, texcoord_vbo_);
    glEnableVertexAttribArray(3);
    glVertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

LimitSurfaceRenderer::~LimitSurfaceRenderer() {
  const GLuint buffers[] = {position_vbo_, normal_vbo_, scalar_vbo_, triangle_ebo_, edge_ebo_};
  glDeleteBuffers(5, buffers);
  glDeleteBuffers(1, &texcoord_vbo_);
  if (texture_) glDeleteTextures(1, &texture_);
  const GLuint vaos[] = {fill_vao_, wire_vao_};
  glDeleteVertexArrays(2, vaos);
}

void LimitSurfaceRenderer::set_topology(std::span<const std::uint32_t> face_offsets,
                                        std::span<const std::uint32_t> face_corners,
                                        std::size_t num_vertices) {
  if (face_offsets.empty() || face_offsets.front() != 0 || face_offsets.back() != face_corners.size()) {
    throw TopologyError("limit surface: face offsets must start at 0 and end at the corner count (" +
                        std::to_string(face_corners.size()) + ")");
  }
  if (num_vertices > static_cast<std::size_t>(std::numeric_limits<GLint>::max())) {
    throw RenderError("limit surface too large to draw");
  }
  const std::size_t num_faces = face_offsets.size() - 1;
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint64_t> edges;  // (min << 32 | max)
  triangles.reserve(3 * face_corners.size());
  edges.reserve(face_corners.size());
  for (std::size_t f = 0; f < num_faces; ++f) {
    const std::uint32_t begin = face_offsets[f], end = face_offsets[f + 1];
    if (end < begin) throw TopologyError("limit surface: face offsets decrease at face " + std::to_string(f));
    const std::uint32_t k = end - begin;
    for (std::uint32_t i = begin; i < end; ++i) {
      if (face_corners[i] >= num_vertices) {
        throw TopologyError("limit surface: face " + std::to_string(f) + " names vertex " +
                            std::to_string(face_corners[i]) + " of " + std::to_string(num_vertices));
      }
    }
    if (k < 3) continue;
    for (std::uint32_t i = 0; i < k; ++i) {
      const std::uint32_t a = face_corners[begin + i], b = face_corners[begin + (i + 1) % k];
      edges.push_back(static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b));
    }
    for (std::uint32_t i = 1; i + 1 < k; ++i) {
      triangles.insert(triangles.end(),
                       {face_corners[begin], face_corners[begin + i], face_corners[begin + i + 1]});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::uint32_t> edge_pairs(2 * edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    edge_pairs[2 * e] = static_cast<std::uint32_t>(edges[e] >> 32);
    edge_pairs[2 * e + 1] = static_cast<std::uint32_t>(edges[e]);
  }
  if (triangles.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()) ||
      edge_pairs.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max())) {
    throw RenderError("limit surface too large to draw: too many triangles");
  }
  // An evenly spread sample of edges, for the wireframe's mean on-screen length.
  edge_sample_.clear();
  const std::size_t stride = std::max<std::size_t>(edges.size() / kEdgeSample, 1);
  for (std::size_t e = 0; e < edges.size(); e += stride) {
    edge_sample_.insert(edge_sample_.end(), {edge_pairs[2 * e], edge_pairs[2 * e + 1]});
  }

  num_vertices_ = num_vertices;
  triangle_index_count_ = triangles.size();
  edge_index_count_ = edge_pairs.size();
  center_ = glm::dvec3(0.0);
  bounds_ = Bounds{};
  mean_edge_length_ = 0.0;
  glBindVertexArray(fill_vao_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(std::uint32_t)),
               triangles.empty() ? nullptr : triangles.data(), GL_STATIC_DRAW);
  glBindVertexArray(wire_vao_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(edge_pairs.size() * sizeof(std::uint32_t)),
               edge_pairs.empty() ? nullptr : edge_pairs.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  const std::vector<float> zeros(3 * num_vertices, 0.0f);
  for (const GLuint buffer : {position_vbo_, normal_vbo_}) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(zeros.size() * sizeof(float)), zeros.data(),
                 GL_DYNAMIC_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, scalar_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(num_vertices * sizeof(float)), zeros.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, texcoord_vbo_);
  const std::vector<float> uv_zeros(2 * num_vertices, 0.0f);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(uv_zeros.size() * sizeof(float)), uv_zeros.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void LimitSurfaceRenderer::set_positions_normals(std::span<const double> xyz, std::span<const double> normals) {
  if (xyz.size() != 3 * num_vertices_ || normals.size() != 3 * num_vertices_) {
    throw Error("limit surface: " + std::to_string(xyz.size()) + " coordinates and " +
                std::to_string(normals.size()) + " normal components for " + std::to_string(num_vertices_) +
                " vertices");
  }
  bounds_ = point_bounds(xyz);
  center_ = bounds_.empty ? glm::dvec3(0.0) : 0.5 * (bounds_.min + bounds_.max);
  const auto n = static_cast<std::uint32_t>(num_vertices_);
  upload_vec3_range(position_vbo_, xyz, center_, 0, n);
  upload_vec3_range(normal_vbo_, normals, glm::dvec3(0.0), 0, n, true);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  double sum = 0.0;
  for (std::size_t i = 0; i < edge_sample_.size(); i += 2) {
    const std::size_t a = 3 * static_cast<std::size_t>(edge_sample_[i]);
    const std::size_t b = 3 * static_cast<std::size_t>(edge_sample_[i + 1]);
    sum += glm::distance(glm::dvec3(xyz[a], xyz[a + 1], xyz[a + 2]), glm::dvec3(xyz[b], xyz[b + 1], xyz[b + 2]));
  }
  mean_edge_length_ = edge_sample_.empty() ? 0.0 : sum / static_cast<double>(edge_sample_.size() / 2);
}

void LimitSurfaceRenderer::update(std::span<const double> xyz, std::span<const double> normals,
                                  std::span<const std::uint32_t> changed_vertices) {
  if (xyz.size() != 3 * num_vertices_ || normals.size() != 3 * num_vertices_) {
    throw Error("limit surface: update needs the full position and normal arrays");
  }
  for (const auto& [first, last] : upload_ranges(changed_vertices)) {
    if (last > num_vertices_) throw Error("limit surface: changed vertex out of range");
    upload_vec3_range(position_vbo_, xyz, center_, first, last);
    upload_vec3_range(normal_vbo_, normals, glm::dvec3(0.0), first, last, true);
    const Bounds b = point_bounds(
        xyz.subspan(3 * static_cast<std::size_t>(first), 3 * static_cast<std::size_t>(last - first)));
    if (bounds_.empty) {
      bounds_ = b;
    } else if (!b.empty) {
      bounds_.min = glm::min(bounds_.min, b.min);
      bounds_.max = glm::max(bounds_.max, b.max);
    }
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void LimitSurfaceRenderer::set_scalar(std::span<const float> value01) {
  if (!value01.empty() && value01.size() != num_vertices_) {
    throw Error("limit surface: " + std::to_string(value01.size()) + " scalars for " +
                std::to_string(num_vertices_) + " vertices");
  }
  const std::vector<float> zeros(value01.empty() ? num_vertices_ : 0, 0.0f);
  glBindBuffer(GL_ARRAY_BUFFER, scalar_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(num_vertices_ * sizeof(float)),
               value01.empty() ? zeros.data() : value01.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void LimitSurfaceRenderer::set_texcoords(std::span<const float> uv) {
  if (!uv.empty() && uv.size() != 2 * num_vertices_)
    throw Error("limit surface: " + std::to_string(uv.size() / 2) + " texture coordinates for " + std::to_string(num_vertices_) + " vertices");
  const std::vector<float> zeros(uv.empty() ? 2 * num_vertices_ : 0, 0.0f);
  glBindBuffer(GL_ARRAY_BUFFER, texcoord_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(2 * num_vertices_ * sizeof(float)), uv.empty() ? zeros.data() : uv.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void LimitSurfaceRenderer::set_texture(std::span<const std::uint8_t> rgba, int width, int height, int wrap_s, int wrap_t) {
  if (width < 1 || height < 1 || rgba.size() != 4 * std::size_t(width) * std::size_t(height))
    throw Error("limit surface: a texture of " + std::to_string(rgba.size()) + " bytes for " + std::to_string(width) + "x" + std::to_string(height));
  const auto wrap = [](int w) { return w == 33071 ? GL_CLAMP_TO_EDGE : w == 33648 ? GL_MIRRORED_REPEAT : GL_REPEAT; };
  if (!texture_) glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Rows go up from the bottom in GL: the image's top row is at v = 1, as OBJ's v runs.
  std::vector<std::uint8_t> flipped(rgba.size());
  const std::size_t row = 4 * std::size_t(width);
  for (int y = 0; y < height; ++y)
    std::copy_n(rgba.data() + row * std::size_t(height - 1 - y), row, flipped.data() + row * std::size_t(y));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap(wrap_s));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap(wrap_t));
  glBindTexture(GL_TEXTURE_2D, 0);
}

void LimitSurfaceRenderer::draw(const OrbitCamera& camera, const SurfaceStyle& style) const {
  if (num_vertices_ == 0 || triangle_index_count_ == 0) return;
  const glm::mat4 model_view(camera.view() * glm::translate(glm::dmat4(1.0), center_));
  const glm::mat4 projection(camera.projection());
  program_->use();
  program_->set("u_model_view", model_view);
  program_->set("u_projection", projection);
  // llvmpipe clips by gl_ClipDistance even with GL_CLIP_DISTANCE0 disabled: keep-all plane.
  program_->set("u_clip_plane", style.clip ? local_plane(style.clip_plane, center_) : glm::vec4(0, 0, 0, 1));
  program_->set("u_orthographic", camera.orthographic ? 1.0f : 0.0f);
  program_->set("u_smooth", style.smooth ? 1.0f : 0.0f);
  program_->set("u_color_map", style.color_map ? 1.0f : 0.0f);
  const bool textured = style.textured && texture_;
  program_->set("u_textured", textured ? 1.0f : 0.0f);
  if (textured) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture_);
    program_->set("u_texture", 0);
  }
  program_->set("u_front_color", kClayColor);
  program_->set("u_back_color", kBackColor);
  if (style.clip) glEnable(GL_CLIP_DISTANCE0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);

  // Push the fill back so the edges drawn at the same depth win.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  program_->set("u_wire", 0.0f);
  glBindVertexArray(fill_vao_);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(triangle_index_count_), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);

  if (style.wireframe && edge_index_count_ > 0) {
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    const double edge_pixels = mean_edge_length_ / camera.world_per_pixel();
    program_->set("u_wire", 1.0f);
    program_->set("u_wire_color", glm::vec4(glm::vec3(kWireColor), kWireColor.a * wire_fade(edge_pixels)));
    glBindVertexArray(wire_vao_);
    glDrawElements(GL_LINES, static_cast<GLsizei>(edge_index_count_), GL_UNSIGNED_INT, nullptr);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  glDisable(GL_CLIP_DISTANCE0);
  if (textured) glBindTexture(GL_TEXTURE_2D, 0);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace sublift
