#version 450 core
// The exact tracer's walks (trace/hier/trace.glsl, hfx::ExactTracer): a lane per slot (a pixel of
// the viewport in each plane) in groups of 8x8 slots, where the rays draw stored this draw's ray
// or, on a flat patch (HFX_TRACE_PATCH), where the pixel's ray meets the patch (hfx_patch_ray,
// below: no rays draw): its view walk (hfx_trace, from the beam start's depth where
// HFX_BEAM_START), then, where its light ray is to be walked, that walk as the draw would make it
// (hfx_surface_shadow: the texel shadows where they hold it), along the flat patch's light or,
// with HFX_TRACE_LIGHTS, the pixel's.
// The hit, the shadow and the fetches go back into the slot.

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

#ifndef HFX_TRACE_PATCH
#define HFX_TRACE_PATCH 0
#endif
#if HFX_TRACE_PATCH
#include "trace/hier/patch.glsl"
// The flat patch as the draw places it (ExactTracer::walks; its map from the screen in
// patch.glsl). u_patchDepth: clip z as (u, v, 1) . it, for the near and far planes' tests.
// u_patchBudget: the pixel budget (0 for a caster's pass: its texels are no screen pixels);
// u_patchWalksLight: 1 where the light ray is walked (the light above the patch, self-shadows
// drawn, no caster), u_patchLight its texcoords per unit climbed (the texel shadows' light where
// they are read).
uniform vec3 u_patchDepth;
uniform float u_patchBudget;
uniform int u_patchWalksLight;
uniform vec2 u_patchLight;

// The rays draw's work for the pixel, from the screen: where its ray meets the patch ahead of the
// eye, between the near and the far plane and within a pixel of the box of its texcoords (a
// fragment of the patch's may lie there; the rest of the box is walked for nothing where the patch
// is not a rectangle), its ray, its tolerance and whether its light ray is walked (`info`:
// hfx_traceInfo's, the mark and the level-of-detail blend included) and true; or, where it is seen
// from below or past the level-of-detail threshold, the slot marked normal mapped, and false. The
// texcoords' derivatives are the draw's: the differences across the pixel's 2x2 quad of the window,
// along its row and its column (dFdxFine and dFdyFine; PixelNeighbours), not the map's derivative
// at the pixel, which differs from them by the map's curvature: enough to move the level-of-detail
// fade and a pixel budget's tolerance, and so the hits (Picking's fade, on llvmpipe: 8589 of 24590
// pixels up to 0.24 texels apart).
bool hfx_patch_ray(ivec2 pixel, int slot, out vec4 ray, out uvec2 info) {
    ray = vec4(0.0);
    info = uvec2(0u);
    const vec2 perPixel = 2.0 / vec2(u_traceWidth, u_traceHeight);
    vec2 uv0;
    float w;
    if (!hfx_patch_point((vec2(pixel) + 0.5) * perPixel - 1.0, uv0, w)) return false;
    const float z = dot(u_patchDepth, vec3(uv0, 1.0));
    // The quad's other pixel along the row and along the column (window coordinates pair them).
    const ivec2 other = ((pixel + u_traceOrigin) ^ 1) - u_traceOrigin;
    const ivec2 toOther = other - pixel; // +1 where the pixel is the quad's left (lower) one
    vec2 uvAcross, uvUp;
    float wAcross, wUp;
    vec2 dx, dy;
    if (hfx_patch_point((vec2(other.x, pixel.y) + 0.5) * perPixel - 1.0, uvAcross, wAcross) &&
        hfx_patch_point((vec2(pixel.x, other.y) + 0.5) * perPixel - 1.0, uvUp, wUp)) {
        dx = (uvAcross - uv0) * float(toOther.x);
        dy = (uvUp - uv0) * float(toOther.y);
    } else { // a neighbour behind the eye: the map's derivative at the pixel
        dx = (u_patchFromScreen[0].xy - uv0 * u_patchFromScreen[0].z) * (w * perPixel.x);
        dy = (u_patchFromScreen[1].xy - uv0 * u_patchFromScreen[1].z) * (w * perPixel.y);
    }
    const vec2 margin = abs(dx) + abs(dy);
    // (Clip z within [-w, w]: GL's depth range, and the [0, w] of GL_ZERO_TO_ONE within it.)
    if (!(abs(z) <= w * 1.0001) || any(lessThan(uv0, u_patchBox.xy - margin)) ||
        any(greaterThan(uv0, u_patchBox.zw + margin)))
        return false; // no fragment of the patch's: the slot is left as it is
    const vec3 viewTS = hfx_patch_view(uv0);
    const vec2 texels = vec2(hfx_size());
    const float mipLevel = hfx_level_of(dx * texels, dy * texels);
    if (!(viewTS.z > 0.0 && mipLevel <= u_lodThreshold && u_depthScale > 0.0)) {
        hfx_traceInfo[slot] = uvec2(0u, hfx_trace_mark(false));
        return false;
    }
    const vec2 parallax = viewTS.xy / viewTS.z * u_depthScale;
    const float rayPixels = u_patchBudget > 0.0 ? hfx_screen_length(parallax, dx, dy) : 0.0;
    const float tolerance = rayPixels > 0.0 ? u_patchBudget / rayPixels : 0.0;
    const float blend = clamp(mipLevel - (u_lodThreshold - 1.0), 0.0, 1.0);
    ray = vec4(uv0, parallax);
    info = uvec2(floatBitsToUint(tolerance) | (u_patchWalksLight != 0 ? HFX_TRACE_WALKS_LIGHT : 0u),
                 hfx_trace_mark(true) | (packUnorm2x16(vec2(blend, 0.0)) & 0xffffu));
    return true;
}
#endif

// The planes of slots: a triplanar mapping's three (its projections' rays), else one. Past the
// first, a pixel's row is its row in the plane (only the first plane reads the beam start or a
// flat patch's rays, which a triplanar mapping has not).
uniform int u_tracePlanes;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= u_traceWidth || pixel.y >= u_traceHeight * u_tracePlanes) return;
    const int slot = pixel.y * u_traceWidth + pixel.x;
#if HFX_TRACE_PATCH
    vec4 stored;
    uvec2 info;
    if (!hfx_patch_ray(pixel, slot, stored, info)) return;
#else
    const uvec2 info = hfx_traceInfo[slot];
    if ((info.y & 0xffff0000u) != hfx_trace_mark(true)) return; // no ray of this draw's, or normal mapped
    const vec4 stored = hfx_traceRays[slot];
#endif
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
#elif HFX_TRACE_PATCH
        const vec2 light = u_patchLight;
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
    hfx_traceInfo[slot] = uvec2(uint(g_fetches), info.y);
}
