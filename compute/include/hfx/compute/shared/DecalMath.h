#ifndef HFX_DECAL_MATH_H
#define HFX_DECAL_MATH_H
#include "ClPrelude.h"

/* Height change of one crater at distance r from its centre, in units of its radius (r = 1 at
   the lip): a parabolic bowl -depth (1 - r^2) inside, plus a raised rim of rimHeight around
   r = 1, of half-width rimWidth (in radii), shaped (1 - s^2)^2 so it ends smoothly. Zero for
   r >= 1 + rimWidth: a stamp touches only its footprint. */
HFX_FN float hfx_crater_profile(float r, float depth, float rimHeight, float rimWidth) {
    float change = 0.0f;
    if (r < 1.0f) change -= depth * (1.0f - r * r);
    float s = (r - 1.0f) / rimWidth;
    if (s > -1.0f && s < 1.0f) {
        float q = 1.0f - s * s;
        change += rimHeight * q * q;
    }
    return change;
}

/* Applies one stamp's change to the damage d of a texel whose base height is `base`, keeping
   base + d in [0, 1]: damage accumulates, but never leaves the height range. */
HFX_FN float hfx_apply_damage(float d, float change, float base) {
    float next = d + change;
    float lo = -base, hi = 1.0f - base;
    return next < lo ? lo : (next > hi ? hi : next);
}

/* 0 below e0, 1 above e1, a smooth cubic between (GLSL's smoothstep). */
HFX_FN float hfx_decal_smoothstep(float e0, float e1, float x) {
    float t = (x - e0) / (e1 - e0);
    t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
    return t * t * (3.0f - 2.0f * t);
}

/* The scorch's outline at an impact of phase p: the angle's harmonics 3, 5, 7, 11, 13 and 17 turned
   by p, 2.3p, 3.3p, 1.3p, -p and -2.3p, as (cos 3p', sin 3p'...) need no trigonometry per texel:
   wobble[] = (cos p, sin p, cos 2.3p, sin 2.3p), computed once per stamp (hfx_decal_wobble); the
   phases 3.3p and 1.3p are their sum and difference, -p and -2.3p their conjugates. */
HFX_FN void hfx_decal_wobble(float phase, float* wobble) {
    wobble[0] = HFX_COS(phase);
    wobble[1] = HFX_SIN(phase);
    wobble[2] = HFX_COS(2.3f * phase);
    wobble[3] = HFX_SIN(2.3f * phase);
}

/* The shading marks of one impact at a texel (dx, dy) from its centre, in radii (r = 1 at the
   lip). Scorch: full at the lip and fading from there, (1 - t^2)^2 with t from 0 at the lip to 1
   at the outline (from half the outline where that lies within 2 radii), so the soot is darkest
   at the crater and has no flat plate and no hard rim. The outline lies at the reach (in radii)
   times 1 + 0.07 sin(3a + p) + 0.07 sin(5a + 2.3p) + 0.07 sin(7a + 3.3p) + 0.06 sin(11a + 1.3p)
   + 0.06 sin(13a - p) + 0.05 sin(17a - 2.3p) at the angle a (p the impact's phase; the multiple
   angles from powers of (cos a + i sin a)): a blast's ragged rays, and no two burns share an
   outline. The orders are primes and none holds over a fifth of the variance, so a burn too small
   for the fine orders to show is no star (one order 5 at 0.18 read as a five-pointed one).
   Roughness: the fresh fracture of the bowl and the lip, fading out by 1.5 radii. Occlusion:
   the bowl's shadowed floor, 1 - strength (1 - r^2) inside the lip. Each is scaled by its
   strength (the heal curves' values). */
HFX_FN void hfx_decal_marks(float dx, float dy, float scorchStrength, float roughStrength, float occlusionStrength,
                            float reach, float c1, float s1, float c2, float s2, float* scorch, float* rough,
                            float* occlusion) {
    float r = HFX_SQRT(dx * dx + dy * dy);
    *scorch = 0.0f;
    if (scorchStrength > 0.0f && r < 1.4f * reach) {
        float inv = r > 0.0f ? 1.0f / r : 0.0f;
        float c = r > 0.0f ? dx * inv : 1.0f, s = dy * inv;
        /* (c + i s)^2, ^3, ^4, ^5, ^7, ^11, ^13, ^17 */
        float c2a = c * c - s * s, s2a = 2.0f * c * s;
        float c3a = c2a * c - s2a * s, s3a = s2a * c + c2a * s;
        float c4a = c2a * c2a - s2a * s2a, s4a = 2.0f * c2a * s2a;
        float c5a = c3a * c2a - s3a * s2a, s5a = s3a * c2a + c3a * s2a;
        float c7a = c5a * c2a - s5a * s2a, s7a = s5a * c2a + c5a * s2a;
        float c11a = c7a * c4a - s7a * s4a, s11a = s7a * c4a + c7a * s4a;
        float c13a = c11a * c2a - s11a * s2a, s13a = s11a * c2a + c11a * s2a;
        float c17a = c13a * c4a - s13a * s4a, s17a = s13a * c4a + c13a * s4a;
        /* The phases 3.3p = p + 2.3p and 1.3p = 2.3p - p */
        float cSum = c1 * c2 - s1 * s2, sSum = s1 * c2 + c1 * s2, cDiff = c2 * c1 + s2 * s1, sDiff = s2 * c1 - c2 * s1;
        float edge = reach * (1.0f + 0.07f * (s3a * c1 + c3a * s1) + 0.07f * (s5a * c2 + c5a * s2) +
                              0.07f * (s7a * cSum + c7a * sSum) + 0.06f * (s11a * cDiff + c11a * sDiff) +
                              0.06f * (s13a * c1 - c13a * s1) + 0.05f * (s17a * c2 - c17a * s2));
        float inner = edge < 2.0f ? 0.5f * edge : 1.0f;
        float t = (r - inner) / (edge - inner);
        t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
        float q = 1.0f - t * t;
        *scorch = scorchStrength * q * q;
    }
    *rough = roughStrength * (1.0f - hfx_decal_smoothstep(1.0f, 1.5f, r));
    *occlusion = r < 1.0f ? 1.0f - occlusionStrength * (1.0f - r * r) : 1.0f;
}

/* A 32-bit integer hash of a lattice point (an avalanche of multiplies and shifts: every bit of
   the point moves about half the bits out). */
HFX_FN unsigned int hfx_decal_hash(int x, int y) {
    unsigned int h = (unsigned int)x * 0x8da6b343u ^ (unsigned int)y * 0xd8163841u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    h ^= h >> 15;
    return h;
}

/* Cooling embers crack into plates: a Voronoi diagram of one jittered point per lattice cell
   (inside the middle 0.8 of the cell; the two nearest are looked for in the 3x3 cells around the
   point), at (x, y) in cells. Its distance to the bisector of its two nearest points (the plates' edge
   there, in cells) against `width`: 1 on a crack's middle, falling smoothly to 0 a width out. */
HFX_FN float hfx_decal_cracks(float x, float y, float width) {
    float fx = HFX_FLOOR(x), fy = HFX_FLOOR(y);
    int ix = (int)fx, iy = (int)fy;
    fx = x - fx;
    fy = y - fy;
    float d1 = 1e9f, d2 = 1e9f, p1x = 0.0f, p1y = 0.0f, p2x = 0.0f, p2y = 0.0f;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            unsigned int h = hfx_decal_hash(ix + i, iy + j);
            float px = (float)i + 0.1f + 0.8f * (float)(h & 0xffffu) * (1.0f / 65535.0f);
            float py = (float)j + 0.1f + 0.8f * (float)(h >> 16) * (1.0f / 65535.0f);
            float ex = px - fx, ey = py - fy, d = ex * ex + ey * ey;
            if (d < d1) {
                d2 = d1;
                p2x = p1x;
                p2y = p1y;
                d1 = d;
                p1x = px;
                p1y = py;
            } else if (d < d2) {
                d2 = d;
                p2x = px;
                p2y = py;
            }
        }
    float sx = p2x - p1x, sy = p2y - p1y;
    float edge = (d2 - d1) / (2.0f * HFX_SQRT(sx * sx + sy * sy));
    return 1.0f - hfx_decal_smoothstep(0.0f, width, edge);
}

/* A fresh crater's heat (0 to `strength`) at (dx, dy) radii from its centre, before its cracks:
   its bowl glows like embers, most at the floor, strength (1 - r^2)^2, none from the lip out
   (inside every stamp's reach). */
HFX_FN float hfx_decal_heat(float dx, float dy, float strength) {
    float r2 = dx * dx + dy * dy;
    if (r2 >= 1.0f) return 0.0f;
    float inside = 1.0f - r2;
    return strength * inside * inside;
}

/* The share of hfx_decal_heat a crater's floor shows at (dx, dy) radii from its centre: a crust
   cracked into plates (hfx_decal_cracks: 0.4 radii across, or 4 texels where the crater is
   small, `texel` being a texel in radii; cracks 0.06 radii or 0.75 texels wide; the lattice
   turned and moved by the impact's phase through wobble (cos p, sin p)). The cracks show all of
   the heat, the plates 0.6 strength of it, so as a crater cools its plates darken first and the
   cracks glow last. */
HFX_FN float hfx_decal_crust(float dx, float dy, float strength, float texel, float cosPhase, float sinPhase) {
    float cell = HFX_MAX(0.4f, 4.0f * texel), width = HFX_MAX(0.06f, 0.75f * texel) / cell;
    float x = (cosPhase * dx - sinPhase * dy) / cell + 17.0f * cosPhase;
    float y = (sinPhase * dx + cosPhase * dy) / cell + 17.0f * sinPhase;
    float crust = 0.6f * HFX_MIN(strength, 1.0f);
    return crust + (1.0f - crust) * hfx_decal_cracks(x, y, width);
}

/* How far (radii) a stamp's marks reach: its crater's lip and rim, its roughness, its scorch
   (the outline's wobble adds at most 40%). */
HFX_FN float hfx_decal_reach(float rimWidth, float scorchStrength, float roughStrength, float scorchReach) {
    float reach = 1.0f + rimWidth;
    if (roughStrength > 0.0f && reach < 1.5f) reach = 1.5f;
    if (scorchStrength > 0.0f && reach < 1.4f * scorchReach) reach = 1.4f * scorchReach;
    return reach;
}
#endif
