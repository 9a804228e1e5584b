#include "EdgeMath.h"

/* Height-bounds pyramid: per texel the (max, min) of the surface over its footprint. Level 0 has
   one texel per bilinear cell: cell (i, j) lies between the samples i..i+1 and j..j+1 (texel
   centres), so the max and min of those four corners bound every bilinearly interpolated height
   inside it. Each further level takes the max of the maxima and the min of the minima of 2x2
   texels of the one below (a lone last row or column counts alone). */

__kernel void bounds_cells(__global const float* height, __global float2* level0, int width, int rows) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= rows) return;
    /* The cell's far corners: across an edge that wraps, the first sample (as the wrapped texture
       interpolates); across one that clamps, the last again. */
    int x1 = hfx_edge_next(x, width, HFX_WRAP_U), y1 = hfx_edge_next(y, rows, HFX_WRAP_V);
    float2 a = (float2)(height[y * width + x], height[y * width + x1]);
    float2 b = (float2)(height[y1 * width + x], height[y1 * width + x1]);
    float2 hi = fmax(a, b), lo = fmin(a, b);
    level0[y * width + x] = (float2)(fmax(hi.x, hi.y), fmin(lo.x, lo.y));
}

/* Both levels live in one buffer: the finer at finerOffset, the coarser at offset (texels). */
__kernel void bounds_reduce(__global float2* pyramid, int finerOffset, int finerWidth, int finerRows,
                            int offset, int width, int rows) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= rows) return;
    __global const float2* finer = pyramid + finerOffset;
    __global float2* coarser = pyramid + offset;
    int x0 = 2 * x, y0 = 2 * y;
    int x1 = min(x0 + 1, finerWidth - 1), y1 = min(y0 + 1, finerRows - 1);
    float2 a = finer[y0 * finerWidth + x0], b = finer[y0 * finerWidth + x1];
    float2 c = finer[y1 * finerWidth + x0], d = finer[y1 * finerWidth + x1];
    coarser[y * width + x] = (float2)(fmax(fmax(a.x, b.x), fmax(c.x, d.x)), fmin(fmin(a.y, b.y), fmin(c.y, d.y)));
}
