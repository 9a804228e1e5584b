#include "DecalMath.h"

/* One step of the damage map: heal (scale the damage), then apply this batch's stamps in order,
   each clamped so base + damage stays in [0,1], then write the combined height.
   Stamps are binned on the host into square tiles of TILE texels: tileStart[t]..tileStart[t+1]
   index tileStamps, the stamps whose footprint touches tile t, in batch order. A texel loops
   over its tile's list only, so thousands of stamps cost what their footprints cover.
   stamps[i] = (centre x, centre y in texels, 1 / radius in texels, depth),
   shapes[i] = (rimHeight, rimWidth, squared reach in texels^2, 0): texels beyond the reach of a
   stamp in their tile's list skip it before any square root. */
__kernel void decals(__global float* damage, __global const float* base, __global float* height,
                     int width, int rows, float heal, int tilesX,
                     __global const int* tileStart, __global const int* tileStamps,
                     __global const float4* stamps, __global const float4* shapes) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= rows) return;
    int i = y * width + x;
    float b = base[i];
    float d = damage[i] * heal;
    int tile = (y / TILE) * tilesX + x / TILE;
    for (int k = tileStart[tile]; k < tileStart[tile + 1]; ++k) {
        int s = tileStamps[k];
        float4 stamp = stamps[s];
        float dx = (x + 0.5f) - stamp.x, dy = (y + 0.5f) - stamp.y;
        /* Along an axis that wraps, the nearest copy of the stamp: centres lie in the map, so
           one shift suffices. */
        if (HFX_WRAP_U) dx += dx > 0.5f * width ? -(float)width : (dx < -0.5f * width ? (float)width : 0.0f);
        if (HFX_WRAP_V) dy += dy > 0.5f * rows ? -(float)rows : (dy < -0.5f * rows ? (float)rows : 0.0f);
        float4 shape = shapes[s];
        float d2 = dx * dx + dy * dy;
        if (d2 >= shape.z) continue;
        float r = sqrt(d2) * stamp.z;
        d = hfx_apply_damage(d, hfx_crater_profile(r, stamp.w, shape.x, shape.y), b);
    }
    damage[i] = d;
    float h = b + d;
    height[i] = h < 0.0f ? 0.0f : (h > 1.0f ? 1.0f : h);
}
