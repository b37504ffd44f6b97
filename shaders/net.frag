// Control net: flat colour; points are round sprites with a dark rim for contrast on any
// background. u_alpha < 1 is the x-ray ghost pass.
in vec4 v_color;
flat in float v_outline;

uniform float u_points;
uniform float u_alpha;

out vec4 frag_color;

void main() {
  vec4 color = v_color;
  if (u_points > 0.5) {
    float r = length(gl_PointCoord - vec2(0.5));
    if (r > 0.5) discard;
    if (v_outline > 0.5) color.rgb = mix(color.rgb, vec3(0.04, 0.04, 0.06), smoothstep(0.36, 0.44, r));
  }
  frag_color = vec4(color.rgb, color.a * u_alpha);
}
