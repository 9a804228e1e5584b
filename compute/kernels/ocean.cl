#include "OceanMath.h"

/* The half spectra of one cascade at time t: h(k, t), and with `displacement` the horizontal
   displacement D(k, t) = i k/|k| h(k, t) (x and y), each (N/2 + 1) x N, back to back. h(-k) =
   conj(h(k)) and so D(-k) = conj(D(k)): a complex-to-real transform of each half gives the
   field. h0 and omega (N x N, FFT order) are made on the host, zero outside the cascade's band;
   during a wind change h0 is blended from h0From (hfx_ocean_blend: the waves fade where they are).
   t is reduced modulo the repeat period (frequencies are multiples of 2 pi / T), so omega * t
   stays small and exact in float over any run. */
__kernel void ocean_spectrum(__global const float2* h0From, __global const float2* h0, float blend,
                             __global const float* omega, __global float2* out, int N, float t, float dk,
                             int displacement) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x > N / 2 || y >= N) return;
    int k = y * N + x, mk = ((N - y) % N) * N + (N - x) % N; /* index of -k */
    float are, aim, bre, bim;
    hfx_ocean_blend(h0From[k].x, h0From[k].y, h0[k].x, h0[k].y, blend, &are, &aim);
    hfx_ocean_blend(h0From[mk].x, h0From[mk].y, h0[mk].x, h0[mk].y, blend, &bre, &bim);
    float re, im;
    hfx_ocean_mode(are, aim, bre, bim, -omega[k] * t, &re, &im);
    int halves = (N / 2 + 1) * N, o = y * (N / 2 + 1) + x;
    out[o] = (float2)(re, im);
    if (!displacement) return;
    float kx = dk * (float)x, ky = dk * (float)(y < N / 2 ? y : y - N);
    float len = sqrt(kx * kx + ky * ky);
    float ux = len > 0.0f ? kx / len : 0.0f, uy = len > 0.0f ? ky / len : 0.0f;
    /* i (re + i im) = -im + i re */
    out[halves + o] = (float2)(-im * ux, re * ux);
    out[2 * halves + o] = (float2)(-im * uy, re * uy);
}

/* On the Lagrangian grid (the undisplaced points): the Jacobian of the displacement, and the
   foam, which is attached to the water (it rides the orbital motion with its point) and drifts
   downwind: last step's foam, `drift` texels upwind, decayed, plus what this step's J < threshold
   injects, capped at 1. Its young part is carried alike and decays faster (youngDecay): what is
   injected is young, and young foam is at most the foam. fields: h, Dx, Dy (N x N each, metres).
   Also the packed grid (hfx_ocean_pack: displacement, its gradient, height, foam, young foam)
   for the Eulerian resample. */
__kernel void ocean_lagrangian(__global const float* fields, __global const float* foamIn,
                               __global float* foamOut, __global const float* youngIn,
                               __global float* youngOut, __global float* jacobian,
                               __global float* packed, int N, float lambdaPerTexel, float decay,
                               float youngDecay, float injection, float threshold, float driftX,
                               float driftY) {
    int i = get_global_id(0), j = get_global_id(1);
    if (i >= N || j >= N) return;
    int n = N * N, k = j * N + i;
    float J = hfx_ocean_jacobian(fields + n, fields + 2 * n, N, lambdaPerTexel, i, j);
    jacobian[k] = J;
    float x = (float)i - driftX, y = (float)j - driftY;
    float injected = injection * fmax(threshold - J, 0.0f);
    float foam = clamp(hfx_ocean_sample(foamIn, N, x, y) * decay + injected, 0.0f, 1.0f);
    float young = clamp(hfx_ocean_sample(youngIn, N, x, y) * youngDecay + injected, 0.0f, foam);
    foamOut[k] = foam;
    youngOut[k] = young;
    hfx_ocean_pack(fields, N, lambdaPerTexel, i, j, foam, young, packed);
}

/* The Eulerian field the renderer traces: for texel (i, j), the Lagrangian point displaced onto
   it, and the height and foam there. height = 0.5 + metres * scale, clamped to [0,1]. The foam's
   texel is its coverage in alpha and its young part in red (OceanCascade::foamColor). */
__kernel void ocean_eulerian(__global const float* packed, __global float* height, __global float* meters,
                             __global uchar4* foamColor, int N, float lambdaPerTexel, float scale, int iterations) {
    int i = get_global_id(0), j = get_global_id(1);
    if (i >= N || j >= N) return;
    int k = j * N + i;
    HfxOceanCell c = hfx_ocean_lagrangian_texel(packed, N, lambdaPerTexel, iterations, i, j);
    float H = hfx_ocean_lerp(packed, c, HFX_OCEAN_H);
    meters[k] = H;
    height[k] = clamp(0.5f + H * scale, 0.0f, 1.0f);
    float f = hfx_ocean_lerp(packed, c, HFX_OCEAN_FOAM);
    float y = hfx_ocean_lerp(packed, c, HFX_OCEAN_YOUNG);
    foamColor[k] = (uchar4)(convert_uchar_sat(y * 255.0f + 0.5f), 255, 255,
                            convert_uchar_sat(f * 255.0f + 0.5f));
}
