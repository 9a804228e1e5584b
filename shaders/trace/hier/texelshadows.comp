#version 450 core
// The texel shadows of a flat surface under one light (hfx::TexelShadowPass): a lane per texel of
// the target, the exact tracer's self-shadow (trace/hier.glsl's hfx_shadow, the walk every pixel
// would make) of a light ray from the sample at its own height, towards the pass's light
// (u_shadowLight: texcoords per unit climbed, penumbra). A compute pass: the walks need no
// rasteriser, and a compute chip runs them on every unit where it draws on a few.
// Sample (i, j) sits at texcoords ((i, j) + 0.5) / size; the target holds every u_texelStride-th
// sample on each axis (its texel (a, b) is sample (a, b) * stride).

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/heights.glsl"
#include "trace/common.glsl"
#include "trace/hier.glsl"

// Groups of 16x16 lanes (TexelShadowPass reads the size from the program). llvmpipe ran the walks
// in 8x8 groups in 1.01-1.26x the time of the fragment pass the compute pass replaced, in 16x16
// ones in 0.91-1.13x, its noise (2026-11-30, docs/history/tuning.md); a GPU's warp then covers
// 16x2 texels, whose light rays run side by side.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = HFX_IMAGE_PASS_OUTPUT, r32f) uniform writeonly image2D i_texelShadows;
uniform int u_texelStride;

void main() {
    const ivec2 target = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(target, imageSize(i_texelShadows)))) return;
    const ivec2 texel = target * u_texelStride;
    const ivec2 size = hfx_size();
    HfxShadowRay ray;
    ray.h0 = texelFetch(s_surface, texel, 0).w;
    ray.uv = (vec2(texel) + 0.5) / vec2(size);
    ray.span = u_shadowLight.xy * (1.0 - ray.h0);
    ray.level = 0.0;
    ray.samples = 0;
    ray.sharpness = 1.0 / u_shadowLight.z;
    imageStore(i_texelShadows, target, vec4(ray.h0 < 1.0 ? hfx_shadow(ray) : 0.0));
}
