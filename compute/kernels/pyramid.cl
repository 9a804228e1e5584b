#include "EdgeMath.h"

/* Maximum-height pyramid. Level 0 has one texel per bilinear cell: cell (i, j) lies between the
   samples i..i+1 and j..j+1 (texel centres), so its value, the max of those four corners,
   bounds every bilinearly interpolated height inside it. Each further level takes the max of
   2x2 texels of the one below (a lone last row or column counts alone). */

__kernel void max_cells(__global const float* height, __global float* level0, int width, int rows) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= rows) return;
    /* The cell's far corners: across an edge that wraps, the first sample (as the wrapped texture
       interpolates); across one that clamps, the last again. */
    int x1 = hfx_edge_next(x, width, HFX_WRAP_U), y1 = hfx_edge_next(y, rows, HFX_WRAP_V);
    float a = fmax(height[y * width + x], height[y * width + x1]);
    float b = fmax(height[y1 * width + x], height[y1 * width + x1]);
    level0[y * width + x] = fmax(a, b);
}

/* Both levels live in one buffer: the finer at finerOffset, the coarser at offset (floats). */
__kernel void max_reduce(__global float* pyramid, int finerOffset, int finerWidth, int finerRows,
                         int offset, int width, int rows) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= rows) return;
    __global const float* finer = pyramid + finerOffset;
    __global float* coarser = pyramid + offset;
    int x0 = 2 * x, y0 = 2 * y;
    int x1 = min(x0 + 1, finerWidth - 1), y1 = min(y0 + 1, finerRows - 1);
    float a = fmax(finer[y0 * finerWidth + x0], finer[y0 * finerWidth + x1]);
    float b = fmax(finer[y1 * finerWidth + x0], finer[y1 * finerWidth + x1]);
    coarser[y * width + x] = fmax(a, b);
}
