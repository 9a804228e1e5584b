#version 450 core
// The deferred light walks' pixels (trace/hier/deferred.vert): the colour the walk gave, at the
// depth the surface draw wrote there (tested GL_EQUAL, so a pixel something nearer has since
// covered keeps that).
flat in vec4 v_color;
flat in float v_depth;
layout(location = 0) out vec4 o_color;

void main() {
    o_color = v_color;
    gl_FragDepth = v_depth;
}
