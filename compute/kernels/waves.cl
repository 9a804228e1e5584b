#include "WavesMath.h"

/* Sum of directional waves into a float height buffer, row y at v = (y + 0.5) / size.
   waves[i] = (m, n, amplitude, phase at this time). */
__kernel void waves(__global float* height, int size, __constant float4* waves, int count,
                    float sharpness, float inverseTotalAmplitude) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= size || y >= size) return;
    float u = (x + 0.5f) / size, v = (y + 0.5f) / size;
    float sum = 0.0f;
    for (int i = 0; i < count; ++i) {
        float4 w = waves[i];
        sum += w.z * hfx_wave_term(u, v, w.x, w.y, w.w, sharpness);
    }
    height[y * size + x] = hfx_wave_height(sum, inverseTotalAmplitude);
}
