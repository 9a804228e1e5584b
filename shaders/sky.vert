#version 450 core
// One triangle over the whole viewport (no vertex data), at the far plane; the fragment stage
// turns each pixel into a view direction.
out vec2 v_ndc;

void main() {
    const vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
    v_ndc = corner;
    gl_Position = vec4(corner, 1.0, 1.0);
}
