#ifndef HFX_WAVES_MATH_H
#define HFX_WAVES_MATH_H
#include "ClPrelude.h"

/* Directional waves on a tileable patch. A wave with (m, n) whole cycles across the patch has
   phase angle theta = 2 pi (m u + n v) + phase at (u, v) in [0,1); phase already holds -omega*t.
   theta splits into a part of u and a part of v, so sin(theta) = sin a cos b + cos a sin b
   with a and b tabulated per column and per row: the per-texel cost is a few multiplies. */

/* 2 pi * frac(cycles * position) + phase: small arguments, exact in float over long runs. */
HFX_FN float hfx_wave_angle(float cycles, float position, float phase) {
    float turns = cycles * position;
    turns -= HFX_FLOOR(turns);
    return HFX_TWO_PI * turns + phase;
}

/* Crest shape of a wind wave from s = sin(theta): s + 2 q (s^2 - 1) adds the second harmonic of
   a Stokes wave (q = steepness in [0, 1/4]): crests narrow and peaked, troughs wide and flat.
   Monotonic in s for q <= 1/4, so the result stays in [-1, 1] with -1 and 1 reached. */
HFX_FN float hfx_wave_shape(float s, float steepness) {
    return s + 2.0f * steepness * (s * s - 1.0f);
}

/* Maps the amplitude-weighted sum of shapes into the stored convention h in [0,1]. */
HFX_FN float hfx_wave_height(float weightedSum, float inverseTotalAmplitude) {
    return 0.5f + 0.5f * weightedSum * inverseTotalAmplitude;
}
#endif
