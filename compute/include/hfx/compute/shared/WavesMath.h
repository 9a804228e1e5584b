#ifndef HFX_WAVES_MATH_H
#define HFX_WAVES_MATH_H
#include "ClPrelude.h"

/* One directional wave of a tileable patch. (u, v) in [0,1) is the position on the patch;
   (m, n) whole cycles across it, so the sum tiles exactly; phase already holds -omega*t.
   The crest shape 2*((1+sin)/2)^sharpness - 1 stays in [-1,1]; sharpness 1 is a plain sine,
   above 1 gives the narrow crests and wide troughs of wind waves (GPU Gems 1, ch. 1). */
HFX_FN float hfx_wave_term(float u, float v, float m, float n, float phase, float sharpness) {
    float cycles = m * u + n * v;
    cycles -= HFX_FLOOR(cycles); /* keeps the sine's argument small and exact in float */
    float s = 0.5f * (1.0f + HFX_SIN(HFX_TWO_PI * cycles + phase));
    return 2.0f * HFX_POW(s, sharpness) - 1.0f;
}

/* Maps the amplitude-weighted sum of terms into the stored convention h in [0,1]. */
HFX_FN float hfx_wave_height(float weightedSum, float inverseTotalAmplitude) {
    return 0.5f + 0.5f * weightedSum * inverseTotalAmplitude;
}
#endif
