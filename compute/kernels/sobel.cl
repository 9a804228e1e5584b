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

/* The same filter, four texels along x per work-item (width a multiple of 4): each row's six
   values are loaded once (one vload4 and the two neighbours) for four outputs instead of nine
   loads per output. Measured on PoCL (docs/BENCHMARKS.md, BM_SobelKernel): 1.03-1.50x the one-texel kernel, same
   results bit for bit. */
__kernel void sobel4(__global const float* height, __global float4* out, int width, int height_,
                     float scaleX, float scaleY) {
    int x0 = get_global_id(0) * 4, y = get_global_id(1);
    if (x0 >= width || y >= height_) return;
    int xl = edge(x0 - 1, width), xr = edge(x0 + 4, width);
    int rows[3] = {edge_y(y - 1, height_) * width, y * width, edge_y(y + 1, height_) * width};
    float r[3][6];
    for (int k = 0; k < 3; ++k) {
        float4 m = vload4(0, height + rows[k] + x0);
        r[k][0] = height[rows[k] + xl];
        r[k][1] = m.x;
        r[k][2] = m.y;
        r[k][3] = m.z;
        r[k][4] = m.w;
        r[k][5] = height[rows[k] + xr];
    }
    for (int i = 0; i < 4; ++i) {
        float normal[3];
        hfx_normal_from_slopes(hfx_sobel_dx(r[0][i], r[0][i + 2], r[1][i], r[1][i + 2], r[2][i], r[2][i + 2]),
                               hfx_sobel_dy(r[0][i], r[0][i + 1], r[0][i + 2], r[2][i], r[2][i + 1], r[2][i + 2]),
                               scaleX, scaleY, normal);
        out[rows[1] + x0 + i] = (float4)(normal[0], normal[1], normal[2], r[1][i + 1]);
    }
}

/* Adds the relief that a field gained since `base` to an artist's normal map: in slope space
   (x/z, y/z), where heights add, out = detail + (current - base). Where nothing changed the
   detail normal comes through exactly; `current` and `base` are this kernel's Sobel outputs of
   the changed and the original heights, `detail` the normal map (xyz) in the same layout.
   Writes `current` in place, keeping its height (w). */
__kernel void sobel_add_detail(__global float4* current, __global const float4* base,
                               __global const float4* detail, int n) {
    int k = get_global_id(0);
    if (k >= n) return;
    float4 c = current[k], b = base[k], d = detail[k];
    if (c.x == b.x && c.y == b.y && c.z == b.z) {
        current[k] = (float4)(d.x, d.y, d.z, c.w);
        return;
    }
    float dz = fmax(d.z, 0.05f);
    float sx = d.x / dz + (c.x / c.z - b.x / b.z);
    float sy = d.y / dz + (c.y / c.z - b.y / b.z);
    float inv = rsqrt(sx * sx + sy * sy + 1.0f);
    current[k] = (float4)(sx * inv, sy * inv, inv, c.w);
}
