#include "WavesMath.h"

/* waves[i] = (m, n, amplitude, phase at this time). Rows and columns share one table layout:
   columns[i * size + x] = (sin a, cos a) of wave i at u = (x + 0.5) / size, rows likewise in v. */
__kernel void wave_tables(__global float2* columns, __global float2* rows, int size,
                          __constant float4* waves) {
    int x = get_global_id(0), i = get_global_id(1);
    if (x >= size) return;
    float4 w = waves[i];
    float position = (x + 0.5f) / size;
    float c;
    float s = sincos(hfx_wave_angle(w.x, position, w.w), &c);
    columns[i * size + x] = (float2)(s, c);
    s = sincos(hfx_wave_angle(w.y, position, 0.0f), &c);
    rows[i * size + x] = (float2)(s, c);
}

/* Sum of the waves into a float height buffer, row y at v = (y + 0.5) / size. */
__kernel void waves(__global float* height, int size, __global const float2* columns,
                    __global const float2* rows, __constant float4* waves, int count,
                    float steepness, float inverseTotalAmplitude) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= size || y >= size) return;
    float sum = 0.0f;
    for (int i = 0; i < count; ++i) {
        float2 a = columns[i * size + x], b = rows[i * size + y];
        float s = a.x * b.y + a.y * b.x; /* sin(a + b) */
        sum += waves[i].z * hfx_wave_shape(s, steepness);
    }
    height[y * size + x] = hfx_wave_height(sum, inverseTotalAmplitude);
}
