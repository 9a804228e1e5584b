#ifndef HFX_NOISE_MATH_H
#define HFX_NOISE_MATH_H
#include "ClPrelude.h"

/* Gradient noises, computed in float the same way by the kernels and the C++ references.
   - Perlin's Improved Noise (SIGGRAPH 2002): his permutation, fade and grad, optionally periodic
     in x and y (lattice coordinates wrapped before hashing).
   - Simplex noise in 3D (Perlin 2001, as laid out by Gustavson 2005), same hash and gradients.
   - psrdnoise 2D (Gustavson & McEwan, JCGT 2022): periodic simplex noise on a hexagonal grid with
     gradients rotated by alpha, returning its exact gradient. */

HFX_CONSTANT int hfx_perm[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103,
    30,  69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,
    197, 62,  94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174,
    20,  125, 136, 171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166, 77,  146, 158, 231,
    83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,  55,  46,  245, 40,  244, 102, 143,
    54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,  18,  169, 200, 196,
    135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250, 124,
    123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,
    182, 189, 28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101,
    155, 167, 43,  172, 9,   129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185,
    112, 104, 218, 246, 97,  228, 251, 34,  242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,
    51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,  181, 199, 106, 157, 184, 84,  204, 176,
    115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114, 67,  29,  24,  72,  243,
    141, 128, 195, 78,  66,  215, 61,  156, 180};

/* Perlin's p[] of 512 entries is p[i & 255]; sums of a table entry and a coordinate stay < 512. */
HFX_FN int hfx_p(int i) { return hfx_perm[i & 255]; }
HFX_FN int hfx_wrap(int i, int period) {
    int m = i % period;
    return m < 0 ? m + period : m;
}
HFX_FN float hfx_fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
HFX_FN float hfx_lerp(float t, float a, float b) { return a + t * (b - a); }
HFX_FN float hfx_grad(int hash, float x, float y, float z) {
    int h = hash & 15;
    float u = h < 8 ? x : y;
    float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}
HFX_FN int hfx_hash3(int x, int y, int z) { return hfx_p(hfx_p(hfx_p(x) + y) + z); }

/* Improved Noise with the integer lattice wrapped to periodX x periodY in x and y (256 each:
   Perlin's own noise, whose table already repeats every 256). */
HFX_FN float hfx_perlin3_periodic(float x, float y, float z, int periodX, int periodY) {
    float fx = HFX_FLOOR(x), fy = HFX_FLOOR(y), fz = HFX_FLOOR(z);
    int X0 = hfx_wrap((int)fx, periodX), Y0 = hfx_wrap((int)fy, periodY), Z0 = ((int)fz) & 255;
    int X1 = hfx_wrap(X0 + 1, periodX), Y1 = hfx_wrap(Y0 + 1, periodY), Z1 = Z0 + 1;
    x -= fx;
    y -= fy;
    z -= fz;
    float u = hfx_fade(x), v = hfx_fade(y), w = hfx_fade(z);
    return hfx_lerp(
        w,
        hfx_lerp(v, hfx_lerp(u, hfx_grad(hfx_hash3(X0, Y0, Z0), x, y, z),
                             hfx_grad(hfx_hash3(X1, Y0, Z0), x - 1.0f, y, z)),
                 hfx_lerp(u, hfx_grad(hfx_hash3(X0, Y1, Z0), x, y - 1.0f, z),
                          hfx_grad(hfx_hash3(X1, Y1, Z0), x - 1.0f, y - 1.0f, z))),
        hfx_lerp(v, hfx_lerp(u, hfx_grad(hfx_hash3(X0, Y0, Z1), x, y, z - 1.0f),
                             hfx_grad(hfx_hash3(X1, Y0, Z1), x - 1.0f, y, z - 1.0f)),
                 hfx_lerp(u, hfx_grad(hfx_hash3(X0, Y1, Z1), x, y - 1.0f, z - 1.0f),
                          hfx_grad(hfx_hash3(X1, Y1, Z1), x - 1.0f, y - 1.0f, z - 1.0f))));
}
HFX_FN float hfx_perlin3(float x, float y, float z) { return hfx_perlin3_periodic(x, y, z, 256, 256); }

/* One corner of a simplex: (0.6 - r^2)^4 falloff times the gradient ramp. */
HFX_FN float hfx_simplex_corner(int hash, float x, float y, float z) {
    float t = 0.6f - x * x - y * y - z * z;
    if (t < 0.0f) return 0.0f;
    t *= t;
    return t * t * hfx_grad(hash, x, y, z);
}

/* 3D simplex noise, about [-1, 1]. */
HFX_FN float hfx_simplex3(float x, float y, float z) {
    const float F3 = 1.0f / 3.0f, G3 = 1.0f / 6.0f;
    float s = (x + y + z) * F3;
    float fi = HFX_FLOOR(x + s), fj = HFX_FLOOR(y + s), fk = HFX_FLOOR(z + s);
    float t = (fi + fj + fk) * G3;
    float x0 = x - (fi - t), y0 = y - (fj - t), z0 = z - (fk - t);
    int i1, j1, k1, i2, j2, k2; /* offsets of the second and third corners */
    if (x0 >= y0) {
        if (y0 >= z0) { i1 = 1; j1 = 0; k1 = 0; i2 = 1; j2 = 1; k2 = 0; }
        else if (x0 >= z0) { i1 = 1; j1 = 0; k1 = 0; i2 = 1; j2 = 0; k2 = 1; }
        else { i1 = 0; j1 = 0; k1 = 1; i2 = 1; j2 = 0; k2 = 1; }
    } else {
        if (y0 < z0) { i1 = 0; j1 = 0; k1 = 1; i2 = 0; j2 = 1; k2 = 1; }
        else if (x0 < z0) { i1 = 0; j1 = 1; k1 = 0; i2 = 0; j2 = 1; k2 = 1; }
        else { i1 = 0; j1 = 1; k1 = 0; i2 = 1; j2 = 1; k2 = 0; }
    }
    int i = ((int)fi) & 255, j = ((int)fj) & 255, k = ((int)fk) & 255;
    float n = hfx_simplex_corner(hfx_hash3(i, j, k), x0, y0, z0) +
              hfx_simplex_corner(hfx_hash3(i + i1, j + j1, k + k1), x0 - i1 + G3, y0 - j1 + G3, z0 - k1 + G3) +
              hfx_simplex_corner(hfx_hash3(i + i2, j + j2, k + k2), x0 - i2 + 2.0f * G3,
                                 y0 - j2 + 2.0f * G3, z0 - k2 + 2.0f * G3) +
              hfx_simplex_corner(hfx_hash3(i + 1, j + 1, k + 1), x0 - 1.0f + 3.0f * G3,
                                 y0 - 1.0f + 3.0f * G3, z0 - 1.0f + 3.0f * G3);
    return 32.0f * n;
}

HFX_FN float hfx_mod(float x, float period) { return x - HFX_FLOOR(x / period) * period; }

/* The psrdnoise hash of a hexagonal-lattice point (u, v), in [0, 289). */
HFX_FN float hfx_psrd_hash(float u, float v) {
    float h = hfx_mod(u, 289.0f);
    h = hfx_mod((h * 51.0f + 2.0f) * h + v, 289.0f);
    return hfx_mod((h * 34.0f + 10.0f) * h, 289.0f);
}

/* One corner: adds its value to *n and its gradient to g[0], g[1]. (vx, vy): the corner in
   texture space; (dx, dy) = position - corner. */
HFX_FN void hfx_psrd_corner(float vx, float vy, float dx, float dy, float periodX, float periodY,
                            float alpha, float* n, float* g) {
    float wx = periodX > 0.0f ? hfx_mod(vx, periodX) : vx;
    float wy = periodY > 0.0f ? hfx_mod(vy, periodY) : vy;
    /* Back to simplex space; the rounding fixes the float error of the wrap. */
    float iu = HFX_FLOOR(wx + 0.5f * wy + 0.5f), iv = HFX_FLOOR(wy + 0.5f);
    float psi = hfx_psrd_hash(iu, iv) * 0.07482f + alpha;
    float gx = HFX_COS(psi), gy = HFX_SIN(psi);
    float w = 0.8f - dx * dx - dy * dy;
    if (w <= 0.0f) return;
    float w2 = w * w, w4 = w2 * w2;
    float ramp = gx * dx + gy * dy;
    *n += w4 * ramp;
    float dw = -8.0f * w2 * w * ramp;
    g[0] += w4 * gx + dw * dx;
    g[1] += w4 * gy + dw * dy;
}

/* psrdnoise 2D, about [-1, 1]; periods > 0 tile (x: whole number, y: even whole number);
   writes the exact gradient d/dx, d/dy to gradient[0..1]. */
HFX_FN float hfx_psrdnoise2(float x, float y, float periodX, float periodY, float alpha, float* gradient) {
    float u = x + y * 0.5f, v = y;
    float i0u = HFX_FLOOR(u), i0v = HFX_FLOOR(v);
    float o1u = (u - i0u) >= (v - i0v) ? 1.0f : 0.0f, o1v = 1.0f - o1u;
    float v0x = i0u - i0v * 0.5f, v0y = i0v;
    float v1x = v0x + o1u - o1v * 0.5f, v1y = v0y + o1v;
    float v2x = v0x + 0.5f, v2y = v0y + 1.0f;
    float n = 0.0f, g[2] = {0.0f, 0.0f};
    hfx_psrd_corner(v0x, v0y, x - v0x, y - v0y, periodX, periodY, alpha, &n, g);
    hfx_psrd_corner(v1x, v1y, x - v1x, y - v1y, periodX, periodY, alpha, &n, g);
    hfx_psrd_corner(v2x, v2y, x - v2x, y - v2y, periodX, periodY, alpha, &n, g);
    gradient[0] = 10.9f * g[0];
    gradient[1] = 10.9f * g[1];
    return 10.9f * n;
}

/* Noise kinds and fractal sums, as the noise kernel's -D options and NoiseConfig name them. */
#define HFX_NOISE_PERLIN 0
#define HFX_NOISE_SIMPLEX 1
#define HFX_NOISE_PSRD 2
#define HFX_FRACTAL_FBM 0
#define HFX_FRACTAL_RIDGED 1
#define HFX_FRACTAL_TURBULENCE 2

/* One octave at lattice position (x, y) and time coordinate t: Perlin and simplex move through
   their third dimension, psrdnoise rotates its gradients by t. Periods <= 0: not periodic. */
HFX_FN float hfx_noise_octave(int kind, float x, float y, float t, float periodX, float periodY) {
    float g[2];
    if (kind == HFX_NOISE_PSRD) return hfx_psrdnoise2(x, y, periodX, periodY, t, g);
    if (kind == HFX_NOISE_SIMPLEX) return hfx_simplex3(x, y, t);
    return periodX > 0.0f ? hfx_perlin3_periodic(x, y, t, (int)periodX, (int)periodY)
                          : hfx_perlin3(x, y, t);
}

/* Sum of octaves at (x, y) in base-lattice units, mapped to [0,1]: fBm 0.5 + 0.5 sum / total,
   ridged sum (1 - |n|)^2 / total, turbulence sum |n| / total (total = sum of the amplitudes).
   Each octave scales the position and the periods by `lacunarity` (2 keeps periods whole) and
   shifts by a fixed offset so octaves do not line up at the origin.
   Band-limited: octave i counts with weight clamp(1 + finest - i, 0, 1), so those past `finest`
   (an octave's index, fractional) fade out over one octave and are not evaluated, while `total`
   stays every octave's: the coarse octaves keep their contrast where the fine ones go (Musgrave's
   fractional octaves, for a point whose lattice is squeezed below what its texels can show).
   t is the noise's third axis: with solid 0, a time each octave reads as it is (shifted); with
   solid 1, a third axis of space, scaled and shifted with x and y (a solid noise, periods 0). */
HFX_FN float hfx_fractal_octaves(int kind, int fractal, float x, float y, float t, int solid, int octaves,
                                 float lacunarity, float gain, float periodX, float periodY, float finest) {
    /* The octaves with a weight, i < finest + 1, run as a loop of their own: no branch in it. */
    int shown = finest + 1.0f >= (float)octaves ? octaves : (finest + 1.0f > 0.0f ? (int)HFX_CEIL(finest + 1.0f) : 0);
    float sum = 0.0f, amplitude = 1.0f, total = 0.0f, scale = 1.0f;
    for (int i = 0; i < shown; ++i) {
        float weight = HFX_MIN(1.0f + finest - (float)i, 1.0f);
        float offset = 17.0f * (float)i;
        float n = hfx_noise_octave(kind, x * scale + offset, y * scale + offset,
                                   solid ? t * scale + offset : t + 3.7f * (float)i, periodX * scale, periodY * scale);
        if (fractal == HFX_FRACTAL_RIDGED) {
            float r = 1.0f - HFX_FABS(n);
            n = r * r;
        } else if (fractal == HFX_FRACTAL_TURBULENCE) {
            n = HFX_FABS(n);
        }
        sum += amplitude * weight * n;
        amplitude *= gain;
        scale *= lacunarity;
    }
    amplitude = 1.0f;
    for (int i = 0; i < octaves; ++i) {
        total += amplitude;
        amplitude *= gain;
    }
    float h = fractal == HFX_FRACTAL_FBM ? 0.5f + 0.5f * sum / total : sum / total;
    return h < 0.0f ? 0.0f : (h > 1.0f ? 1.0f : h);
}

/* hfx_fractal_octaves over a plane, t its time. */
HFX_FN float hfx_fractal_limited(int kind, int fractal, float x, float y, float t, int octaves,
                                 float lacunarity, float gain, float periodX, float periodY, float finest) {
    return hfx_fractal_octaves(kind, fractal, x, y, t, 0, octaves, lacunarity, gain, periodX, periodY, finest);
}

/* Every octave at full weight. */
HFX_FN float hfx_fractal(int kind, int fractal, float x, float y, float t, int octaves,
                         float lacunarity, float gain, float periodX, float periodY) {
    return hfx_fractal_limited(kind, fractal, x, y, t, octaves, lacunarity, gain, periodX, periodY, (float)octaves);
}

/* One texel of a noise field at texcoords (u, v): frequencyX x frequencyY base cells across the
   field (whole numbers along an axis that wraps), optionally domain-warped (Quilez): the position
   moves by `warp` cells times a second fractal pair, which keeps the result periodic where it
   was. wrapU / wrapV: the field tiles along u / v (hfx::EdgeMode; Perlin's lattice repeats every
   256 cells anyway, which is what an axis that does not wrap gets). */
HFX_FN float hfx_noise_texel(int kind, int fractal, float u, float v, float frequencyX,
                             float frequencyY, int wrapU, int wrapV, float t, int octaves,
                             float lacunarity, float gain, float warp) {
    float x = u * frequencyX, y = v * frequencyY;
    float periodX = wrapU ? frequencyX : 0.0f;
    float periodY = wrapV ? frequencyY : (wrapU ? 256.0f : 0.0f);
    if (warp > 0.0f) {
        float qx = hfx_fractal(kind, HFX_FRACTAL_FBM, x + 5.0f, y + 1.0f, t, octaves, lacunarity,
                               gain, periodX, periodY);
        float qy = hfx_fractal(kind, HFX_FRACTAL_FBM, x + 1.0f, y + 9.0f, t, octaves, lacunarity,
                               gain, periodX, periodY);
        x += warp * (2.0f * qx - 1.0f);
        y += warp * (2.0f * qy - 1.0f);
    }
    return hfx_fractal(kind, fractal, x, y, t, octaves, lacunarity, gain, periodX, periodY);
}
#endif
