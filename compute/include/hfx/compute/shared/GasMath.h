#ifndef HFX_GAS_MATH_H
#define HFX_GAS_MATH_H
#include "ClPrelude.h"

/* Stable fluids (Stam 1999; Harris, GPU Gems ch. 38) on a staggered (MAC) grid of W x H cells,
   lengths in cells, velocities in cells per second. Cell (i, j) has its centre at (i+.5, j+.5);
   u lives on x-faces at (i, j+.5), v on y-faces at (i+.5, j). The divergence (faces to centres)
   and the pressure gradient (centres to faces) are both compact differences, so their product is
   exactly the 5-point Laplacian the pressure solve inverts: no mode escapes the projection.
   x is periodic. y is periodic, or walled: a wall lies on the y-faces of row 0 (which, on the
   wrapped grid, is also the top edge of row H-1), where v = 0 and pressure is Neumann. */

HFX_FN_INLINE int hfx_gas_wrap(int i, int n) {
    if (i >= 0 && i < n) return i; /* the common case costs no integer division */
    int m = i % n;
    return m < 0 ? m + n : m;
}

/* A neighbour's index, at most one step outside [0, n): a select, not an integer division. */
HFX_FN_INLINE int hfx_gas_step(int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); }

/* The sampling position of a field stored at (i + ox, j + oy), for a point (x, y). Solid in y:
   y is clamped to the stored rows inside the walls, so nothing is read across them (rows of v
   reach the top wall, row H, which wraps to the wall row 0; other fields stop at H-1). */
HFX_FN_INLINE void hfx_gas_position(int H, float x, float y, float ox, float oy, int walls, float* fx,
                             float* fy) {
    *fx = x - ox;
    *fy = y - oy;
    if (walls) *fy = HFX_MIN(HFX_MAX(*fy, 0.0f), oy == 0.0f ? (float)H : (float)(H - 1));
}

/* Bilinear sample of a field stored at (i + ox, j + oy), at point (x, y). */
HFX_FN_INLINE float hfx_gas_sample(HFX_GLOBAL const float* f, int W, int H, float x, float y, float ox,
                            float oy, int walls) {
    float fx, fy;
    hfx_gas_position(H, x, y, ox, oy, walls, &fx, &fy);
    float x0 = HFX_FLOOR(fx), y0 = HFX_FLOOR(fy), sx = fx - x0, sy = fy - y0;
    int i0 = hfx_gas_wrap((int)x0, W), j0 = hfx_gas_wrap((int)y0, H);
    int i1 = hfx_gas_step(i0 + 1, W), j1 = hfx_gas_step(j0 + 1, H);
    float a = f[j0 * W + i0] + sx * (f[j0 * W + i1] - f[j0 * W + i0]);
    float b = f[j1 * W + i0] + sx * (f[j1 * W + i1] - f[j1 * W + i0]);
    return a + sy * (b - a);
}

/* Smallest and largest of the 4 stored values around (x, y): MacCormack's limiter. */
HFX_FN_INLINE void hfx_gas_bounds(HFX_GLOBAL const float* f, int W, int H, float x, float y, float ox,
                           float oy, int walls, float* lo, float* hi) {
    float fx, fy;
    hfx_gas_position(H, x, y, ox, oy, walls, &fx, &fy);
    int i0 = hfx_gas_wrap((int)HFX_FLOOR(fx), W), j0 = hfx_gas_wrap((int)HFX_FLOOR(fy), H);
    int i1 = hfx_gas_step(i0 + 1, W), j1 = hfx_gas_step(j0 + 1, H);
    float a = f[j0 * W + i0], b = f[j0 * W + i1], c = f[j1 * W + i0], d = f[j1 * W + i1];
    *lo = HFX_MIN(HFX_MIN(a, b), HFX_MIN(c, d));
    *hi = HFX_MAX(HFX_MAX(a, b), HFX_MAX(c, d));
}

/* Where the value now at grid point (i + ox, j + oy) came from dt ago: traced back along the
   velocity with the midpoint rule. */
HFX_FN_INLINE void hfx_gas_departure(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v, int W, int H,
                              int i, int j, float ox, float oy, float dt, int walls, float* px,
                              float* py) {
    float x = (float)i + ox, y = (float)j + oy;
    float vx = hfx_gas_sample(u, W, H, x, y, 0.0f, 0.5f, walls);
    float vy = hfx_gas_sample(v, W, H, x, y, 0.5f, 0.0f, walls);
    float mx = x - 0.5f * dt * vx, my = y - 0.5f * dt * vy;
    vx = hfx_gas_sample(u, W, H, mx, my, 0.0f, 0.5f, walls);
    vy = hfx_gas_sample(v, W, H, mx, my, 0.5f, 0.0f, walls);
    *px = x - dt * vx;
    *py = y - dt * vy;
}

/* Semi-Lagrangian advection of the field stored at (i + ox, j + oy). */
HFX_FN_INLINE float hfx_gas_advect(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                            HFX_GLOBAL const float* src, int W, int H, int i, int j, float ox,
                            float oy, float dt, int walls) {
    float px, py;
    hfx_gas_departure(u, v, W, H, i, j, ox, oy, dt, walls, &px, &py);
    return hfx_gas_sample(src, W, H, px, py, ox, oy, walls);
}

/* MacCormack's correction (Selle et al. 2008): forward = advect(src, dt), backward =
   advect(forward, -dt); the estimate forward + (src - backward) / 2 is second order, and is
   clamped to the values around the departure point so it adds no new extrema. */
HFX_FN_INLINE float hfx_gas_maccormack(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                                HFX_GLOBAL const float* src, HFX_GLOBAL const float* forward,
                                HFX_GLOBAL const float* backward, int W, int H, int i, int j,
                                float ox, float oy, float dt, int walls) {
    int k = j * W + i;
    float corrected = forward[k] + 0.5f * (src[k] - backward[k]);
    float px, py, lo, hi;
    hfx_gas_departure(u, v, W, H, i, j, ox, oy, dt, walls, &px, &py);
    hfx_gas_bounds(src, W, H, px, py, ox, oy, walls, &lo, &hi);
    return HFX_MIN(HFX_MAX(corrected, lo), hi);
}

/* Divergence of cell (i, j): outflow through its four faces. */
HFX_FN_INLINE float hfx_gas_divergence(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v, int W, int H,
                                int i, int j) {
    int ir = hfx_gas_step(i + 1, W), jt = hfx_gas_step(j + 1, H);
    return (u[j * W + ir] - u[j * W + i]) + (v[jt * W + i] - v[j * W + i]);
}

/* One Jacobi sweep of the pressure Poisson equation sum(p_n - p) = div at cell (i, j);
   across a wall the neighbour is left out (Neumann). */
HFX_FN_INLINE float hfx_gas_pressure_jacobi(HFX_GLOBAL const float* p, HFX_GLOBAL const float* div, int W,
                                     int H, int i, int j, int walls) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    float sum = p[j * W + il] + p[j * W + ir];
    float n = 2.0f;
    if (!walls || j > 0) { sum += p[jb * W + i]; n += 1.0f; }
    if (!walls || j < H - 1) { sum += p[jt * W + i]; n += 1.0f; }
    return (sum - div[j * W + i]) / n;
}

/* One Jacobi sweep of implicit viscosity (1 - a L) x = x0 on a face field (periodic stencil;
   solid walls keep v = 0 on row 0, handled by the caller). */
HFX_FN_INLINE float hfx_gas_diffuse_jacobi(HFX_GLOBAL const float* x, HFX_GLOBAL const float* x0, int W,
                                    int H, int i, int j, float a) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    float sum = x[j * W + il] + x[j * W + ir] + x[jb * W + i] + x[jt * W + i];
    return (x0[j * W + i] + a * sum) / (1.0f + 4.0f * a);
}

/* Cell-centred vorticity dv/dx - du/dy from the face velocities around cell (i, j). */
HFX_FN_INLINE float hfx_gas_curl(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v, int W, int H, int i,
                          int j) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    float vr = 0.5f * (v[j * W + ir] + v[jt * W + ir]), vl = 0.5f * (v[j * W + il] + v[jt * W + il]);
    float ut = 0.5f * (u[jt * W + i] + u[jt * W + ir]), ub = 0.5f * (u[jb * W + i] + u[jb * W + ir]);
    return 0.5f * (vr - vl) - 0.5f * (ut - ub);
}

/* Vorticity confinement (Fedkiw et al. 2001) at cell (i, j): eps * (N x w), N = grad|w| / |grad|w||.
   Writes the force's x and y. */
HFX_FN_INLINE void hfx_gas_confinement(HFX_GLOBAL const float* curl, int W, int H, int i, int j, float eps,
                                float* force) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    float gx = 0.5f * (HFX_FABS(curl[j * W + ir]) - HFX_FABS(curl[j * W + il]));
    float gy = 0.5f * (HFX_FABS(curl[jt * W + i]) - HFX_FABS(curl[jb * W + i]));
    float len = HFX_SQRT(gx * gx + gy * gy) + 1e-6f;
    float w = curl[j * W + i];
    force[0] = eps * (gy / len) * w;
    force[1] = -eps * (gx / len) * w;
}
#endif
