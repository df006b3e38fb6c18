#version 330 core
// Analytic antialiasing: the pixel's coverage across each edge, from its centre's distance.
in vec4 v_colour;
in vec2 v_edge;
out vec4 frag;
void main() {
  vec2 c = clamp(v_edge + 0.5, 0.0, 1.0);
  frag = vec4(v_colour.rgb, v_colour.a * c.x * c.y);
}
