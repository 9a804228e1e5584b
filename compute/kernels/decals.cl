#include "DecalMath.h"

/* One step of the damage map: heal (scale the damage), then apply this batch's stamps in order,
   each clamped so base + damage stays in [0,1], then write the combined height.
   Stamps are binned on the host into square tiles of TILE texels: tileStart[t]..tileStart[t+1]
   index tileStamps, the stamps whose footprint touches tile t, in batch order. A texel loops
   over its tile's list only, so thousands of stamps cost what their footprints cover.
   stamps[i] = (u, v, radius, depth), shapes[i] = (rimHeight, rimWidth); distances in units of
   the map's width. */
__kernel void decals(__global float* damage, __global const float* base, __global float* height,
                     int width, int rows, float heal, int tilesX,
                     __global const int* tileStart, __global const int* tileStamps,
                     __global const float4* stamps, __global const float2* shapes) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= rows) return;
    int i = y * width + x;
    float b = base[i];
    float d = damage[i] * heal;
    int tile = (y / TILE) * tilesX + x / TILE;
    for (int k = tileStart[tile]; k < tileStart[tile + 1]; ++k) {
        int s = tileStamps[k];
        float4 stamp = stamps[s];
        float dx = (x + 0.5f) - stamp.x * width, dy = (y + 0.5f) - stamp.y * rows;
#ifndef CLAMP_EDGES
        dx -= width * rint(dx / width);
        dy -= rows * rint(dy / rows);
#endif
        float r = sqrt(dx * dx + dy * dy) / (stamp.z * width);
        float2 shape = shapes[s];
        d = hfx_apply_damage(d, hfx_crater_profile(r, stamp.w, shape.x, shape.y), b);
    }
    damage[i] = d;
    float h = b + d;
    height[i] = h < 0.0f ? 0.0f : (h > 1.0f ? 1.0f : h);
}
