// Flat line colour; alpha blends the lines into the shading so dense meshes stay readable.
uniform vec4 u_color;

out vec4 frag_color;

void main() {
  frag_color = u_color;
}
