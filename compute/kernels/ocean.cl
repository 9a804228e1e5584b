#include "OceanMath.h"

/* h(k, t) for every stored wave vector; h0 and omega were made on the host at set-up.
   t is reduced modulo the spectrum's repeat period (frequencies are multiples of 2 pi / T), so
   omega * t stays small and exact in float over any run. */
__kernel void ocean_spectrum(__global const float2* h0, __global const float* omega,
                             __global float2* out, int N, float t) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= N || y >= N) return;
    int k = y * N + x, mk = ((N - y) % N) * N + (N - x) % N; /* index of -k */
    float2 a = h0[k], b = h0[mk];
    float re, im;
    hfx_ocean_mode(a.x, a.y, b.x, b.y, -omega[k] * t, &re, &im);
    out[k] = (float2)(re, im);
}

/* The FFT's real part, mapped to h in [0,1]: 0.5 + height * scale, clamped. */
__kernel void ocean_height(__global const float2* field, __global float* height, int N, float scale) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= N || y >= N) return;
    height[y * N + x] = clamp(0.5f + field[y * N + x].x * scale, 0.0f, 1.0f);
}
