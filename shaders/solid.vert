#version 330 core
// Coloured triangles in pixel coordinates (origin top-left, y down). Pixel row 0 maps to the
// bottom of the framebuffer, so glReadPixels returns the image top row first: no flip needed.
// edge: the vertex's signed distances [px] from up to two antialiased edges (draw_list.hpp).
layout(location = 0) in vec2 pos;
layout(location = 1) in vec4 colour;
layout(location = 2) in vec2 edge;
uniform vec2 viewport;
out vec4 v_colour;
out vec2 v_edge;
void main() {
  gl_Position = vec4(2.0 * pos.x / viewport.x - 1.0, 2.0 * pos.y / viewport.y - 1.0, 0.0, 1.0);
  v_colour = colour;
  v_edge = edge;
}
