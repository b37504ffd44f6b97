// Wireframe overlay: polygon edges, one vertex per mesh vertex.
layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;

void main() {
  gl_Position = u_projection * (u_model_view * vec4(a_position, 1.0));
}
