#version 450 core
// The deferred light walks (trace/hier/deferred.glsl, hfx::ExactTracer::finish): one invocation
// per ray the surface draw appended, dispatched indirectly with the groups the draw counted. It
// walks the ray (hfx_shadow, trace/hier.glsl: the walk the draw would have made), so the rays
// share warps one to a lane, on every core a compute dispatch reaches (a GPU may give graphics
// fewer), and stores the pixel's colour in the ray's last vec4 for deferred.vert to write.

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/heights.glsl"
#include "trace/common.glsl"
#include "trace/hier.glsl"
#include "trace/hier/deferred.glsl"

layout(local_size_x = HFX_DEFERRED_GROUP) in;

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= min(hfx_deferredCount, hfx_deferredCapacity)) return; // past the capacity: walked in the draw
    const int at = HFX_DEFERRED_VEC4S * int(i);
    const vec4 a = hfx_deferredRays[at], b = hfx_deferredRays[at + 1], c = hfx_deferredRays[at + 2],
               d = hfx_deferredRays[at + 3];
    HfxShadowRay ray;
    ray.uv = b.xy;
    ray.h0 = b.z;
    ray.span = vec2(b.w, c.x);
    ray.level = 0.0;
    ray.samples = 0;
    ray.sharpness = u_shadowSharpness;
    const vec3 color = c.yzw + (1.0 - hfx_shadow(ray) * a.w) * d.xyz;
    hfx_deferredRays[at + 3] = vec4(hfx_output(color), 1.0);
}
