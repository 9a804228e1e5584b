#ifndef HFX_GAS_MATH_H
#define HFX_GAS_MATH_H
#include "ClPrelude.h"

/* Stable fluids (Stam 1999; Harris, GPU Gems ch. 38) on a staggered (MAC) grid of W x H cells,
   lengths in cells, velocities in cells per second. Cell (i, j) has its centre at (i+.5, j+.5);
   u lives on x-faces at (i, j+.5), v on y-faces at (i+.5, j). The divergence (faces to centres)
   and the pressure gradient (centres to faces) are both compact differences, so their product is
   exactly the 5-point Laplacian the pressure solve inverts: no mode escapes the projection.
   x is periodic. y is periodic, or walled: a wall lies on the y-faces of row 0 (which, on the
   wrapped grid, is also the top edge of row H-1), where v = 0 and pressure is Neumann.

   A sphere (GasConfig::sphere): the grid is a longitude-latitude map, the walls its poles, and
   a cell of longitude in row y is m(y) = (2H / W) sin(pi y / H) cells of latitude wide (1 at the
   equator of a 2:1 map). Lengths are in cells of latitude and u is the eastward wind in them, so
   a point moves u / m cells of the grid along x a second, and the differences along x, the
   divergence's fluxes and the pressure's weights carry m (the sphere's flux form). `metric`
   holds m at y = t / 2 for t in [0, 2H] (the face rows at even t, the rows' centres at odd t),
   then tan(latitude) / R at the same points (R = H / pi, the radius in cells; 0 at the poles);
   a flat grid's holds 1s and 0s, with which every function below is the flat one to the bit. */

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

/* The sum of a row's n values, compensated (Kahan): the dye's mass and a row's mean wind. */
HFX_FN_INLINE float hfx_gas_row_sum(HFX_GLOBAL const float* row, int n) {
    float sum = 0.0f, carry = 0.0f;
    for (int i = 0; i < n; ++i) {
        float y = row[i] - carry;
        float t = sum + y;
        carry = (t - sum) - y;
        sum = t;
    }
    return sum;
}

/* The metric m (a cell of longitude in cells of latitude) at row height y, linear between the
   table's half-row points, y held to the rows' centres (at a pole m is 0). */
HFX_FN_INLINE float hfx_gas_metric_at(HFX_GLOBAL const float* metric, int H, float y) {
    float t = 2.0f * HFX_MIN(HFX_MAX(y, 0.5f), (float)H - 0.5f);
    int t0 = (int)t < 2 * H - 1 ? (int)t : 2 * H - 1;
    return metric[t0] + (t - (float)t0) * (metric[t0 + 1] - metric[t0]);
}

/* Where the value now at grid point (i + ox, j + oy) came from dt ago: traced back along the
   velocity with the midpoint rule, the wind along x in cells of the grid (u / m). */
HFX_FN_INLINE void hfx_gas_departure(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                              HFX_GLOBAL const float* metric, int W, int H, int i, int j, float ox,
                              float oy, float dt, int walls, float* px, float* py) {
    float x = (float)i + ox, y = (float)j + oy;
    float vx = hfx_gas_sample(u, W, H, x, y, 0.0f, 0.5f, walls) / hfx_gas_metric_at(metric, H, y);
    float vy = hfx_gas_sample(v, W, H, x, y, 0.5f, 0.0f, walls);
    float mx = x - 0.5f * dt * vx, my = y - 0.5f * dt * vy;
    vx = hfx_gas_sample(u, W, H, mx, my, 0.0f, 0.5f, walls) / hfx_gas_metric_at(metric, H, my);
    vy = hfx_gas_sample(v, W, H, mx, my, 0.5f, 0.0f, walls);
    *px = x - dt * vx;
    *py = y - dt * vy;
}

/* Semi-Lagrangian advection of the field stored at (i + ox, j + oy). */
HFX_FN_INLINE float hfx_gas_advect(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                            HFX_GLOBAL const float* metric, HFX_GLOBAL const float* src, int W, int H,
                            int i, int j, float ox, float oy, float dt, int walls) {
    float px, py;
    hfx_gas_departure(u, v, metric, W, H, i, j, ox, oy, dt, walls, &px, &py);
    return hfx_gas_sample(src, W, H, px, py, ox, oy, walls);
}

/* MacCormack's correction (Selle et al. 2008): forward = advect(src, dt), backward =
   advect(forward, -dt); the estimate forward + (src - backward) / 2 is second order, and is
   clamped to the values around the departure point (px, py), the forward advection's, so it adds
   no new extrema. */
HFX_FN_INLINE float hfx_gas_maccormack_from(HFX_GLOBAL const float* src, HFX_GLOBAL const float* forward,
                                            HFX_GLOBAL const float* backward, int W, int H, int i, int j,
                                            float ox, float oy, float px, float py, int walls) {
    int k = j * W + i;
    float corrected = forward[k] + 0.5f * (src[k] - backward[k]);
    float lo, hi;
    hfx_gas_bounds(src, W, H, px, py, ox, oy, walls, &lo, &hi);
    return HFX_MIN(HFX_MAX(corrected, lo), hi);
}

/* The same, its departure point traced again. */
HFX_FN_INLINE float hfx_gas_maccormack(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                                HFX_GLOBAL const float* metric, HFX_GLOBAL const float* src,
                                HFX_GLOBAL const float* forward, HFX_GLOBAL const float* backward,
                                int W, int H, int i, int j, float ox, float oy, float dt, int walls) {
    float px, py;
    hfx_gas_departure(u, v, metric, W, H, i, j, ox, oy, dt, walls, &px, &py);
    return hfx_gas_maccormack_from(src, forward, backward, W, H, i, j, ox, oy, px, py, walls);
}

/* sin and cos of x together, written out: Cody and Waite's reduction by pi / 2 in three parts,
   then Cephes' single-precision polynomials on [-pi/4, pi/4]. Within 1e-7 of the true values, and
   1.6 ulp of those over 0.01, for |x| < 60 (GasMath.TheFramesSinCosIsWithinAnUlpAndAHalf): the same
   bits on the device and in the C++ reference, and no call left in the kernel, which a CPU
   device's compiler cannot vectorise across work-items (on PoCL, 2 cores of an AMD EPYC, the turn
   took 8.5 ms of the planet's 45 ms step with four sin and two cos calls a cell, 2.5 with these). */
HFX_FN_INLINE void hfx_gas_sincos(float x, float* s, float* c) {
    float k = HFX_FLOOR(x * 0.63661977236758134f + 0.5f); /* the nearest multiple of pi / 2 */
    float r = ((x - k * 1.5703125f) - k * 4.837512969970703125e-4f) - k * 7.54978995489188216e-8f;
    float r2 = r * r;
    float sr = r + r * r2 * (-1.6666654611e-1f + r2 * (8.3321608736e-3f + r2 * -1.9515295891e-4f));
    float cr = 1.0f - 0.5f * r2 +
               r2 * r2 * (4.166664568298827e-2f + r2 * (-1.388731625493765e-3f + r2 * 2.443315711809948e-5f));
    /* The quadrant, 0 to 3, k held within 2^24 first so that its conversion cannot overflow (an
       infinite or NaN x gives NaN through r, as sin and cos do). */
    int q = (int)HFX_MIN(HFX_MAX(k, -16777216.0f), 16777216.0f) & 3;
    *s = q == 0 ? sr : q == 1 ? cr : q == 2 ? -sr : -cr;
    *c = q == 0 ? cr : q == 1 ? -sr : q == 2 ? -cr : sr;
}

/* The wind turned as the sphere's frame turns under it (GasConfig::sphere): moving along x, the
   local east and north turn by u tan(latitude) / R a unit of length, so the curvature terms
   du/dt = u v tan / R and dv/dt = -u^2 tan / R turn (u, v) by -u tan dt / R. Each row's zonal
   mean wind (zonal: each row's sum of u) is not turned by its own share of that angle: its push,
   -mean^2 tan / R, is the same all along its row, and between walls the pressure's zonal part
   (which the projection finds exactly) balances it, so a zonal jet stays a jet at its speed
   (turned and then projected, it lost 1 - cos of its angle a step). The rest turns exactly, its
   speed kept however large the angle near a pole. At a u face, v is the four faces around it
   averaged; at a v face, u is, and the mean the two rows'. Writes the turned u and v of cell
   (i, j); the wall's v stays 0. */
HFX_FN_INLINE void hfx_gas_turn(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                                HFX_GLOBAL const float* metric, HFX_GLOBAL const float* zonal, int W,
                                int H, int i, int j, float dt, int walls, float* uOut, float* vOut) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    HFX_GLOBAL const float* tanR = metric + 2 * H + 1;
    float uk = u[j * W + i], vk = v[j * W + i];
    float vbar = 0.25f * (v[j * W + il] + vk + v[jt * W + il] + v[jt * W + i]);
    float mean = zonal[j] / (float)W, t = tanR[2 * j + 1] * dt;
    float a = -uk * t, own = a + mean * t; /* the angle, and the share not the mean's */
    float s, c, so, co;
    hfx_gas_sincos(a, &s, &c);
    hfx_gas_sincos(own, &so, &co);
    *uOut = (uk - mean) * c - vbar * s + mean * co;
    float ubar = 0.25f * (u[jb * W + i] + u[jb * W + ir] + uk + u[j * W + ir]);
    mean = 0.5f * (zonal[jb] + zonal[j]) / (float)W;
    t = tanR[2 * j] * dt;
    a = -ubar * t;
    own = a + mean * t;
    hfx_gas_sincos(a, &s, &c);
    hfx_gas_sincos(own, &so, &co);
    *vOut = (walls && j == 0) ? 0.0f : (ubar - mean) * s + vk * c + mean * so;
}

/* Divergence of cell (i, j): outflow through its four faces (their lengths the metric's), over
   its area m. */
HFX_FN_INLINE float hfx_gas_divergence(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                                HFX_GLOBAL const float* metric, int W, int H, int i, int j) {
    int ir = hfx_gas_step(i + 1, W), jt = hfx_gas_step(j + 1, H);
    return ((u[j * W + ir] - u[j * W + i]) + (v[jt * W + i] * metric[2 * j + 2] - v[j * W + i] * metric[2 * j])) /
           metric[2 * j + 1];
}

/* The weights of cell (i, j)'s pressure stencil: its neighbours along x (1 / m), below and above
   (the faces' m, 0 across a wall: Neumann), and its area m, which scales the divergence. */
HFX_FN_INLINE void hfx_gas_pressure_weights(HFX_GLOBAL const float* metric, int H, int j, int walls, float* w) {
    w[0] = 1.0f / metric[2 * j + 1];
    w[1] = (!walls || j > 0) ? metric[2 * j] : 0.0f;
    w[2] = (!walls || j < H - 1) ? metric[2 * j + 2] : 0.0f;
    w[3] = metric[2 * j + 1];
}

/* One Jacobi sweep of the pressure Poisson equation sum(w_n (p_n - p)) = m div at cell (i, j),
   weights as hfx_gas_pressure_weights gives them; across a wall the neighbour is left out. */
HFX_FN_INLINE float hfx_gas_pressure_jacobi(HFX_GLOBAL const float* p, HFX_GLOBAL const float* div,
                                     HFX_GLOBAL const float* metric, int W, int H, int i, int j,
                                     int walls) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    float w[4];
    hfx_gas_pressure_weights(metric, H, j, walls, w);
    float sum = w[0] * (p[j * W + il] + p[j * W + ir]);
    if (w[1] != 0.0f) sum += w[1] * p[jb * W + i];
    if (w[2] != 0.0f) sum += w[2] * p[jt * W + i];
    return (sum - w[3] * div[j * W + i]) / (2.0f * w[0] + w[1] + w[2]);
}

/* One Jacobi sweep of implicit viscosity (1 - a L) x = x0 on a face field (periodic stencil;
   solid walls keep v = 0 on row 0, handled by the caller; flat grids only). */
HFX_FN_INLINE float hfx_gas_diffuse_jacobi(HFX_GLOBAL const float* x, HFX_GLOBAL const float* x0, int W,
                                    int H, int i, int j, float a) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    float sum = x[j * W + il] + x[j * W + ir] + x[jb * W + i] + x[jt * W + i];
    return (x0[j * W + i] + a * sum) / (1.0f + 4.0f * a);
}

/* Cell-centred vorticity (dv/dx - d(m u)/dy) / m from the face velocities around cell (i, j). */
HFX_FN_INLINE float hfx_gas_curl(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                          HFX_GLOBAL const float* metric, int W, int H, int i, int j) {
    int il = hfx_gas_step(i - 1, W), ir = hfx_gas_step(i + 1, W);
    int jb = hfx_gas_step(j - 1, H), jt = hfx_gas_step(j + 1, H);
    float vr = 0.5f * (v[j * W + ir] + v[jt * W + ir]), vl = 0.5f * (v[j * W + il] + v[jt * W + il]);
    float ut = 0.5f * (u[jt * W + i] + u[jt * W + ir]) * metric[2 * jt + 1];
    float ub = 0.5f * (u[jb * W + i] + u[jb * W + ir]) * metric[2 * jb + 1];
    return (0.5f * (vr - vl) - 0.5f * (ut - ub)) / metric[2 * j + 1];
}

/* Vorticity confinement (Fedkiw et al. 2001) at cell (i, j): eps * (N x w), N = grad|w| / |grad|w||,
   on the map's cells (a sphere's too: it gives back what the grid's own dissipation takes, at the
   grid's scale). Writes the force's x and y. */
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
