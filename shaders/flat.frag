#version 450 core
// A solid colour with the polygon's own depth: stand-in geometry that intersects a surface.

layout(location = 0) out vec4 o_color;
uniform vec4 u_color;

void main() { o_color = u_color; }
