#version 450 core
// The deferred light walks (trace/hier/deferred.glsl, hfx::ExactTracer): one point per ray the
// surface draw appended, drawn indirectly with the buffer's count. The vertex stage walks the
// ray (hfx_shadow, trace/hier.glsl: the walk the draw would have made), so 32 walks share a
// warp, and puts the point on its pixel with the colour that shadow gives; deferred.frag writes
// it where the draw's own depth still stands (GL_EQUAL).

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/heights.glsl"
#include "trace/common.glsl"
#include "trace/hier.glsl"
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
    const vec4 a = hfx_deferredRays[HFX_DEFERRED_VEC4S * i], b = hfx_deferredRays[HFX_DEFERRED_VEC4S * i + 1],
               c = hfx_deferredRays[HFX_DEFERRED_VEC4S * i + 2], d = hfx_deferredRays[HFX_DEFERRED_VEC4S * i + 3];
    HfxShadowRay ray;
    ray.uv = b.xy;
    ray.h0 = b.z;
    ray.span = vec2(b.w, c.x);
    ray.level = 0.0;
    ray.samples = 0;
    ray.sharpness = u_shadowSharpness;
    const vec3 color = c.yzw + (1.0 - hfx_shadow(ray) * a.w) * d.xyz;
    v_color = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
    v_depth = a.z;
    gl_Position = vec4((a.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
