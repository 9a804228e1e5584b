#ifndef HFX_COLOR_MATH_H
#define HFX_COLOR_MATH_H
#include "ClPrelude.h"

/* A colour ramp: `count` stops of (position, r, g, b) with rising positions in [0,1]; a value
   below the first stop takes its colour, above the last the last's, between two the linear mix.
   Writes 8-bit RGBA (alpha 255), rounded to nearest: what the albedo texture stores. */
HFX_FN void hfx_ramp_rgba8(float value, HFX_GLOBAL const float* stops, int count, unsigned char* out) {
    float r = stops[1], g = stops[2], b = stops[3];
    if (!(value > stops[0])) {
        /* NaN lands here too: the first colour, never garbage. */
    } else if (value >= stops[4 * (count - 1)]) {
        r = stops[4 * (count - 1) + 1];
        g = stops[4 * (count - 1) + 2];
        b = stops[4 * (count - 1) + 3];
    } else {
        int i = 0;
        while (i + 2 < count && value >= stops[4 * (i + 1)]) ++i;
        const float a = stops[4 * i], z = stops[4 * (i + 1)];
        const float t = z > a ? (value - a) / (z - a) : 0.0f;
        r = stops[4 * i + 1] + t * (stops[4 * (i + 1) + 1] - stops[4 * i + 1]);
        g = stops[4 * i + 2] + t * (stops[4 * (i + 1) + 2] - stops[4 * i + 2]);
        b = stops[4 * i + 3] + t * (stops[4 * (i + 1) + 3] - stops[4 * i + 3]);
    }
    out[0] = (unsigned char)(HFX_MIN(HFX_MAX(r, 0.0f), 1.0f) * 255.0f + 0.5f);
    out[1] = (unsigned char)(HFX_MIN(HFX_MAX(g, 0.0f), 1.0f) * 255.0f + 0.5f);
    out[2] = (unsigned char)(HFX_MIN(HFX_MAX(b, 0.0f), 1.0f) * 255.0f + 0.5f);
    out[3] = 255;
}
#endif
