#include "OceanMath.h"

/* h(k, t) for the wave vectors with kx index 0..N/2; h0 and omega (N x N, FFT order) were made on
   the host at set-up. h(-k, t) = conj(h(k, t)) by construction, so the other half is implied and
   a complex-to-real transform of this half gives the height: half the transform's work.
   t is reduced modulo the spectrum's repeat period (frequencies are multiples of 2 pi / T), so
   omega * t stays small and exact in float over any run. */
__kernel void ocean_spectrum(__global const float2* h0, __global const float* omega,
                             __global float2* out, int N, float t) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x > N / 2 || y >= N) return;
    int k = y * N + x, mk = ((N - y) % N) * N + (N - x) % N; /* index of -k */
    float2 a = h0[k], b = h0[mk];
    float re, im;
    hfx_ocean_mode(a.x, a.y, b.x, b.y, -omega[k] * t, &re, &im);
    out[y * (N / 2 + 1) + x] = (float2)(re, im);
}

/* The transform's sum, mapped to h in [0,1]: 0.5 + height * scale, clamped. */
__kernel void ocean_height(__global const float* sum, __global float* height, int N, float scale) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= N || y >= N) return;
    height[y * N + x] = clamp(0.5f + sum[y * N + x] * scale, 0.0f, 1.0f);
}
