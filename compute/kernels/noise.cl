#include "NoiseMath.h"

/* A noise height field, row y at v = (y + 0.5) / rows. KIND and FRACTAL are -D options
   (HFX_NOISE_*, HFX_FRACTAL_*), and so are the edges (HFX_WRAP_U, HFX_WRAP_V from
   hfx::edgeOptions): each variant compiles to straight code. */
__kernel void noise(__global float* height, int columns, int rows, float frequencyX,
                    float frequencyY, float t, int octaves, float lacunarity, float gain,
                    float warp) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= columns || y >= rows) return;
    float u = (x + 0.5f) / columns, v = (y + 0.5f) / rows;
    height[y * columns + x] = hfx_noise_texel(KIND, FRACTAL, u, v, frequencyX, frequencyY, HFX_WRAP_U,
                                              HFX_WRAP_V, t, octaves, lacunarity, gain, warp);
}
