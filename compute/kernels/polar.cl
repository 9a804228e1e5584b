/* The polar filter (PolarFilter.h): each row of a longitude-latitude field averaged over a box
   of widths[y] texels centred on each texel, wrapping round the row. Texel i covers [i, i + 1);
   the box's average is that of the piecewise-constant row, from its prefix sums. */

/* One work-item a row: prefix[y * (width + 1) + i] = the sum of field[j] - 0.5 for j < i (the
   heights' middle taken out, so the sums stay small and keep their precision). Rows whose box is
   at most a texel wide are copied by polar_filter and need none. */
__kernel void polar_sums(__global const float* field, __global float* prefix, __global const float* widths,
                         int width, int height) {
    int y = get_global_id(0);
    if (y >= height || widths[y] <= 1.0f) return;
    __global const float* row = field + (size_t)y * width;
    __global float* p = prefix + (size_t)y * (width + 1);
    float sum = 0.0f;
    p[0] = 0.0f;
    for (int i = 0; i < width; ++i) {
        sum += row[i] - 0.5f;
        p[i + 1] = sum;
    }
}

/* The row's integral of (field - 0.5) from 0 to t, any t (whole turns of the row added). */
float polar_integral(__global const float* p, __global const float* row, int width, float t) {
    float turns = floor(t / (float)width);
    float within = t - turns * (float)width;
    int i = min((int)within, width - 1);
    return turns * p[width] + p[i] + (within - (float)i) * (row[i] - 0.5f);
}

__kernel void polar_filter(__global const float* field, __global const float* prefix, __global const float* widths,
                           __global float* out, int width, int height) {
    int x = get_global_id(0), y = get_global_id(1);
    if (x >= width || y >= height) return;
    size_t k = (size_t)y * width + x;
    float w = widths[y];
    if (w <= 1.0f) { /* the box lies inside the texel */
        out[k] = field[k];
        return;
    }
    __global const float* row = field + (size_t)y * width;
    __global const float* p = prefix + (size_t)y * (width + 1);
    float centre = (float)x + 0.5f;
    float sum = polar_integral(p, row, width, centre + 0.5f * w) - polar_integral(p, row, width, centre - 0.5f * w);
    out[k] = 0.5f + sum / w;
}
