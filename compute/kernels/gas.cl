#include "GasMath.h"

/* Kernels of one stable-fluids step; see GasMath.h for the grid. x always wraps; y wraps when
   HFX_WRAP_V (hfx::edgeOptions), else walls bound it (WALLS), and face fields of v keep v = 0 on
   the wall row (j = 0). */
#define WALLS (!HFX_WRAP_V)

#define ID                                                                                         \
    int i = get_global_id(0), j = get_global_id(1);                                                \
    if (i >= W || j >= H) return;                                                                  \
    int k = j * W + i;

__kernel void advect(__global const float* restrict u, __global const float* restrict v,
                     __global const float* restrict metric, __global const float* restrict src,
                     __global float* restrict dst, int W, int H, float ox, float oy, float dt, int wallRow) {
    ID
    dst[k] = (WALLS && wallRow && j == 0) ? 0.0f
                                            : hfx_gas_advect(u, v, metric, src, W, H, i, j, ox, oy, dt, WALLS);
}

/* MacCormack's first pass: advect's, keeping each cell's departure point for the correction,
   which would otherwise trace it again (on PoCL, a third of the advection's time). */
__kernel void advect_forward(__global const float* restrict u, __global const float* restrict v,
                             __global const float* restrict metric, __global const float* restrict src,
                             __global float* restrict dst, __global float2* restrict departures, int W, int H,
                             float ox, float oy, float dt, int wallRow) {
    ID
    if (WALLS && wallRow && j == 0) { /* (maccormack writes the wall's 0 without its departure) */
        dst[k] = 0.0f;
        return;
    }
    float px, py;
    hfx_gas_departure(u, v, metric, W, H, i, j, ox, oy, dt, WALLS, &px, &py);
    departures[k] = (float2)(px, py);
    dst[k] = hfx_gas_sample(src, W, H, px, py, ox, oy, WALLS);
}

__kernel void maccormack(__global const float* src, __global const float* forward, __global const float* backward,
                         __global const float2* departures, __global float* dst, int W, int H, float ox, float oy,
                         int wallRow) {
    ID
    if (WALLS && wallRow && j == 0) {
        dst[k] = 0.0f;
        return;
    }
    const float2 d = departures[k];
    dst[k] = hfx_gas_maccormack_from(src, forward, backward, W, H, i, j, ox, oy, d.x, d.y, WALLS);
}

/* The wind turned by the sphere's frame over dt (hfx_gas_turn; zonal: each row's sum of u), into
   uOut and vOut. */
__kernel void turn(__global const float* restrict u, __global const float* restrict v,
                   __global const float* restrict metric, __global const float* restrict zonal,
                   __global float* restrict uOut, __global float* restrict vOut, int W, int H, float dt) {
    ID
    float a, b;
    hfx_gas_turn(u, v, metric, zonal, W, H, i, j, dt, WALLS, &a, &b);
    uOut[k] = a;
    vOut[k] = b;
}

/* Each face row's mean v taken away (one work-item a row; the wall's row stays 0): between walls
   no gas crosses a whole row, so the zonal mean of an incompressible flow's v is 0 on every face
   row, and this is the projection's zonal part done exactly (its pressure a function of the row
   alone, its gradient along v alone), the part Jacobi's sweeps converge slowest on. */
__kernel void remove_row_mean(__global float* v, int W, int H) {
    int j = get_global_id(0);
    if (j >= H || j == 0) return;
    float mean = hfx_gas_row_sum(v + j * W, W) / (float)W;
    for (int i = 0; i < W; ++i) v[j * W + i] -= mean;
}

/* The cell (i, j) a work-item of a w x h window from cell (i0, j0) stands on, x wrapped, and y
   wrapped too where there are no walls; false off the window or past a wall. */
inline int hfx_window_cell(int W, int H, int i0, int j0, int w, int h, int* i, int* j) {
    int gi = get_global_id(0), gj = get_global_id(1);
    if (gi >= w || gj >= h) return 0;
    *i = hfx_gas_wrap(i0 + gi, W);
    *j = j0 + gj;
    if (WALLS ? (*j < 0 || *j >= H) : 0) return 0;
    *j = hfx_gas_wrap(*j, H);
    return 1;
}

/* An offset (cells) between two points, the shorter way round where the map wraps. */
inline float2 hfx_window_offset(int W, int H, float dx, float dy) {
    dx -= W * rint(dx / W);
    if (!WALLS) dy -= H * rint(dy / H);
    return (float2)(dx, dy);
}

/* A splat of force (cells/s^2 for dt seconds) and dye (added, or where target >= 0 moved that
   share of the way to it) at (x, y) cells: the force's Gaussian round, of radius r, the dye's an
   oval, exp(-rho^2) with rho^2 = dx^2 / (aspect r)^2 + dy^2 / r^2, and the target wound into
   `arms` spiral arms of armTarget (GasArms, their mean over the step's sweep), over the
   w x h window of cells from (i0, j0) (GasField::step: 6 of the oval's radii about the centre,
   where its Gaussian falls below 10^-15 of its peak; x wraps, and y too where there are no
   walls). */
__kernel void splat(__global float* u, __global float* v, __global float* dye, int W, int H, float x,
                    float y, float r, float fx, float fy, float amount, float target, float dt, int i0, int j0,
                    int w, int h, float aspect, int arms, float armTarget, float contrast, float turned,
                    float winding, float sinc1, float sinc2) {
    int i, j;
    if (!hfx_window_cell(W, H, i0, j0, w, h, &i, &j)) return;
    int k = j * W + i;
    float2 o = hfx_window_offset(W, H, (float)i + 0.5f - x, (float)j + 0.5f - y);
    float dx = o.x, dy = o.y;
    /* (A uniform branch: a storm's feed pushes nothing, and adding nothing changes no bit.) */
    if (fx != 0.0f) u[k] += dt * fx * exp(-((dx + 0.5f) * (dx + 0.5f) + dy * dy) / (r * r));
    if (fy != 0.0f) {
        if (!(WALLS && j == 0)) v[k] += dt * fy * exp(-(dx * dx + (dy + 0.5f) * (dy + 0.5f)) / (r * r));
    }
    float ex = dx / (aspect * r), ey = dy / r, rho2 = ex * ex + ey * ey, e = exp(-rho2);
    if (target >= 0.0f && arms > 0) {
        /* The crest's square, (1 + cos t)^2 / 4 = 3/8 + cos(t) / 2 + cos(2t) / 8, averaged over
           the step's sweep: each harmonic scaled by sinc of half the phase it sweeps (sinc1,
           sinc2: GasField::step's). The harmonics only within 3 radii: beyond, the feed moves the
           dye by under 10^-4 of them a step (and by at most 10^-3 where the band's relaxation,
           0.15 a second, holds it), so there the arms are their mean. t = arms phi + arms
           (winding rim - turned): the first part's cosine and sine are the oval's direction
           raised to the power `arms` (no atan2). */
        float rim = 1.0f - e, crest2 = 0.375f;
        if (rho2 < 9.0f) {
            float len = sqrt(rho2), ur = len > 0.0f ? ex / len : 1.0f, ui = len > 0.0f ? ey / len : 0.0f;
            float zr = 1.0f, zi = 0.0f;
            for (int n = 0; n < arms; ++n) {
                float next = zr * ur - zi * ui;
                zi = zr * ui + zi * ur;
                zr = next;
            }
            float cb, sb = sincos((float)arms * (winding * rim - turned), &cb);
            float c = zr * cb - zi * sb;
            crest2 += 0.5f * sinc1 * c + 0.125f * sinc2 * (2.0f * c * c - 1.0f);
        }
        target += (armTarget - target) * contrast * fmin(rim / 0.6321f, 1.0f) * crest2;
    }
    dye[k] = target >= 0.0f ? dye[k] + (target - dye[k]) * clamp(amount * e, 0.0f, 1.0f)
                            : clamp(dye[k] + amount * e, 0.0f, 1.0f);
}

/* A vortex the velocity is held towards (GasField::addVortex) at (x, y) cells, semi-axes a along
   x and b along y (cells), over the w x h window from (i0, j0): each face moves share *
   exp(-rho^2) of the way to the drift + the wind of psi = psi0 exp(-rho^2), rho^2 = dx^2/a^2 +
   dy^2/b^2, which is u = d(psi)/dy = -2 dy / b^2 psi, v = -d(psi)/dx / m = 2 dx / a^2 psi / m (on a
   sphere's map, m v = -d(psi)/dx keeps the wind divergence-free under its metric, GasMath.h: the
   oval's shape is the map's, its wind the sphere's). */
__kernel void vortex(__global float* u, __global float* v, __global const float* metric, int W, int H, float x,
                     float y, float a, float b, float psi0, float driftX, float driftY, float share, int i0, int j0,
                     int w, int h) {
    int i, j;
    if (!hfx_window_cell(W, H, i0, j0, w, h, &i, &j)) return;
    int k = j * W + i;
    float2 o = hfx_window_offset(W, H, (float)i - x, (float)j + 0.5f - y); /* the u face */
    float rho2 = o.x * o.x / (a * a) + o.y * o.y / (b * b), psi = psi0 * exp(-rho2);
    u[k] += (driftX - 2.0f * o.y / (b * b) * psi - u[k]) * share * exp(-rho2);
    if (WALLS && j == 0) return; /* v = 0 on the wall */
    o = hfx_window_offset(W, H, (float)i + 0.5f - x, (float)j - y); /* the v face */
    rho2 = o.x * o.x / (a * a) + o.y * o.y / (b * b);
    psi = psi0 * exp(-rho2);
    v[k] += (driftY + 2.0f * o.x / (a * a) * psi / metric[2 * j] - v[k]) * share * exp(-rho2);
}

/* The velocity at n points (cells), bilinear from the faces: GasField::velocityAt. */
__kernel void sample_velocity(__global const float* u, __global const float* v, __global const float* points,
                              __global float* out, int n, int W, int H) {
    int i = get_global_id(0);
    if (i >= n) return;
    float x = points[2 * i], y = points[2 * i + 1];
    out[2 * i] = hfx_gas_sample(u, W, H, x, y, 0.0f, 0.5f, WALLS);
    out[2 * i + 1] = hfx_gas_sample(v, W, H, x, y, 0.5f, 0.0f, WALLS);
}

/* Zonal jets: u moves `share` of the way to its row's jet (GasField's jetRows: a function of the
   row alone, worked out once on the host, where three transcendentals a cell took a CPU device a
   fifth of the planet's step). */
__kernel void jets(__global float* u, __global const float* rows, int W, int H, float share) {
    ID
    u[k] += (rows[j] - u[k]) * share;
}

/* The dye moves `share` of the way to its row's band (GasConfig::dyeRate). */
__kernel void relax_dye(__global float* dye, __global const float* rows, int W, int H, float share) {
    ID
    dye[k] += (rows[j] - dye[k]) * share;
}

/* Bounds the velocity: each component to +-limit cells per second. */
__kernel void clamp_speed(__global float* u, __global float* v, int W, int H, float limit) {
    ID
    u[k] = clamp(u[k], -limit, limit);
    v[k] = clamp(v[k], -limit, limit);
}

__kernel void curl(__global const float* u, __global const float* v, __global const float* metric,
                   __global float* w, int W, int H) {
    ID
    w[k] = hfx_gas_curl(u, v, metric, W, H, i, j);
}

/* Adds the confinement force, computed at the two cells beside each face, to u and v. */
__kernel void confine(__global const float* w, __global float* u, __global float* v, int W, int H,
                      float eps, float dt) {
    ID
    float a[2], b[2];
    hfx_gas_confinement(w, W, H, i, j, eps, a);
    hfx_gas_confinement(w, W, H, hfx_gas_step(i - 1, W), j, eps, b);
    u[k] += dt * 0.5f * (a[0] + b[0]);
    if (WALLS && j == 0) return;
    hfx_gas_confinement(w, W, H, i, hfx_gas_step(j - 1, H), eps, b);
    v[k] += dt * 0.5f * (a[1] + b[1]);
}

__kernel void diffuse(__global const float* x, __global const float* x0, __global float* dst, int W,
                      int H, float a, int wallRow) {
    ID
    dst[k] = (WALLS && wallRow && j == 0) ? 0.0f : hfx_gas_diffuse_jacobi(x, x0, W, H, i, j, a);
}

__kernel void divergence(__global const float* u, __global const float* v, __global const float* metric,
                         __global float* div, int W, int H) {
    ID
    div[k] = hfx_gas_divergence(u, v, metric, W, H, i, j);
}

__kernel void pressure(__global const float* p, __global const float* div, __global const float* metric,
                       __global float* dst, int W, int H) {
    ID
    dst[k] = hfx_gas_pressure_jacobi(p, div, metric, W, H, i, j, WALLS);
}

/* The same sweep, four cells along i per work-item (W a multiple of 4), as float4: the rows are
   loaded once with vload4 and shifted for the left and right neighbours. The weights are the
   row's, and the operations run in hfx_gas_pressure_jacobi's order (left + right, then below,
   then above), so the results are the same bit for bit. */
__kernel void pressure4(__global const float* p, __global const float* div, __global const float* metric,
                        __global float* dst, int W, int H) {
    int i0 = get_global_id(0) * 4, j = get_global_id(1);
    if (i0 >= W || j >= H) return;
    int row = j * W;
    float w[4];
    hfx_gas_pressure_weights(metric, H, j, WALLS, w);
    float4 c = vload4(0, p + row + i0);
    float l = p[row + hfx_gas_step(i0 - 1, W)], r = p[row + hfx_gas_step(i0 + 4, W)];
    float4 sum = w[0] * ((float4)(l, c.x, c.y, c.z) + (float4)(c.y, c.z, c.w, r));
    if (w[1] != 0.0f) sum += w[1] * vload4(0, p + hfx_gas_step(j - 1, H) * W + i0);
    if (w[2] != 0.0f) sum += w[2] * vload4(0, p + hfx_gas_step(j + 1, H) * W + i0);
    vstore4((sum - w[3] * vload4(0, div + row + i0)) / (2.0f * w[0] + w[1] + w[2]), 0, dst + row + i0);
}

/* GasPressure::Exact between walls, one zonal wavenumber k a work-item (K = W/2 + 1 of them):
   `s` holds the rows' transforms of the divergence (rows of K complex values, RealFft::Rows) and
   becomes the pressure's. Along y each k's tridiagonal system (the Jacobi sweep's equation, its x
   neighbours' sum turned into its eigenvalue: GasField.cpp's gasPressureColumns) is eliminated
   downward with the host's factors (the pivots' reciprocals and Thomas's c', H x K) and solved
   upward; `rhs` scales each row's divergence (its area and the inverse transform's 1 / W) and
   `lower` is each row's weight of the row below. A k whose pivots are 0 is singular, the zonal
   means, which have no divergence once each face row's mean v is gone: its pressure is 0. */
__kernel void solve_columns(__global float2* s, __global const float* upper, __global const float* pivots,
                            __global const float* lower, __global const float* rhs, int K, int H) {
    int k = get_global_id(0);
    if (k >= K) return;
    if (pivots[k] == 0.0f) {
        for (int j = 0; j < H; ++j) s[j * K + k] = (float2)(0.0f, 0.0f);
        return;
    }
    float2 x = (float2)(0.0f, 0.0f);
    for (int j = 0; j < H; ++j) {
        x = (rhs[j] * s[j * K + k] - lower[j] * x) * pivots[j * K + k];
        s[j * K + k] = x;
    }
    for (int j = H - 2; j >= 0; --j) {
        x = s[j * K + k] - upper[j * K + k] * x;
        s[j * K + k] = x;
    }
}

/* GasConfig::rotation's step, one zonal wavenumber k a work-item (K = W/2 + 1), on the projected
   wind: the beta term of the vorticity equation, d zeta / dt = -beta v (beta = df/dy, f = 2 omega
   sin(latitude)), taken implicitly, trapezoidal: zeta gains -dt beta (v + v') / 2, v' the wind
   after it, which adds and takes no energy however long the step. At the corners' rows 1..H-1
   (v at a corner is its two faces' mean), for the streamfunction psi of the gain (0 on the
   walls), whose add_stream wind has the vorticity -L psi / m with
     L psi = (psi[i-1] + psi[i+1] - 2 psi) / m + m(j+1/2) (psi[j+1] - psi) + m(j-1/2) (psi[j-1] - psi)
   (m the corner row's), this is, per k, the tridiagonal system
     (L_k + i dt beta sin(2 pi k / W) / 2) psi = m dt beta v_k.
   `s` holds the rows' transforms of v (rows of K, RealFft::Rows) and becomes psi's; `scratch`
   (as large) holds the elimination's c'; `scale` is the inverse transform's 1 / W. */
inline float2 hfx_cmul(float2 a, float2 b) { return (float2)(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
inline float2 hfx_cdiv(float2 a, float2 b) {
    return (float2)(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / (b.x * b.x + b.y * b.y);
}
__kernel void beta_columns(__global float2* s, __global float2* scratch, __global const float* metric, int W,
                           int H, float dt, float omega, float scale) {
    int k = get_global_id(0), K = W / 2 + 1;
    if (k >= K) return;
    float theta = 2.0f * (float)k / (float)W, sk = sinpi((float)k / (float)W);
    float eigen = 4.0f * sk * sk; /* 2 - 2 cos(theta pi) */
    float2 corner = (float2)(1.0f + cospi(theta), -sinpi(theta)) * 0.5f; /* a corner's two faces */
    s[k] = (float2)(0.0f, 0.0f);
    float2 c = (float2)(0.0f, 0.0f), d = (float2)(0.0f, 0.0f);
    for (int j = 1; j < H; ++j) {
        float m = metric[2 * j], below = metric[2 * j - 1], above = metric[2 * j + 1];
        float beta = 2.0f * omega * sinpi((float)j / (float)H) * M_PI_F / (float)H; /* cos(latitude) / R */
        float lower = j > 1 ? below : 0.0f, upper = j < H - 1 ? above : 0.0f;
        float2 diagonal = (float2)(-(below + above) - eigen / m, 0.5f * dt * beta * sinpi(theta));
        float2 pivot = diagonal - lower * c;
        float2 rhs = (m * dt * beta * scale) * hfx_cmul(s[j * K + k], corner);
        c = hfx_cdiv((float2)(upper, 0.0f), pivot);
        d = hfx_cdiv(rhs - lower * d, pivot);
        scratch[j * K + k] = c;
        s[j * K + k] = d;
    }
    for (int j = H - 2; j >= 1; --j) {
        d = s[j * K + k] - hfx_cmul(scratch[j * K + k], d);
        s[j * K + k] = d;
    }
}

/* GasConfig::viscosity on the sphere, first half, on the projected wind: at each corner of rows
   1..H-1, L psi of the wind's streamfunction psi (L as beta_columns writes it; the wind is
   add_stream's of psi), read from the faces about the corner:
     L psi = v(i-1, j) - v(i, j) + m(j+1/2) u(i, j) - m(j-1/2) u(i, j-1),
   the vorticity -L psi / m times -m. Row 0, the wall's corners, 0. */
__kernel void corner_laplacian(__global const float* u, __global const float* v, __global const float* metric,
                               __global float* out, int W, int H) {
    ID
    out[k] = j == 0 ? 0.0f
                    : v[j * W + hfx_gas_step(i - 1, W)] - v[k] + metric[2 * j + 1] * u[k] -
                          metric[2 * j - 1] * u[(j - 1) * W + i];
}

/* Second half, one zonal wavenumber k a work-item: the vorticity diffused implicitly, zeta' =
   (1 - a D)^-1 zeta with D = L / m the sphere's Laplacian at the corners and a = viscosity dt,
   is the wind of psi' = (1 - a D)^-1 psi, and the change psi' - psi solves
     (m - a L_k) (psi' - psi) = a (L psi)_k,
   one real tridiagonal system per k (walls: 0 at rows 0 and H), diagonally dominant. `s` holds
   the rows' transforms of L psi (corner_laplacian's, rows of K) and becomes the change's;
   `scratch` the elimination's c'; `scale` the inverse transform's 1 / W. Each spherical harmonic
   of degree n then loses the share a n (n + 1) / R^2 / (1 + a n (n + 1) / R^2) of its wind a step
   (R = H / pi cells), as on the flat grid each Fourier mode does. */
__kernel void viscous_columns(__global float2* s, __global float* scratch, __global const float* metric, int W,
                              int H, float a, float scale) {
    int k = get_global_id(0), K = W / 2 + 1;
    if (k >= K) return;
    float sk = sinpi((float)k / (float)W), eigen = 4.0f * sk * sk; /* 2 - 2 cos(2 pi k / W) */
    s[k] = (float2)(0.0f, 0.0f);
    float c = 0.0f;
    float2 d = (float2)(0.0f, 0.0f);
    for (int j = 1; j < H; ++j) {
        float m = metric[2 * j], below = metric[2 * j - 1], above = metric[2 * j + 1];
        float lower = j > 1 ? -a * below : 0.0f, upper = j < H - 1 ? -a * above : 0.0f;
        float pivot = m + a * (below + above + eigen / m) - lower * c;
        c = upper / pivot;
        d = ((a * scale) * s[j * K + k] - lower * d) / pivot;
        scratch[j * K + k] = c;
        s[j * K + k] = d;
    }
    for (int j = H - 2; j >= 1; --j) {
        d = s[j * K + k] - scratch[j * K + k] * d;
        s[j * K + k] = d;
    }
}

/* Adds the wind of the streamfunction psi at the corners (rows 0 and H, the walls, 0):
   u = psi(i, j+1) - psi(i, j), m v = psi(i, j) - psi(i+1, j), which has no divergence on the
   sphere (hfx_gas_divergence) and whose vorticity is -L psi / m (L as beta_columns writes it). */
__kernel void add_stream(__global float* u, __global float* v, __global const float* psi,
                         __global const float* metric, int W, int H) {
    ID
    u[k] += (j + 1 < H ? psi[(j + 1) * W + i] : 0.0f) - psi[k];
    if (j > 0) v[k] += (psi[k] - psi[j * W + hfx_gas_step(i + 1, W)]) / metric[2 * j];
}

/* GasPressure::Exact on a torus (a flat grid), one mode (k, l) a work-item: `s` holds the
   divergence's 2D transform (rows of K = W/2 + 1, RealFft::Both), and each mode is divided by
   the 5-point Laplacian's eigenvalue, -(2 - 2 cos(2 pi k / W)) - (2 - 2 cos(2 pi l / H)); the
   constant's pressure is 0. `scale`, 1 / (W H), is the inverse transform's. */
__kernel void pressure_modes(__global float2* s, int W, int H, float scale) {
    int k = get_global_id(0), l = get_global_id(1), K = W / 2 + 1;
    if (k >= K || l >= H) return;
    float sx = sinpi((float)k / (float)W), sy = sinpi((float)l / (float)H);
    float eigen = 4.0f * (sx * sx + sy * sy); /* 2 - 2 cos 2a = 4 sin^2 a, exact for the longest waves */
    s[l * K + k] = (k == 0 && l == 0) ? (float2)(0.0f, 0.0f) : s[l * K + k] * (-scale / eigen);
}

/* u -= grad p on every face (along x over the row's m); the wall's v stays 0. */
__kernel void project(__global float* u, __global float* v, __global const float* p,
                      __global const float* metric, int W, int H) {
    ID
    u[k] -= (p[k] - p[j * W + hfx_gas_step(i - 1, W)]) / metric[2 * j + 1];
    v[k] = (WALLS && j == 0) ? 0.0f : v[k] - (p[k] - p[hfx_gas_step(j - 1, H) * W + i]);
}

__kernel void dye_height(__global const float* dye, __global float* height, int W, int H) {
    ID
    height[k] = clamp(dye[k], 0.0f, 1.0f);
}

/* Dye mass, kept by a global correction: advection by interpolation (and MacCormack's limiter
   above all) is not conservative. Row sums (Kahan), then one work-item totals them, each row
   weighted by its cells' area (the metric's m, 1 on a flat grid), and leaves before/after in
   factor[0], then every texel scales: no read-back, no host round trip. */
__kernel void row_sums(__global const float* f, __global float* sums, int W, int H) {
    int j = get_global_id(0);
    if (j >= H) return;
    sums[j] = hfx_gas_row_sum(f + j * W, W);
}

__kernel void mass_factor(__global const float* before, __global const float* after,
                          __global const float* metric, int H, __global float* factor) {
    if (get_global_id(0) != 0) return;
    float a = 0.0f, b = 0.0f;
    for (int j = 0; j < H; ++j) {
        a += before[j] * metric[2 * j + 1];
        b += after[j] * metric[2 * j + 1];
    }
    factor[0] = b > 0.0f ? a / b : 1.0f;
}

__kernel void scale(__global float* f, __global const float* factor, int W, int H) {
    ID
    f[k] = clamp(f[k] * factor[0], 0.0f, 1.0f);
}
