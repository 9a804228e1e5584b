#include "EdgeMath.h"
#include "SobelMath.h"

/* Tangent-space normals of any height buffer; writes float4 (normal.xyz, height) per texel so a
   renderer gets normal and height in one fetch. Neighbours across an edge wrap or clamp as the
   source's edge mode says (HFX_WRAP_U, HFX_WRAP_V from hfx::edgeOptions). */
int edge_x(int i, int n) { return hfx_edge_index(i, n, HFX_WRAP_U); }
int edge_y(int j, int n) { return hfx_edge_index(j, n, HFX_WRAP_V); }

__kernel void sobel(__global const float* height, __global float4* out, int width, int height_,
                    float scaleX, float scaleY) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= height_) return;
    int xl = edge_x(x - 1, width), xr = edge_x(x + 1, width);
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
   loads per output; the same results bit for bit (speed: BM_SobelKernel, docs/history/tuning.md). */
__kernel void sobel4(__global const float* height, __global float4* out, int width, int height_,
                     float scaleX, float scaleY) {
    int x0 = get_global_id(0) * 4, y = get_global_id(1);
    if (x0 >= width || y >= height_) return;
    int xl = edge_x(x0 - 1, width), xr = edge_x(x0 + 4, width);
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
