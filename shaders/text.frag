#version 330 core
// FreeType's 8-bit coverage (already antialiased) as alpha.
in vec2 v_uv;
in vec4 v_colour;
uniform sampler2D atlas;
out vec4 frag;
void main() { frag = vec4(v_colour.rgb, v_colour.a * texture(atlas, v_uv).r); }
