// Two-sided clay shading: a headlight slightly above-left of the eye, ambient and a faint
// highlight. Back sides get a cooler tint so flipped or open surfaces are easy to spot.
in vec3 v_position_view;
in vec3 v_normal_view;

uniform vec3 u_front_color;
uniform vec3 u_back_color;
uniform float u_orthographic;

out vec4 frag_color;

void main() {
  vec3 to_eye = u_orthographic > 0.5 ? vec3(0.0, 0.0, 1.0) : normalize(-v_position_view);
  float n_length = length(v_normal_view);
  vec3 n = n_length > 1e-12 ? v_normal_view / n_length : to_eye;
  vec3 base = u_front_color;
  if (dot(n, to_eye) < 0.0) {
    n = -n;
    base = u_back_color;
  }
  vec3 light = normalize(vec3(-0.3, 0.7, 0.6));
  float diffuse = max(dot(n, light), 0.0);
  float fill = 0.5 + 0.5 * dot(n, to_eye);  // keeps silhouettes from going black
  vec3 half_vector = normalize(light + to_eye);
  float highlight = pow(max(dot(n, half_vector), 0.0), 48.0);
  vec3 color = base * (0.30 + 0.52 * diffuse + 0.22 * fill) + vec3(0.08 * highlight);
  frag_color = vec4(color, 1.0);
}
