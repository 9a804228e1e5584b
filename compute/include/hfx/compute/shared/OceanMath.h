#ifndef HFX_OCEAN_MATH_H
#define HFX_OCEAN_MATH_H
#include "ClPrelude.h"

/* Tessendorf's statistical ocean. The spectrum is stored at FFT index (x, y) for the wave
   vector k = 2 pi (n, m) / L with n = x for x < N/2 and x - N otherwise (likewise m), so the
   inverse DFT of the array is the height at the grid points, with no sign flips.

   h(k, t) = h0(k) e^{-i w t} + conj(h0(-k)) e^{i w t}: Hermitian in k, so the height is real,
   and the mode h0(k) e^{i (k.x - w t)} travels along +k (downwind for a wind spectrum).
   Writes the real and imaginary parts of h(k, t) given h0(k), h0(-k) and phase = -w t. */
HFX_FN void hfx_ocean_mode(float h0re, float h0im, float h0mre, float h0mim, float phase,
                           float* re, float* im) {
    float c = HFX_COS(phase), s = HFX_SIN(phase);
    /* h0 (c + i s) + conj(h0m) (c - i s), with phase = -w t */
    *re = (h0re * c - h0im * s) + (h0mre * c - h0mim * s);
    *im = (h0re * s + h0im * c) - (h0mre * s + h0mim * c);
}
#endif
