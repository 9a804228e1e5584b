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
#endif
