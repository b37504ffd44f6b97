// Limit surface: two-sided clay (as mesh.frag), a viridis colour map or a texture, smooth or flat; also the
// flat-coloured wireframe pass (u_wire = 1).
in vec3 v_position_view;
in vec3 v_normal_view;
in float v_scalar;
in vec2 v_texcoord;

uniform float u_wire;
uniform vec4 u_wire_color;
uniform float u_smooth;
uniform float u_color_map;
uniform float u_textured;
uniform sampler2D u_texture;
uniform vec3 u_front_color;
uniform vec3 u_back_color;
uniform float u_orthographic;

out vec4 frag_color;

// Viridis as a degree-6 polynomial (fit by Matt Zucker, CC0) to matplotlib's table.
vec3 viridis(float t) {
  const vec3 c0 = vec3(0.2777273272234177, 0.005407344544966578, 0.3340998053353061);
  const vec3 c1 = vec3(0.1050930431085774, 1.404613529898575, 1.384590162594685);
  const vec3 c2 = vec3(-0.3308618287255563, 0.214847559468213, 0.09509516302823659);
  const vec3 c3 = vec3(-4.634230498983486, -5.799100973351585, -19.33244095627987);
  const vec3 c4 = vec3(6.228269936347081, 14.17993336680509, 56.69055260068105);
  const vec3 c5 = vec3(4.776384997670288, -13.74514537774601, -65.35303263337234);
  const vec3 c6 = vec3(-5.435455855934631, 4.645852612178535, 26.3124352495832);
  return clamp(c0 + t * (c1 + t * (c2 + t * (c3 + t * (c4 + t * (c5 + t * c6))))), 0.0, 1.0);
}

void main() {
  if (u_wire > 0.5) {
    frag_color = u_wire_color;
    return;
  }
  vec3 to_eye = u_orthographic > 0.5 ? vec3(0.0, 0.0, 1.0) : normalize(-v_position_view);
  // Face normal from screen-space derivatives: faces the viewer by construction.
  vec3 face_n = cross(dFdx(v_position_view), dFdy(v_position_view));
  float face_length = length(face_n);
  vec3 n = face_length > 1e-20 ? face_n / face_length : to_eye;
  float n_length = length(v_normal_view);
  if (u_smooth > 0.5 && n_length > 1e-6) {
    n = v_normal_view / n_length;
    if (dot(n, to_eye) < 0.0) n = -n;
  }
  vec3 light = normalize(vec3(-0.3, 0.7, 0.6));
  float diffuse = max(dot(n, light), 0.0);
  float fill = 0.5 + 0.5 * dot(n, to_eye);  // keeps silhouettes from going black
  vec3 half_vector = normalize(light + to_eye);
  float highlight = pow(max(dot(n, half_vector), 0.0), 48.0);
  vec3 color;
  if (u_textured > 0.5) {  // the texture lit gently, as the colour map, so its colours stay readable
    vec3 base = texture(u_texture, v_texcoord).rgb;
    if (!gl_FrontFacing) base *= 0.75;
    color = base * (0.55 + 0.30 * diffuse + 0.20 * fill) + vec3(0.05 * highlight);
  } else if (u_color_map > 0.5) {
    vec3 base = viridis(clamp(v_scalar, 0.0, 1.0));
    if (!gl_FrontFacing) base *= 0.75;
    color = base * (0.55 + 0.30 * diffuse + 0.20 * fill) + vec3(0.05 * highlight);
  } else {
    vec3 base = gl_FrontFacing ? u_front_color : u_back_color;
    color = base * (0.30 + 0.52 * diffuse + 0.22 * fill) + vec3(0.08 * highlight);
  }
  frag_color = vec4(color, 1.0);
}
