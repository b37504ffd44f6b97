#include "render/mesh_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstddef>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/render_errors.h"
#include "render/shader_program.h"

namespace sublift {
namespace {

// A warm neutral clay; back sides a cooler grey-blue.
constexpr glm::vec3 kClayColor{0.82f, 0.71f, 0.60f};
constexpr glm::vec3 kBackColor{0.55f, 0.60f, 0.72f};
constexpr glm::vec4 kWireColor{0.08f, 0.08f, 0.10f, 0.85f};
constexpr glm::vec4 kCurveColor{0.05f, 0.22f, 0.55f, 1.0f};  // polylines: deep blue, opaque
// Wire opacity ramps from kMinWireFade at kFadeStartPixels-long edges to 1 at kFadeEndPixels.
constexpr double kFadeStartPixels = 1.5;
constexpr double kFadeEndPixels = 12.0;
constexpr double kMinWireFade = 0.12;

double mean_edge_length(const MeshBuffers& buffers) {
  if (buffers.edges.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < buffers.edges.size(); i += 2) {
    sum += glm::distance(glm::dvec3(buffers.vertex_positions[buffers.edges[i]]),
                         glm::dvec3(buffers.vertex_positions[buffers.edges[i + 1]]));
  }
  return sum / static_cast<double>(buffers.edges.size() / 2);
}

float wire_fade(double edge_pixels) {
  const double t = (edge_pixels - kFadeStartPixels) / (kFadeEndPixels - kFadeStartPixels);
  return static_cast<float>(std::clamp(t, kMinWireFade, 1.0));
}

template <typename T>
void upload_buffer(GLenum target, GLuint buffer, const std::vector<T>& data) {
  glBindBuffer(target, buffer);
  glBufferData(target, static_cast<GLsizeiptr>(data.size() * sizeof(T)),
               data.empty() ? nullptr : data.data(), GL_STATIC_DRAW);
}

int checked_count(std::size_t n, const char* what) {
  if (n > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max())) {
    throw RenderError(std::string("mesh too large to draw: too many ") + what);
  }
  return static_cast<int>(n);
}

}  // namespace

MeshRenderer::MeshRenderer()
    : fill_program_(std::make_unique<ShaderProgram>("mesh.vert", "mesh.frag")),
      line_program_(std::make_unique<ShaderProgram>("lines.vert", "lines.frag")) {
  glGenVertexArrays(1, &fill_vao_);
  glGenBuffers(1, &fill_vbo_);
  glGenBuffers(1, &fill_ebo_);
  glBindVertexArray(fill_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, fill_vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, fill_ebo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(CornerVertex),
                        reinterpret_cast<const void*>(offsetof(CornerVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(CornerVertex),
                        reinterpret_cast<const void*>(offsetof(CornerVertex, normal)));

  glGenVertexArrays(1, &line_vao_);
  glGenBuffers(1, &line_vbo_);
  glGenBuffers(1, &line_ebo_);
  glBindVertexArray(line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, line_vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, line_ebo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);

  glGenVertexArrays(1, &curve_vao_);
  glGenBuffers(1, &curve_ebo_);
  glBindVertexArray(curve_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, line_vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, curve_ebo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindVertexArray(0);
}

MeshRenderer::~MeshRenderer() {
  const GLuint vaos[] = {fill_vao_, line_vao_, curve_vao_};
  const GLuint buffers[] = {fill_vbo_, fill_ebo_, line_vbo_, line_ebo_, curve_ebo_};
  glDeleteVertexArrays(3, vaos);
  glDeleteBuffers(5, buffers);
}

void MeshRenderer::upload(const SurfaceMesh& mesh) {
  const MeshBuffers buffers = build_mesh_buffers(mesh);
  bounds_ = drawn_bounds(mesh);
  center_ = buffers.center;
  mean_edge_length_ = mean_edge_length(buffers);
  triangle_index_count_ = checked_count(buffers.triangles.size(), "triangles");
  edge_index_count_ = checked_count(buffers.edges.size(), "edges");
  curve_index_count_ = checked_count(buffers.polyline_segments.size(), "polyline segments");
  // The element buffer binding is VAO state: bind the VAO before touching it.
  glBindVertexArray(fill_vao_);
  upload_buffer(GL_ARRAY_BUFFER, fill_vbo_, buffers.corners);
  upload_buffer(GL_ELEMENT_ARRAY_BUFFER, fill_ebo_, buffers.triangles);
  glBindVertexArray(line_vao_);
  upload_buffer(GL_ARRAY_BUFFER, line_vbo_, buffers.vertex_positions);
  upload_buffer(GL_ELEMENT_ARRAY_BUFFER, line_ebo_, buffers.edges);
  glBindVertexArray(curve_vao_);
  upload_buffer(GL_ELEMENT_ARRAY_BUFFER, curve_ebo_, buffers.polyline_segments);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void MeshRenderer::draw(const OrbitCamera& camera, const DisplayOptions& options) const {
  // Composed in double, then rounded: the centre offset cancels before float precision matters.
  const glm::mat4 model_view(camera.view() * glm::translate(glm::dmat4(1.0), center_));
  const glm::mat4 projection(camera.projection());

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  if (options.shaded && triangle_index_count_ > 0) {
    // Push the fill back so the edges drawn at the same depth win.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    fill_program_->use();
    fill_program_->set("u_model_view", model_view);
    fill_program_->set("u_projection", projection);
    fill_program_->set("u_front_color", kClayColor);
    fill_program_->set("u_back_color", kBackColor);
    fill_program_->set("u_orthographic", camera.orthographic ? 1.0f : 0.0f);
    glBindVertexArray(fill_vao_);
    glDrawElements(GL_TRIANGLES, triangle_index_count_, GL_UNSIGNED_INT, nullptr);
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  if (options.wireframe && edge_index_count_ > 0) {
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    line_program_->use();
    line_program_->set("u_model_view", model_view);
    line_program_->set("u_projection", projection);
    const double edge_pixels = mean_edge_length_ / camera.world_per_pixel();
    line_program_->set("u_color", glm::vec4(glm::vec3(kWireColor),
                                            kWireColor.a * wire_fade(edge_pixels)));
    glBindVertexArray(line_vao_);
    glDrawElements(GL_LINES, edge_index_count_, GL_UNSIGNED_INT, nullptr);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  if (curve_index_count_ > 0) {
    line_program_->use();
    line_program_->set("u_model_view", model_view);
    line_program_->set("u_projection", projection);
    line_program_->set("u_color", kCurveColor);
    glBindVertexArray(curve_vao_);
    glDrawElements(GL_LINES, curve_index_count_, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace sublift
