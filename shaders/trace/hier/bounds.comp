#version 450 core
// The exact tracer's height bounds, built on the GL side from the stored texels whenever they
// change (BoundsPass), so they bound exactly what the walk's patch solve reads (a float16 or
// unorm8 surface's rounded heights included) and nothing crosses from the compute device:
//
// - level 0 (HFX_BOUNDS_LEVEL0 1: a program of its own, which reads the texels, not the images):
//   per level-0 cell (i, j), between the samples i..i+1 and j..j+1, the
//   (max, min) of its four corner samples, which bound every bilinearly interpolated height in
//   it; across an edge that wraps the far corner is the first sample, across one that clamps the
//   last again. In the atlas layout with HFX_BOUNDS_CELLS 1 it also writes the four samples,
//   in textureGather's order (x: (i, j+1), y: (i+1, j+1), z: (i+1, j), w: (i, j)), to the cells
//   image the atlas walk reads instead of a gather (on llvmpipe a gather costs about 2.2x an
//   RGBA32F imageLoad);
// - level k > 0: the max of the maxima and the min of the minima of the 2x2 texels of level
//   k - 1 (a lone last row or column counts alone).
//
// A mip chain's level k - 1 and level k are bound to the two image units; the atlas (every level
// in one image, at the origins C++ computes: HeightBounds::atlasOrigin) to both.
layout(local_size_x = 8, local_size_y = 8) in;
#include "bindings.glsl"
#ifndef HFX_PYRAMID_ATLAS
#define HFX_PYRAMID_ATLAS 0
#endif
#ifndef HFX_BOUNDS_CELLS
#define HFX_BOUNDS_CELLS 0
#endif
#ifndef HFX_BOUNDS_LEVEL0
#define HFX_BOUNDS_LEVEL0 0
#endif
#ifndef HFX_BOUNDS_PYRAMID
#define HFX_BOUNDS_PYRAMID 1 // 0: the cells alone (the pyramid came from the compute device)
#endif
layout(binding = HFX_UNIT_SURFACE) uniform sampler2D s_surface;
layout(rg32f, binding = HFX_IMAGE_BOUNDS_FINER) readonly uniform image2D i_finer;
layout(rg32f, binding = HFX_IMAGE_BOUNDS) writeonly uniform image2D i_bounds;
#if HFX_BOUNDS_CELLS
layout(rgba32f, binding = HFX_IMAGE_CELLS) writeonly uniform image2D i_cells;
#endif
uniform ivec2 u_wrap;        // per axis: 1 where the field wraps, 0 where it clamps
uniform ivec2 u_size;        // this level's texels
uniform ivec2 u_finerSize;   // level - 1's texels (level > 0)
uniform ivec2 u_origin;      // where this level's texel (0, 0) lies in i_bounds
uniform ivec2 u_finerOrigin; // ... and level - 1's in i_finer

void main() {
    const ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, u_size))) return;
    vec2 bounds;
#if HFX_BOUNDS_LEVEL0
    {
        const ivec2 last = u_size - 1, n = mix(min(c + 1, last), (c + 1) & last, bvec2(u_wrap)); // power-of-two sizes
        const vec4 s = vec4(texelFetch(s_surface, ivec2(c.x, n.y), 0).w, texelFetch(s_surface, n, 0).w,
                            texelFetch(s_surface, ivec2(n.x, c.y), 0).w, texelFetch(s_surface, c, 0).w);
        bounds = vec2(max(max(s.x, s.y), max(s.z, s.w)), min(min(s.x, s.y), min(s.z, s.w)));
#if HFX_BOUNDS_CELLS
        imageStore(i_cells, c, s);
#endif
    }
#else
    {
        const ivec2 f0 = 2 * c, f1 = min(f0 + 1, u_finerSize - 1);
        const vec2 a = imageLoad(i_finer, u_finerOrigin + f0).rg, b = imageLoad(i_finer, u_finerOrigin + ivec2(f1.x, f0.y)).rg;
        const vec2 d = imageLoad(i_finer, u_finerOrigin + ivec2(f0.x, f1.y)).rg, e = imageLoad(i_finer, u_finerOrigin + f1).rg;
        bounds = vec2(max(max(a.x, b.x), max(d.x, e.x)), min(min(a.y, b.y), min(d.y, e.y)));
    }
#endif
#if HFX_BOUNDS_PYRAMID
    imageStore(i_bounds, u_origin + c, vec4(bounds, 0.0, 0.0));
#endif
}
