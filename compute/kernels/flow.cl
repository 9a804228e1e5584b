#include "FlowMath.h"

/* The gas planet's advected detail (FlowMath.h, hfx::FlowDetail). */

/* Both layers' displacement planes (the first 4 of HFX_FLOW_PLANES x W x H) advected dt into dst, a
   layer whose `reset` is set starting again from zero; the strain plane gets the flow's strain
   rate now (flow_finest then fills the last two from dst). */
__kernel void flow_advect(__global const float* restrict u, __global const float* restrict v,
                          __global const float* restrict metric, __global const float* restrict src,
                          __global float* restrict dst, int W, int H, float dt, int reset0, int reset1) {
    int i = get_global_id(0), j = get_global_id(1);
    if (i >= W || j >= H) return;
    int k = j * W + i, n = W * H;
    float px, py; /* the cell centre's departure, the same for every plane */
    hfx_gas_departure(u, v, metric, W, H, i, j, 0.5f, 0.5f, dt, 1, &px, &py);
    for (int plane = 0; plane < 4; ++plane) {
        int reset = plane < 2 ? reset0 : reset1;
        dst[plane * n + k] = reset ? 0.0f : hfx_flow_advect_from(src + plane * n, W, H, i, j, px, py, plane & 1);
    }
    dst[HFX_FLOW_STRAIN * n + k] = hfx_flow_strain(u, v, metric, W, H, i, j);
}

/* Each layer's finest octave at the cell centres (hfx_flow_cell_finest), from the displacements
   flow_advect wrote into the same planes. */
__kernel void flow_finest(__global float* restrict planes, int W, int H, HfxFlowParams params) {
    int i = get_global_id(0), j = get_global_id(1);
    if (i >= W || j >= H) return;
    for (int k = 0; k < 2; ++k)
        planes[(HFX_FLOW_FINEST + k) * W * H + j * W + i] = hfx_flow_cell_finest(planes, W, H, i, j, k, params);
}

/* The detailed heights, `scale` texels per gas cell along each axis (fine texel (x, y) has its
   centre at ((x + 0.5) / scale, (y + 0.5) / scale) cells), faded to 0.5 along a smoothstep within
   capRows gas rows of the poles and reaching it on the first and last rows, where every column
   meets in one point. */
__kernel void flow_detail(__global const float* restrict heights, __global const float* restrict planes,
                          __global float* restrict out, int W, int H, int scale, HfxFlowParams params,
                          float capRows) {
    int fx = get_global_id(0), fy = get_global_id(1);
    int columns = W * scale, rows = H * scale;
    if (fx >= columns || fy >= rows) return;
    float x = ((float)fx + 0.5f) / (float)scale, y = ((float)fy + 0.5f) / (float)scale;
    float h = hfx_flow_height(heights, planes, W, H, x, y, params);
    if (capRows > 0.0f) {
        float t = fmin((float)fy, (float)(rows - 1 - fy)) / (capRows * (float)scale);
        if (t < 1.0f) h = 0.5f + (h - 0.5f) * t * t * (3.0f - 2.0f * t);
    }
    out[fy * columns + fx] = h;
}
