#version 450 core
// The exact tracer's walks (trace/hier/trace.glsl, hfx::ExactTracer): a lane per pixel of the
// viewport in groups of 8x8 pixels, where the rays draw stored this draw's ray: its view walk
// (hfx_trace, from the beam start's depth where HFX_BEAM_START), then, where the rays draw marked
// its light ray walked, that walk as the draw would make it (hfx_surface_shadow: the texel shadows
// where they hold it), along the flat patch's light or, with HFX_TRACE_LIGHTS, the pixel's. The
// hit, the shadow and the fetches go back into the slot.

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/heights.glsl"
#include "trace/common.glsl"
#include "trace/hier.glsl"
#include "surface/shadow.glsl"
#include "trace/hier/trace.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#if HFX_BEAM_START
layout(binding = HFX_UNIT_BEAM_START) uniform sampler2D s_beamStart;
#endif

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(u_traceWidth, u_traceHeight)))) return;
    const int slot = pixel.y * u_traceWidth + pixel.x;
    const uvec2 info = hfx_traceInfo[slot];
    if ((info.y & 0xffff0000u) != hfx_trace_mark(true)) return; // no ray of this draw's, or normal mapped
    const vec4 stored = hfx_traceRays[slot];
    const float blend = unpackUnorm2x16(info.y & 0xffffu).x;
    HfxRay ray;
    ray.uv = stored.xy;
    ray.parallax = stored.zw;
    ray.cosTheta = 1.0; // (the sampled searches' business)
    ray.level = 0.0;
    ray.samples = 1;
    ray.tolerance = uintBitsToFloat(info.x & ~HFX_TRACE_WALKS_LIGHT);
#if HFX_BEAM_START
    ray.start = texelFetch(s_beamStart, (pixel + u_traceOrigin) / HFX_BEAM_BLOCK, 0).r;
#else
    ray.start = 0.0;
#endif
    const HfxHit hit = hfx_trace(ray);
    // surface.frag's level-of-detail fade to the entry.
    const vec2 uv = mix(hit.uv, ray.uv, blend);
    const float depthFraction = mix(hit.depth, 0.0, blend);
    float shadow = -1.0;
    const float h0 = 1.0 - depthFraction;
    if ((info.x & HFX_TRACE_WALKS_LIGHT) != 0u && h0 < 1.0) {
        // surface.frag's light ray (texcoords per unit climbed): the pixel's, or on a flat patch
        // the texel shadows' light (u_shadowLight.xy), every pixel's.
#if HFX_TRACE_LIGHTS
        const vec2 light = hfx_traceLights[slot];
#else
        const vec2 light = u_shadowLight.xy;
#endif
        HfxShadowRay shadowRay;
        shadowRay.uv = uv;
        shadowRay.h0 = h0;
        shadowRay.span = light * (1.0 - h0);
        shadowRay.level = 0.0;
        shadowRay.samples = 1;
        shadowRay.sharpness = u_shadowSharpness;
        int deferred;
        shadow = hfx_surface_shadow(shadowRay, 1.0, deferred);
    }
    hfx_traceRays[slot] = vec4(uv, depthFraction, shadow);
    hfx_traceInfo[slot].x = uint(g_fetches);
}
