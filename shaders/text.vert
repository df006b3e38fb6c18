#version 330 core
// Glyph quads: pixel coordinates as in solid.vert, atlas coordinates in [0, 1].
layout(location = 0) in vec2 pos;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 colour;
uniform vec2 viewport;
out vec2 v_uv;
out vec4 v_colour;
void main() {
  gl_Position = vec4(2.0 * pos.x / viewport.x - 1.0, 2.0 * pos.y / viewport.y - 1.0, 0.0, 1.0);
  v_uv = uv;
  v_colour = colour;
}
