#ifndef HFX_OCEAN_MATH_H
#define HFX_OCEAN_MATH_H
#include "ClPrelude.h"

/* Tessendorf's statistical ocean. The spectrum is stored at FFT index (x, y) for the wave
   vector k = 2 pi (n, m) / L with n = x for x < N/2 and x - N otherwise (likewise m), so the
   inverse DFT of the array is the field at the grid points, with no sign flips.

   h(k, t) = h0(k) e^{-i w t} + conj(h0(-k)) e^{i w t}: Hermitian in k, so the height is real,
   and the mode h0(k) e^{i (k.x - w t)} travels along +k (downwind for a wind spectrum).
   Writes the real and imaginary parts of h(k, t) given h0(k), h0(-k) and phase = -w t. */
HFX_FN void hfx_ocean_mode(float h0re, float h0im, float h0mre, float h0mim, float phase,
                           float* re, float* im) {
#ifdef __OPENCL_VERSION__
    float c, s = sincos(phase, &c);
#else
    float c = HFX_COS(phase), s = HFX_SIN(phase);
#endif
    /* h0 (c + i s) + conj(h0m) (c - i s), with phase = -w t */
    *re = (h0re * c - h0im * s) + (h0mre * c - h0mim * s);
    *im = (h0re * s + h0im * c) - (h0mre * s + h0mim * c);
}

/* A wind change's amplitude at blend s in [0, 1] from a (the old sea's h0(k)) to b (the new):
   the energy |h|^2 = (1 - s)|a|^2 + s|b|^2 moves linearly, so the spectrum is the linear mix of
   the two and the sea keeps its height mid-change, and the phase is that of mix(a, b, s): a
   and b of one k share their random phase (OceanField draws it per k), so it stays where it is
   and the waves fade in and out in place. Zero where the mix vanishes; a itself at s <= 0 and b
   at s >= 1, exactly: a device's square root and division may be a few ulps off (OpenCL allows
   3 and 2.5), which made the sea move by an ulp the moment a change began. */
HFX_FN void hfx_ocean_blend(float are, float aim, float bre, float bim, float s, float* re, float* im) {
    if (s <= 0.0f) { /* the change has not begun: the old sea itself */
        *re = are;
        *im = aim;
        return;
    }
    if (s >= 1.0f) { /* no change in progress: the new sea itself (and two square roots saved) */
        *re = bre;
        *im = bim;
        return;
    }
    float mre = are + s * (bre - are), mim = aim + s * (bim - aim);
    float len = HFX_SQRT(mre * mre + mim * mim);
    float energy = (1.0f - s) * (are * are + aim * aim) + s * (bre * bre + bim * bim);
    float g = len > 0.0f ? HFX_SQRT(energy) / len : 0.0f;
    *re = mre * g;
    *im = mim * g;
}

/* Bilinear sample of a periodic N x N field (N a power of two) at (x, y) in texel units, the
   grid points at whole numbers. */
HFX_FN_INLINE float hfx_ocean_sample(HFX_GLOBAL const float* f, int N, float x, float y) {
    float fx = HFX_FLOOR(x), fy = HFX_FLOOR(y);
    int i = (int)fx, j = (int)fy;
    float ax = x - fx, ay = y - fy;
    int m = N - 1;
    int i0 = i & m, i1 = (i + 1) & m, j0 = (j & m) * N, j1 = ((j + 1) & m) * N;
    float a = f[j0 + i0] + ax * (f[j0 + i1] - f[j0 + i0]);
    float b = f[j1 + i0] + ax * (f[j1 + i1] - f[j1 + i0]);
    return a + ay * (b - a);
}

/* d/dx of a periodic field along a row (stride 1) or a column (stride N) at index (i, j):
   fourth-order central differences, per texel: exact to (k dx)^4 / 30 of the slope. */
HFX_FN_INLINE float hfx_ocean_derivative(HFX_GLOBAL const float* f, int N, int i, int j, int alongX) {
    int m = N - 1;
    if (alongX) {
        int r = j * N;
        return (8.0f * (f[r + ((i + 1) & m)] - f[r + ((i - 1) & m)]) - (f[r + ((i + 2) & m)] - f[r + ((i - 2) & m)])) /
               12.0f;
    }
    return (8.0f * (f[((j + 1) & m) * N + i] - f[((j - 1) & m) * N + i]) -
            (f[((j + 2) & m) * N + i] - f[((j - 2) & m) * N + i])) /
           12.0f;
}

/* The gradient of lambda D at grid point (i, j) (dimensionless: lambdaPerTexel is the
   choppiness over the texel's size, D in metres): dDx/dx, dDy/dy, and the cross term, which is
   symmetric for D = i k^ h (a gradient field), averaged over its two differences. */
HFX_FN_INLINE void hfx_ocean_gradient(HFX_GLOBAL const float* dx, HFX_GLOBAL const float* dy, int N,
                                      float lambdaPerTexel, int i, int j, float* xx, float* yy, float* xy) {
    *xx = lambdaPerTexel * hfx_ocean_derivative(dx, N, i, j, 1);
    *yy = lambdaPerTexel * hfx_ocean_derivative(dy, N, i, j, 0);
    *xy = 0.5f * lambdaPerTexel * (hfx_ocean_derivative(dx, N, i, j, 0) + hfx_ocean_derivative(dy, N, i, j, 1));
}

/* The Jacobian determinant of x0 -> x0 + lambda D(x0) at grid point (i, j). */
HFX_FN_INLINE float hfx_ocean_jacobian(HFX_GLOBAL const float* dx, HFX_GLOBAL const float* dy, int N,
                                       float lambdaPerTexel, int i, int j) {
    float a = lambdaPerTexel * hfx_ocean_derivative(dx, N, i, j, 1);
    float b = lambdaPerTexel * hfx_ocean_derivative(dx, N, i, j, 0);
    float c = lambdaPerTexel * hfx_ocean_derivative(dy, N, i, j, 1);
    float d = lambdaPerTexel * hfx_ocean_derivative(dy, N, i, j, 0);
    return (1.0f + a) * (1.0f + d) - b * c;
}

/* The Lagrangian grid packed for the Eulerian resample: HFX_OCEAN_PACKED floats per texel, the
   displacement Dx, Dy (metres), its gradient lambda dDx/dx, dDy/dy, dDx/dy (hfx_ocean_gradient's),
   the height h (metres), the foam and its young part. A bilinear sample of all of them reads two
   pairs of neighbouring texels, two or four cache lines, where separate planes took fourteen: the
   resample's Newton steps were 18 of the 28 ms of a 512^2 cascade's step
   (docs/history/tuning.md). */
#define HFX_OCEAN_PACKED 8
#define HFX_OCEAN_DX 0
#define HFX_OCEAN_DY 1
#define HFX_OCEAN_GXX 2
#define HFX_OCEAN_GYY 3
#define HFX_OCEAN_GXY 4
#define HFX_OCEAN_H 5
#define HFX_OCEAN_FOAM 6
#define HFX_OCEAN_YOUNG 7
#define HFX_OCEAN_NEWTON_TOLERANCE 1e-3f

/* The bilinear cell of (x, y) (texel units) in a periodic N x N packed grid: the offsets of its
   four corners' first floats and the fractions. */
typedef struct HfxOceanCell {
    int c00, c10, c01, c11;
    float ax, ay;
} HfxOceanCell;

HFX_FN_INLINE HfxOceanCell hfx_ocean_cell(int N, float x, float y) {
    float fx = HFX_FLOOR(x), fy = HFX_FLOOR(y);
    int i = (int)fx, j = (int)fy, m = N - 1;
    int i0 = i & m, i1 = (i + 1) & m, j0 = (j & m) * N, j1 = ((j + 1) & m) * N;
    HfxOceanCell c;
    c.c00 = (j0 + i0) * HFX_OCEAN_PACKED;
    c.c10 = (j0 + i1) * HFX_OCEAN_PACKED;
    c.c01 = (j1 + i0) * HFX_OCEAN_PACKED;
    c.c11 = (j1 + i1) * HFX_OCEAN_PACKED;
    c.ax = x - fx;
    c.ay = y - fy;
    return c;
}

/* One channel of the packed grid at a cell: the same arithmetic as hfx_ocean_sample. */
HFX_FN_INLINE float hfx_ocean_lerp(HFX_GLOBAL const float* p, HfxOceanCell c, int channel) {
    float a = p[c.c00 + channel] + c.ax * (p[c.c10 + channel] - p[c.c00 + channel]);
    float b = p[c.c01 + channel] + c.ax * (p[c.c11 + channel] - p[c.c01 + channel]);
    return a + c.ay * (b - a);
}

/* Packs texel (i, j) of the Lagrangian grid: fields = h, Dx, Dy (N x N planes, metres). */
HFX_FN_INLINE void hfx_ocean_pack(HFX_GLOBAL const float* fields, int N, float lambdaPerTexel,
                                  int i, int j, float foam, float young, HFX_GLOBAL float* packed) {
    int n = N * N, k = j * N + i;
    HFX_GLOBAL float* p = packed + k * HFX_OCEAN_PACKED;
    float xx, yy, xy;
    hfx_ocean_gradient(fields + n, fields + 2 * n, N, lambdaPerTexel, i, j, &xx, &yy, &xy);
    p[HFX_OCEAN_DX] = fields[n + k];
    p[HFX_OCEAN_DY] = fields[2 * n + k];
    p[HFX_OCEAN_GXX] = xx;
    p[HFX_OCEAN_GYY] = yy;
    p[HFX_OCEAN_GXY] = xy;
    p[HFX_OCEAN_H] = fields[k];
    p[HFX_OCEAN_FOAM] = foam;
    p[HFX_OCEAN_YOUNG] = young;
}

/* The Newton step of hfx_ocean_lagrangian_texel at x0 = (px, py), given lambda D and its
   gradient there. */
HFX_FN_INLINE void hfx_ocean_newton(float x, float y, float lambdaPerTexel, float dx, float dy, float gxx, float gyy,
                                    float gxy, float* px, float* py) {
    float rx = *px + lambdaPerTexel * dx - x;
    float ry = *py + lambdaPerTexel * dy - y;
    float a = 1.0f + gxx, d = 1.0f + gyy, b = gxy;
    float det = a * d - b * b;
    if (det > 0.05f) {
        *px -= (d * rx - b * ry) / det;
        *py -= (a * ry - b * rx) / det;
    } else {
        *px -= rx;
        *py -= ry;
    }
}

/* The Lagrangian point x0 whose displaced position x0 + lambda D(x0) is texel (i, j): Newton's
   method on r(x0) = x0 + lambda D(x0) - x with the displacement's gradient (sampled bilinearly
   from the packed grid), from x0 = x, where the first step reads the texel itself. Quadratic
   where the map does not fold; where its Jacobian falls below 0.05 (a fold), the step is the
   plain fixed point x0 <- x - lambda D(x0) instead, which lands on one of the folded layers.
   Returns the cell of x0. */
HFX_FN_INLINE HfxOceanCell hfx_ocean_lagrangian_texel(HFX_GLOBAL const float* packed, int N, float lambdaPerTexel,
                                                      int iterations, int i, int j) {
    float x = (float)i, y = (float)j, px = x, py = y;
    if (iterations > 0) {
        HFX_GLOBAL const float* p = packed + (j * N + i) * HFX_OCEAN_PACKED;
        hfx_ocean_newton(x, y, lambdaPerTexel, p[HFX_OCEAN_DX], p[HFX_OCEAN_DY], p[HFX_OCEAN_GXX], p[HFX_OCEAN_GYY],
                         p[HFX_OCEAN_GXY], &px, &py);
    }
    HfxOceanCell c = hfx_ocean_cell(N, px, py);
    for (int it = 1; it < iterations; ++it) {
        float qx = px, qy = py;
        hfx_ocean_newton(x, y, lambdaPerTexel, hfx_ocean_lerp(packed, c, HFX_OCEAN_DX),
                         hfx_ocean_lerp(packed, c, HFX_OCEAN_DY), hfx_ocean_lerp(packed, c, HFX_OCEAN_GXX),
                         hfx_ocean_lerp(packed, c, HFX_OCEAN_GYY), hfx_ocean_lerp(packed, c, HFX_OCEAN_GXY), &px, &py);
        c = hfx_ocean_cell(N, px, py);
        if (HFX_FABS(px - qx) + HFX_FABS(py - qy) < HFX_OCEAN_NEWTON_TOLERANCE) break;
    }
    return c;
}
#endif
