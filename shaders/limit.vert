// Limit surface: one vertex per surface vertex with its own normal and colour-map scalar.
layout(location = 0) in vec3 a_position;  // relative to the surface's centre
layout(location = 1) in vec3 a_normal;    // unit, or zero when unknown
layout(location = 2) in float a_scalar;   // colour-map value in [0, 1]
layout(location = 3) in vec2 a_texcoord;  // u, v (v up), when textured

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform vec4 u_clip_plane;  // in the centred coordinates; kept where >= 0

out vec3 v_position_view;
out vec3 v_normal_view;
out float v_scalar;
out vec2 v_texcoord;

void main() {
  vec4 position_view = u_model_view * vec4(a_position, 1.0);
  v_position_view = position_view.xyz;
  // The model-view matrix is a rotation plus translation, so it maps normals as well.
  v_normal_view = mat3(u_model_view) * a_normal;
  v_scalar = a_scalar;
  v_texcoord = a_texcoord;
  gl_ClipDistance[0] = dot(u_clip_plane, vec4(a_position, 1.0));
  gl_Position = u_projection * position_view;
}
