#ifndef HFX_FLOW_MATH_H
#define HFX_FLOW_MATH_H
#include "GasMath.h"
#include "NoiseMath.h"

/* Detail finer than the gas's grid that moves with its flow: texture advection (Max & Becker 1995)
   with two regenerated layers (Neyret 2003, "Advected textures"). Each layer is a field of noise
   coordinates riding on the velocity, stored per cell centre as a displacement d (cells): the
   material now at x sat at x + d in the noise's domain when the layer was last regenerated. A
   semi-Lagrangian step keeps that true: c(x) = x + d(x) and c_new(x) = c_old(p), p the point the
   flow carries to x in dt, so d_new(x) = d_old(p) + (p - x). A shear stretches the noise into
   filaments along it, a vortex winds it into spiral arms; before the stretch grows too long the
   layer starts again from d = 0 with a fresh noise (its generation z), at the moment its weight is
   zero. Layer k's phase is a_k = frac(time / period + k / 2), its weight sin(pi a_k): the two
   weights' squares sum to 1, so the blend of two zero-mean noises keeps its contrast.

   The layers' noise reaches the heights two ways. Added (`amount`), it is a texture of its own
   everywhere. As a warp (`warp`, in cells), each layer's two noises (at z and z + 101) move the
   point at which the gas's heights are read: where the gas is flat (a band's middle) nothing
   changes, and where its colour changes (a band's edge, a storm's rim) the edge frays into the
   filaments the flow has stretched; a warped height is a blend of the gas's own, never outside
   the range around it.

   The detail is strongest where the flow strains (band edges, where the jets shear, and the rims
   of storms) and fades to a `calm` share of it where the flow only translates or turns as a
   whole (the middle of a band, a storm's eye): its amplitude follows the strain rate s (per
   second) as calm + (1 - calm) s / (s + strainScale), s kept per cell in a fifth plane.

   Lengths in gas cells; x wraps over W (longitude), y is walled (the gas's poles). */

/* The flow's strain rate at the centre of cell (i, j): sqrt((du/dx - dv/dy)^2 + (du/dy + dv/dx)^2),
   per second, from central differences of the velocity one cell apart (along x over the row's
   width m: GasMath.h's metric). */
HFX_FN_INLINE float hfx_flow_strain(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                                    HFX_GLOBAL const float* metric, int W, int H, int i, int j) {
    float x = (float)i + 0.5f, y = (float)j + 0.5f, m = metric[2 * j + 1];
    float ux = (hfx_gas_sample(u, W, H, x + 0.5f, y, 0.0f, 0.5f, 1) -
                hfx_gas_sample(u, W, H, x - 0.5f, y, 0.0f, 0.5f, 1)) / m;
    float vy = hfx_gas_sample(v, W, H, x, y + 0.5f, 0.5f, 0.0f, 1) - hfx_gas_sample(v, W, H, x, y - 0.5f, 0.5f, 0.0f, 1);
    float uy = 0.5f * (hfx_gas_sample(u, W, H, x, y + 1.0f, 0.0f, 0.5f, 1) -
                       hfx_gas_sample(u, W, H, x, y - 1.0f, 0.0f, 0.5f, 1));
    float vx = 0.5f * (hfx_gas_sample(v, W, H, x + 1.0f, y, 0.5f, 0.0f, 1) -
                       hfx_gas_sample(v, W, H, x - 1.0f, y, 0.5f, 0.0f, 1)) / m;
    float a = ux - vy, b = uy + vx;
    return HFX_SQRT(a * a + b * b);
}

/* One displacement plane (W x H, at the cell centres) advected: its new value at cell (i, j), whose
   centre the flow carried from (px, py) (hfx_gas_departure; one for all the planes). */
HFX_FN_INLINE float hfx_flow_advect_from(HFX_GLOBAL const float* d, int W, int H, int i, int j, float px,
                                         float py, int axis) {
    float moved = axis == 0 ? px - ((float)i + 0.5f) : py - ((float)j + 0.5f);
    return hfx_gas_sample(d, W, H, px, py, 0.5f, 0.5f, 1) + moved;
}

/* The same over dt, its departure traced here. */
HFX_FN_INLINE float hfx_flow_advect(HFX_GLOBAL const float* u, HFX_GLOBAL const float* v,
                                    HFX_GLOBAL const float* metric, HFX_GLOBAL const float* d, int W,
                                    int H, int i, int j, float dt, int axis) {
    float px, py;
    hfx_gas_departure(u, v, metric, W, H, i, j, 0.5f, 0.5f, dt, 1, &px, &py);
    return hfx_flow_advect_from(d, W, H, i, j, px, py, axis);
}

/* The detail noise at the noise-domain point (x, y) (cells) of generation z: Perlin fBm of
   `octaves` octaves from `frequency` lattice cells per gas cell along x and `aspect` times that
   along y (features that long along the bands), periodic over the W cells of a longitude
   (W * frequency whole), about zero-mean in [-0.5, 0.5]; the octaves past `finest` fade out
   (hfx_fractal_limited). */
HFX_FN float hfx_flow_noise(float x, float y, float z, int W, float frequency, float aspect, int octaves,
                            float finest) {
    return hfx_fractal_limited(HFX_NOISE_PERLIN, HFX_FRACTAL_FBM, x * frequency, y * frequency * aspect, z, octaves,
                               2.0f, 0.5f, (float)W * frequency, 256.0f, finest) -
           0.5f;
}

/* The same noise for a gas on a sphere's map (GasConfig::sphere), read at the sphere's point
   under (x, y): longitude 2 pi x / W, latitude pi (y / H - 1/2), on a sphere of W frequency / 2 pi
   lattice cells' radius (frequency lattice cells per cell of the equator, as hfx_flow_noise has
   along x), its polar axis scaled by `aspect` (along the bands near the equator, the features
   `aspect` times longer, as hfx_flow_noise's; isotropic at a pole, where the axis points out of
   the surface), the generation z moving the point through Perlin's 256-cell lattice. Round on
   the sphere, so its features do not narrow into wedges towards a pole, and seamless across
   the longitude's wrap and at the poles. */
HFX_FN float hfx_flow_noise_sphere(float x, float y, float z, int W, int H, float frequency, float aspect,
                                   int octaves, float finest) {
    float longitude = HFX_TWO_PI * x / (float)W, latitude = 0.5f * HFX_TWO_PI * (y / (float)H - 0.5f);
    float r = (float)W * frequency / HFX_TWO_PI, c = HFX_COS(latitude);
    float px = r * c * HFX_COS(longitude) + z, py = r * HFX_SIN(latitude) * aspect + 0.618034f * z;
    float pz = r * c * HFX_SIN(longitude);
    return hfx_fractal_octaves(HFX_NOISE_PERLIN, HFX_FRACTAL_FBM, px, py, pz, 1, octaves, 2.0f, 0.5f, 0.0f, 0.0f,
                               finest) -
           0.5f;
}

/* Uniform cubic B-spline weights of the four samples around a point t in [0, 1) past the second. */
HFX_FN void hfx_bspline(float t, float* w) {
    float s = 1.0f - t, t2 = t * t;
    w[0] = s * s * s / 6.0f;
    w[1] = (4.0f - 6.0f * t2 + 3.0f * t2 * t) / 6.0f;
    w[2] = (1.0f + 3.0f * t + 3.0f * t2 - 3.0f * t2 * t) / 6.0f;
    w[3] = t2 * t / 6.0f;
}

/* The gas's heights (at the cell centres) at the point (x, y) by a cubic B-spline along each
   axis: smooth in value, slope and curvature, so the fine grid's normals show no creases along
   the cells' edges (a bilinear fill facets them, and an interpolating cubic turns the gas's
   cell-sized noise into blocks); at a centre it is (f[i-1] + 4 f[i] + f[i+1]) / 6 along each
   axis: the grid's own scale, where the simulation is least exact, softened, and what is finer
   left to the advected detail. x wraps, y is clamped to the rows (walls). */
HFX_FN float hfx_flow_base(HFX_GLOBAL const float* f, int W, int H, float x, float y) {
    float fx = x - 0.5f, fy = y - 0.5f;
    float x0 = HFX_FLOOR(fx), y0 = HFX_FLOOR(fy);
    float wx[4], wy[4];
    hfx_bspline(fx - x0, wx);
    hfx_bspline(fy - y0, wy);
    float sum = 0.0f;
    for (int b = 0; b < 4; ++b) {
        int j = (int)y0 - 1 + b;
        j = j < 0 ? 0 : (j > H - 1 ? H - 1 : j);
        float row = 0.0f;
        for (int a = 0; a < 4; ++a) row += wx[a] * f[j * W + hfx_gas_wrap((int)x0 - 1 + a, W)];
        sum += wy[b] * row;
    }
    return sum;
}

/* The planes, each W x H at the cell centres: layer 0's displacement x and y, layer 1's, the strain
   rate at the last step, and each layer's finest octave (hfx_flow_cell_finest). */
#define HFX_FLOW_STRAIN 4
#define HFX_FLOW_FINEST 5
#define HFX_FLOW_PLANES 7

/* What the flow detail's kernels share besides the fields: the detail's shape, the output's
   texels per gas cell, and this frame's layer weights and generations. */
typedef struct HfxFlowParams {
    float amount, frequency, aspect, calm, strainScale;
    int octaves;
    float w0, w1, z0, z1;
    float warp, texels;
    int sphere; /* the gas is a sphere's map: hfx_flow_noise_sphere */
} HfxFlowParams;

/* The finest octave layer k's noise can show at the centre of cell (i, j), fractional: its lattice
   rides on the carried coordinates c(x) = x + d_k(x), which a shear squeezes, so one output texel
   (1 / texels cells) spans J = I + grad d_k of them, and octave i's lattice (frequency 2^i per
   cell along x, aspect times that along y) sigma * frequency * 2^i / texels of its cells, sigma the
   largest singular value of diag(1, aspect) J. An octave shows in full up to half a lattice cell a
   texel (what FlowDetail::octaves() allows an unsqueezed lattice, sigma = aspect) and is gone at
   one: finest = log2(texels / (2 frequency sigma)). Past it the noise would alias into texel-sized
   pits and ridges along the shears (a warped band edge's zipper, dark flecks in the planet's
   diffuse light). grad d_k by central differences of the cell's neighbours (one-sided at the
   walls); planes as hfx_flow_height's. */
HFX_FN float hfx_flow_cell_finest(HFX_GLOBAL const float* planes, int W, int H, int i, int j, int k, HfxFlowParams p) {
    const int n = W * H;
    HFX_GLOBAL const float* dx = planes + 2 * k * n;
    HFX_GLOBAL const float* dy = planes + (2 * k + 1) * n;
    int west = j * W + hfx_gas_step(i - 1, W), east = j * W + hfx_gas_step(i + 1, W);
    int south = (j > 0 ? j - 1 : 0) * W + i, north = (j < H - 1 ? j + 1 : H - 1) * W + i;
    float across = (j > 0 && j < H - 1) ? 0.5f : 1.0f; /* 1 / the rows between south and north */
    float a = 1.0f + 0.5f * (dx[east] - dx[west]), b = across * (dx[north] - dx[south]);
    float c = p.aspect * 0.5f * (dy[east] - dy[west]), d = p.aspect * (1.0f + across * (dy[north] - dy[south]));
    float squares = a * a + b * b + c * c + d * d, det = a * d - b * c;
    float sigma = HFX_SQRT(0.5f * (squares + HFX_SQRT(HFX_MAX(squares * squares - 4.0f * det * det, 0.0f))));
    return HFX_LOG2(p.texels / (2.0f * p.frequency * HFX_MAX(sigma, 1e-6f)));
}

/* Layer k's noises at the point (x, y) (cells), read at the point's carried coordinates and
   band-limited there (its finest octave, kept per cell: hfx_flow_cell_finest): of generation z
   into *along, and where `across` is not null of generation z + 101 into it. */
HFX_FN void hfx_flow_layer(HFX_GLOBAL const float* planes, int W, int H, float x, float y, int k, float z,
                           HfxFlowParams p, float* along, float* across) {
    const int n = W * H;
    float cx = x + hfx_gas_sample(planes + 2 * k * n, W, H, x, y, 0.5f, 0.5f, 1);
    float cy = y + hfx_gas_sample(planes + (2 * k + 1) * n, W, H, x, y, 0.5f, 0.5f, 1);
    float finest = hfx_gas_sample(planes + (HFX_FLOW_FINEST + k) * n, W, H, x, y, 0.5f, 0.5f, 1);
    if (p.sphere) { /* uniform */
        *along = hfx_flow_noise_sphere(cx, cy, z, W, H, p.frequency, p.aspect, p.octaves, finest);
        if (across) *across = hfx_flow_noise_sphere(cx, cy, z + 101.0f, W, H, p.frequency, p.aspect, p.octaves, finest);
    } else {
        *along = hfx_flow_noise(cx, cy, z, W, p.frequency, p.aspect, p.octaves, finest);
        if (across) *across = hfx_flow_noise(cx, cy, z + 101.0f, W, p.frequency, p.aspect, p.octaves, finest);
    }
}

/* A detailed height at the point (x, y) (cells) of the fine grid: the gas's heights
   (hfx_flow_base) read at the point moved by warp times the layers' noises (x by each layer's
   noise at z_k, y by its noise at z_k + 101), plus amount times the noises at z_k, each layer
   weighted, both times the strain's share; clamped to [0, 1]. planes: the HFX_FLOW_PLANES planes.
   The branches are uniform: a layer at weight 0, no warp, or no detail at all (a pole cap alone)
   reads no noise. */
HFX_FN float hfx_flow_height(HFX_GLOBAL const float* heights, HFX_GLOBAL const float* planes, int W,
                             int H, float x, float y, HfxFlowParams p) {
    float h;
    if (p.amount > 0.0f || p.warp > 0.0f) {
        float along = 0.0f, across = 0.0f, a, c;
        if (p.w0 > 0.0f) {
            hfx_flow_layer(planes, W, H, x, y, 0, p.z0, p, &a, p.warp > 0.0f ? &c : 0);
            along += p.w0 * a;
            if (p.warp > 0.0f) across += p.w0 * c;
        }
        if (p.w1 > 0.0f) {
            hfx_flow_layer(planes, W, H, x, y, 1, p.z1, p, &a, p.warp > 0.0f ? &c : 0);
            along += p.w1 * a;
            if (p.warp > 0.0f) across += p.w1 * c;
        }
        float s = hfx_gas_sample(planes + HFX_FLOW_STRAIN * W * H, W, H, x, y, 0.5f, 0.5f, 1);
        float share = p.calm + (1.0f - p.calm) * s / (s + p.strainScale);
        h = hfx_flow_base(heights, W, H, x + p.warp * share * along, y + p.warp * share * across) +
            p.amount * share * along;
    } else {
        h = hfx_flow_base(heights, W, H, x, y);
    }
    return h < 0.0f ? 0.0f : (h > 1.0f ? 1.0f : h);
}
#endif
