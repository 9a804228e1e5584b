#include "DecalMath.h"

/* One step of the damage map: heal (scale the damage; 0 rebuilds it from this batch alone), then
   apply this batch's stamps in order, each clamped so base + damage stays in [0,1], then write
   the combined height; and the batch's shading marks: the albedo (the base colour burnt towards
   soot by the scorch) and the shading channels (roughness, occlusion, scorch, glow).
   Stamps are binned on the host into square tiles of TILE texels: tileStart[t]..tileStart[t+1]
   index tileStamps, the stamps whose footprint touches tile t, in batch order. A texel loops
   over its tile's list only, so thousands of stamps cost what their footprints cover.
   stamps[i] = (centre x, centre y in texels, 1 / radius in texels, depth),
   shapes[i] = (rimHeight, rimWidth, squared reach in texels^2, glow): texels beyond
   the reach of a stamp in their tile's list skip it before any square root.
   looks[i] = (scorch, roughness, occlusion strengths, scorch reach in radii),
   wobbles[i] = hfx_decal_wobble of its phase. */
__kernel void decals(__global float* damage, __global const float* base, __global float* height,
                     int width, int rows, float heal, int tilesX,
                     __global const int* tileStart, __global const int* tileStamps,
                     __global const float4* stamps, __global const float4* shapes, __global const float4* looks,
                     __global const float4* wobbles,
                     __global const uchar4* baseAlbedo, __global uchar4* albedo, __global uchar4* channels,
                     float4 soot) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= rows) return;
    int i = y * width + x;
    float b = base[i];
    float d = damage[i] * heal;
    float scorch = 0.0f, rough = 0.0f, occlusion = 1.0f, glow = 0.0f, hotX = 0.0f, hotY = 0.0f;
    int hottest = -1; /* the stamp whose bowl is hottest here: its crust's cracks show */
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
        float4 look = looks[s];
        if (look.x > 0.0f || look.y > 0.0f || look.z > 0.0f) {
            float sc, ro, oc;
            float4 w = wobbles[s];
            hfx_decal_marks(dx * stamp.z, dy * stamp.z, look.x, look.y, look.z, look.w, w.x, w.y, w.z, w.w, &sc, &ro,
                            &oc);
            scorch = fmax(scorch, sc);
            rough = fmax(rough, ro);
            occlusion = fmin(occlusion, oc);
        }
        if (shape.w > 0.0f) {
            float heat = hfx_decal_heat(dx * stamp.z, dy * stamp.z, shape.w);
            if (heat > glow) {
                glow = heat;
                hottest = s;
                hotX = dx;
                hotY = dy;
            }
        }
    }
    if (hottest >= 0) {
        float4 stamp = stamps[hottest], w = wobbles[hottest];
        glow *= hfx_decal_crust(hotX * stamp.z, hotY * stamp.z, shapes[hottest].w, stamp.z, w.x, w.y);
    }
    damage[i] = d;
    float h = b + d;
    height[i] = h < 0.0f ? 0.0f : (h > 1.0f ? 1.0f : h);
    float4 c = convert_float4(baseAlbedo[i]);
    float4 burnt = c + clamp(scorch, 0.0f, 1.0f) * (soot - c);
    albedo[i] = (uchar4)(convert_uchar_sat_rte(burnt.x), convert_uchar_sat_rte(burnt.y), convert_uchar_sat_rte(burnt.z),
                         baseAlbedo[i].w);
    channels[i] = (uchar4)(convert_uchar_sat_rte(rough * 255.0f), convert_uchar_sat_rte(occlusion * 255.0f),
                           convert_uchar_sat_rte(scorch * 255.0f), convert_uchar_sat_rte(glow * 255.0f));
}
