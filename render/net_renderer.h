#pragma once
// Draws the control net of the edit level: its edges as lines and its vertices as round point
// sprites, coloured by feature class and per-vertex state (hover, selected, soft-selection
// weight), with optional depth cueing, x-ray and a clipping plane.
//
// Layout. One GL vertex per net vertex in four vertex-shared attribute buffers: position (float
// vec3 relative to `center`, the centre of the bounds at set_positions), feature class (u8),
// state (u8) and soft weight (float). Edges are one element buffer of vertex pairs sorted by
// feature class, so each class is one draw call with its own colour and nothing is duplicated
// per edge: update_positions() rewrites only the changed vertices (grouped into a few ranges,
// upload_ranges()), whatever their number of edges.
//
// X-ray draws the net twice: first only where it lies behind what is already in the depth
// buffer (the surface), faded, then depth-tested as usual; so hidden parts show as a ghost and
// visible parts stay crisp. The clipping plane keeps the side where dot(plane, (x, 1)) >= 0
// (world coordinates), through GL_CLIP_DISTANCE0, so points and edges beyond it vanish.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/camera.h"
#include "render/mesh_buffers.h"

namespace sublift {

class ShaderProgram;

/// Colours of the net (linear RGB as written to the framebuffer).
struct NetColors {
  glm::vec3 point{0.10f, 0.11f, 0.14f};      // ordinary control point: near black
  glm::vec3 crease{0.05f, 0.45f, 0.95f};     // feature class 1: crease/boundary vertex or edge
  glm::vec3 corner{0.90f, 0.10f, 0.60f};     // feature class 2: corner vertex (or edge)
  glm::vec3 selected{1.00f, 0.50f, 0.00f};   // state 2
  glm::vec3 hover{0.00f, 0.95f, 0.95f};      // state 1 (wins over selected)
  glm::vec3 soft{1.00f, 0.85f, 0.15f};       // tint of soft-selection weight 1 (unselected)
  glm::vec4 edge{0.12f, 0.13f, 0.17f, 0.85f};  // ordinary edge (alpha blends)
  glm::vec3 fog{0.80f, 0.83f, 0.88f};        // depth cue fades far parts towards this
};

struct NetStyle {
  bool depth_cue = false;  // fade and shrink far parts of the net (lattices)
  bool xray = false;       // show the net through the surface (ghosted where hidden)
  bool clip = false;       // apply clip_plane
  glm::vec4 clip_plane{0, 0, 1, 0};  // keeps dot(plane, (x, y, z, 1)) >= 0, world coordinates
  float point_size = 6;    // pixels for ordinary points; hover/selected are 1.5x
  bool points = true;      // draw the vertices
  bool edges = true;       // draw the edges
  NetColors colors;
};

/// GPU copy of one control net; needs a current GL 3.3 context.
class NetRenderer {
 public:
  /// Compiles net.vert/net.frag; throws ShaderError.
  NetRenderer();
  ~NetRenderer();
  NetRenderer(const NetRenderer&) = delete;
  NetRenderer& operator=(const NetRenderer&) = delete;

  /// Replaces the topology: edges as vertex pairs, per-edge and per-vertex feature class (0
  /// ordinary, 1 crease/boundary, 2 corner; empty spans mean all 0). Resets positions to the
  /// origin and state to none. Throws TopologyError on an index >= num_vertices or size mismatch.
  void set_topology(std::span<const std::uint32_t> edge_pairs, std::span<const std::uint8_t> edge_feature,
                    std::span<const std::uint8_t> vertex_feature, std::size_t num_vertices);
  /// Uploads all positions (3 doubles per vertex) and recentres; throws Error on a size mismatch.
  void set_positions(std::span<const double> xyz);
  /// Uploads only vertices `changed` of the full position array `xyz` (3 doubles per vertex, as
  /// after the change); keeps the centre and grows the bounds.
  void update_positions(std::span<const double> xyz, std::span<const std::uint32_t> changed);
  /// Per-vertex state (0 none, 1 hover, 2 selected, 3 hidden) and soft-selection weight in [0, 1]; empty
  /// spans mean all 0.
  void set_state(std::span<const std::uint8_t> state, std::span<const float> soft_weight);
  /// Uploads only vertices `changed` of the full state/weight arrays (e.g. a hover change).
  void update_state(std::span<const std::uint8_t> state, std::span<const float> soft_weight,
                    std::span<const std::uint32_t> changed);
  /// Draws into the bound framebuffer over what is there (depth-tested against it).
  void draw(const OrbitCamera& camera, const NetStyle& style) const;

  /// Bounds of the positions (set_positions, grown by update_positions).
  const Bounds& bounds() const { return bounds_; }
  std::size_t num_vertices() const { return num_vertices_; }

 private:
  std::unique_ptr<ShaderProgram> program_;
  unsigned vao_ = 0, position_vbo_ = 0, feature_vbo_ = 0, state_vbo_ = 0, weight_vbo_ = 0, edge_ebo_ = 0;
  std::size_t num_vertices_ = 0;
  std::size_t edge_first_[3] = {0, 0, 0}, edge_count_[3] = {0, 0, 0};  // in vertex pairs
  glm::dvec3 center_{0.0};
  Bounds bounds_;
};

// ---- helpers shared with LimitSurfaceRenderer ----

/// Half-open vertex ranges [first, last) covering `changed` (any order, duplicates allowed) for
/// partial uploads: runs closer than `max_gap` are merged, and if more than `max_ranges` remain
/// the smallest gaps are bridged too. Ascending, disjoint.
std::vector<std::pair<std::uint32_t, std::uint32_t>> upload_ranges(std::span<const std::uint32_t> changed,
                                                                   std::uint32_t max_gap = 64,
                                                                   std::size_t max_ranges = 64);

/// Writes vertices [first, last) of `xyz` (3 doubles each) as float vec3 into GL array buffer
/// `buffer` at their own offset: minus `center`, or normalised (zero stays zero) when
/// `normalize`. Needs a current context; the buffer must hold at least `last` vec3.
void upload_vec3_range(unsigned buffer, std::span<const double> xyz, const glm::dvec3& center,
                       std::uint32_t first, std::uint32_t last, bool normalize = false);

/// Bounds of all points of `xyz` (3 doubles each).
Bounds point_bounds(std::span<const double> xyz);

}  // namespace sublift
