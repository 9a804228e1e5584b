#include "SobelMath.h"

/* Tangent-space normals of any height buffer; writes float4 (normal.xyz, height) per texel so a
   renderer gets normal and height in one fetch. Edges wrap (periodic fields) unless CLAMP_EDGES. */
/* i is at most one step outside [0, n): a select, not an integer division. CLAMP_Y wraps x
   only (longitude-latitude grids). */
int edge(int i, int n) {
#ifdef CLAMP_EDGES
    return clamp(i, 0, n - 1);
#else
    return i < 0 ? i + n : (i >= n ? i - n : i);
#endif
}
int edge_y(int j, int n) {
#ifdef CLAMP_Y
    return clamp(j, 0, n - 1);
#else
    return edge(j, n);
#endif
}

__kernel void sobel(__global const float* height, __global float4* out, int width, int height_,
                    float scaleX, float scaleY) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= height_) return;
    int xl = edge(x - 1, width), xr = edge(x + 1, width);
    int yn = edge_y(y - 1, height_) * width, ys = edge_y(y + 1, height_) * width, yc = y * width;
    float nw = height[yn + xl], n = height[yn + x], ne = height[yn + xr];
    float w = height[yc + xl], c = height[yc + x], e = height[yc + xr];
    float sw = height[ys + xl], s = height[ys + x], se = height[ys + xr];
    float normal[3];
    hfx_normal_from_slopes(hfx_sobel_dx(nw, ne, w, e, sw, se), hfx_sobel_dy(nw, n, ne, sw, s, se),
                           scaleX, scaleY, normal);
    out[yc + x] = (float4)(normal[0], normal[1], normal[2], c);
}
