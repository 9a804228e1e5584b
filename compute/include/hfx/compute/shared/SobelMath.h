#ifndef HFX_SOBEL_MATH_H
#define HFX_SOBEL_MATH_H
#include "ClPrelude.h"

/* 3x3 Sobel divided by its first moment (8), so the result is the slope in height per texel.
   Names are the neighbours: row "n" is y-1, row "s" is y+1 (v grows with y). */
HFX_FN float hfx_sobel_dx(float nw, float ne, float w, float e, float sw, float se) {
    return ((ne + 2.0f * e + se) - (nw + 2.0f * w + sw)) * 0.125f;
}
HFX_FN float hfx_sobel_dy(float nw, float n, float ne, float sw, float s, float se) {
    return ((sw + 2.0f * s + se) - (nw + 2.0f * n + ne)) * 0.125f;
}
/* Tangent-space normal of the surface z = depth * h(u, v), from slopes per texel; scaleX and
   scaleY are depth * width and depth * height (texels per texture unit). Writes x, y, z. */
HFX_FN void hfx_normal_from_slopes(float dx, float dy, float scaleX, float scaleY, float* out) {
    float nx = -dx * scaleX, ny = -dy * scaleY;
    float inv = 1.0f / HFX_SQRT(nx * nx + ny * ny + 1.0f);
    out[0] = nx * inv;
    out[1] = ny * inv;
    out[2] = inv;
}
#endif
