#include "ColorMath.h"

/* Colours a float field through a ramp into 8-bit RGBA, the layout of an albedo texture. */
__kernel void colorize(__global const float* field, __global uchar4* out, __global const float* stops,
                       int count, int n) {
    int k = get_global_id(0);
    if (k >= n) return;
    unsigned char rgba[4];
    hfx_ramp_rgba8(field[k], stops, count, rgba);
    out[k] = (uchar4)(rgba[0], rgba[1], rgba[2], rgba[3]);
}
