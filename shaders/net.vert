// Control net: one vertex per net vertex, drawn as GL_LINES (indexed edges) and GL_POINTS.
// Colour is decided here from feature class, state and soft weight (see NetColors).
layout(location = 0) in vec3 a_position;  // relative to the net's centre
layout(location = 1) in uint a_feature;   // 0 ordinary, 1 crease/boundary, 2 corner
layout(location = 2) in uint a_state;     // 0 none, 1 hover, 2 selected, 3 hidden (not drawn)
layout(location = 3) in float a_weight;   // soft-selection weight in [0, 1]

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform vec4 u_clip_plane;   // in the centred coordinates; kept where >= 0
uniform float u_points;      // 1 drawing points, 0 drawing edges
uniform float u_point_size;  // pixels
uniform float u_depth_bias;  // NDC units, pulls the net in front of a coincident surface
uniform float u_depth_cue;   // 1: fade and shrink with depth between u_cue_near and u_cue_far
uniform float u_cue_near;
uniform float u_cue_far;
uniform vec4 u_edge_color;   // colour of the edge class being drawn
uniform vec3 u_color_point;
uniform vec3 u_color_crease;
uniform vec3 u_color_corner;
uniform vec3 u_color_selected;
uniform vec3 u_color_hover;
uniform vec3 u_color_soft;
uniform vec3 u_color_fog;

out vec4 v_color;
flat out float v_outline;  // 1: draw a dark rim around the point

void main() {
  vec4 position_view = u_model_view * vec4(a_position, 1.0);
  gl_Position = u_projection * position_view;
  gl_Position.z -= u_depth_bias * gl_Position.w;
  gl_ClipDistance[0] = dot(u_clip_plane, vec4(a_position, 1.0));

  float cue = 0.0;
  if (u_depth_cue > 0.5) {
    cue = clamp((-position_view.z - u_cue_near) / (u_cue_far - u_cue_near), 0.0, 1.0);
  }
  float selected = a_state == 2u ? 1.0 : 0.0;
  vec4 color;
  float size = u_point_size;
  if (u_points > 0.5) {
    vec3 base = a_feature == 2u ? u_color_corner : (a_feature == 1u ? u_color_crease : u_color_point);
    if (a_feature != 0u) size *= 1.2;
    base = mix(base, u_color_soft, clamp(a_weight, 0.0, 1.0));
    if (a_state == 2u) {
      base = u_color_selected;
      size *= 1.5;
    }
    if (a_state == 1u) {
      base = u_color_hover;
      size *= 1.5;
    }
    color = vec4(base, 1.0);
  } else {
    // Edges between selected (or weighted) vertices lean towards the selection colour.
    float tint = max(selected, clamp(a_weight, 0.0, 1.0));
    color = vec4(mix(u_edge_color.rgb, u_color_selected, 0.7 * tint), mix(u_edge_color.a, 1.0, tint));
  }
  color.rgb = mix(color.rgb, u_color_fog, 0.7 * cue);
  color.a *= 1.0 - 0.5 * cue;
  v_color = color;
  v_outline = size >= 5.0 ? 1.0 : 0.0;
  gl_PointSize = max(size * (1.0 - 0.4 * cue), 1.0);
  // Hidden points (another time layer of an animation) fall outside the clip volume.
  if (a_state == 3u) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
