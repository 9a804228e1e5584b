#version 450 core
// The deferred light walks' pixels (trace/hier/deferred.glsl, hfx::ExactTracer::finish): one
// point per ray the surface draw appended, drawn indirectly with the buffer's count, after
// deferred.comp walked them. It puts the point on its pixel with the colour the walk gave;
// deferred.frag writes it where the draw's own depth still stands (GL_EQUAL).

#include "bindings.glsl"
#define HFX_DEFERRED_ACCESS readonly
#include "trace/hier/deferred.glsl"

uniform vec4 u_viewport; // x, y, width, height: the draw's
flat out vec4 v_color;
flat out float v_depth;

void main() {
    const int i = gl_VertexID;
    if (uint(i) >= hfx_deferredCapacity) { // walked in the draw
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_color = vec4(0.0);
        v_depth = 0.0;
        return;
    }
    const vec4 a = hfx_deferredRays[HFX_DEFERRED_VEC4S * i];
    v_color = hfx_deferredRays[HFX_DEFERRED_VEC4S * i + 3];
    v_depth = a.z;
    // (At a clip depth inside either convention's range: the fragment writes the stored depth.)
    gl_Position = vec4((a.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0, 0.5, 1.0);
    gl_PointSize = 1.0;
}
