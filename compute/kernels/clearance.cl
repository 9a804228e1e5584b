/* Clearance map for one directional light: per bilinear cell, the climb past which a light ray
   from any point of the cell, in any direction within `slack` of `g`, stays above the cone edge
   of its penumbra, so the exact shadow walk can stop there (shaders/trace/hier.glsl).

   A light ray from a point p of cell (i, j) at height h0 moves g texels per unit of height it
   climbs (texel coordinates: cell i between the samples i and i + 1). After climbing d its cone
   edge stands at h0 + d (1 - penumbra) >= lo + d (1 - penumbra), lo the cell's lowest corner.
   The climb is cut into steps of one texel along g's major axis; a step [d0, d1] sweeps a box of
   cells (the cell moved by g d0 .. g d1, widened by slack d1 and a rounding margin), whose highest
   corner (pyramid level 0) is compared with the edge at d0. The clearance is the end of the last
   step whose box reaches it (0: none), found walking back from the far end in runs of steps.
   The first step is special: there the walk only asks for hard shadow (the surface above the ray
   itself; shaders/trace/hier.glsl counts the penumbra from a texel away), and the ray starts on
   the surface, so it is clear when the surface rises slower than the ray along g over the step's
   box: the bilinear patch's derivative along g (plus slack
   times its gradient's magnitude), at its largest on a corner, below 1. Steps end where the edge
   passes the field's maximum. Cells past the field wrap (power-of-two sizes) or clamp, as the
   field's edges do. `cells` is the whole pyramid (level 0 first, level k at levelOffsets[k]);
   its last level's single texel holds the field's maximum. */

int hfx_clear_index(int i, int n, int wrap) { return wrap ? (i & (n - 1)) : clamp(i, 0, n - 1); }

/* floor(i / 2^p), negative i included. */
int hfx_clear_shift(int i, int p) { return i >= 0 ? i >> p : ~((~i) >> p); }

/* The highest corner over level-0 cells [x0, x1] x [y0, y1]: read at level 0, or at the coarsest
   level p whose texels cover the box with at most three per axis (a superset: never lower). */
float hfx_box_top(__global const float2* cells, __global const int* levelOffsets, int levels, int width, int rows,
                  int x0, int x1, int y0, int y1, int fine) {
    int p = 0;
    if (!fine) {
        const int extent = max(x1 - x0, y1 - y0) + 1;
        while (p < levels - 1 && (2 << p) < extent) ++p;
    }
    if (p == levels - 1) return cells[levelOffsets[p]].x; /* the whole field */
    const int w = max(width >> p, 1), h = max(rows >> p, 1);
    __global const float2* level = cells + levelOffsets[p];
    const int u0 = hfx_clear_shift(x0, p), u1 = hfx_clear_shift(x1, p);
    const int v0 = hfx_clear_shift(y0, p), v1 = hfx_clear_shift(y1, p);
    float top = -1e30f;
    for (int v = v0; v <= v1; ++v) {
        const int row = hfx_clear_index(v, h, HFX_WRAP_V) * w;
        for (int u = u0; u <= u1; ++u) top = fmax(top, level[row + hfx_clear_index(u, w, HFX_WRAP_U)].x);
    }
    return top;
}

__kernel void clearance_map(__global const float* height, __global const float2* cells, __global float* clearance,
                            int width, int rows, float2 g, float penumbra, float slack, __global const int* levelOffsets,
                            int levels) {
    const int i = get_global_id(0), j = get_global_id(1);
    if (i >= width || j >= rows) return;
    const float margin = 1e-5f;  /* heights: the shader's rounding of the cone edge */
    const float reach = 1e-3f;   /* texels: the boxes' rounding */
    const float lo = cells[j * width + i].y, fieldMax = cells[levelOffsets[levels - 1]].x;
    const float major = fmax(fmax(fabs(g.x), fabs(g.y)), 1e-3f);
    const float step = 1.0f / major; /* climb per texel along the major axis */
    float clear = 0.0f;

    /* The steps after the first, up to where the cone edge passes the field's maximum or the ray
       the relief's top (h = 1: a ray from h0 >= lo climbs 1 - lo at most), from the far end
       back: the first that reaches the edge is the last along the ray. Runs of 2^L steps are
       tested at once (their box's top, read from a coarse level, against the edge at their
       start: if that passes, every step in them does), doubled after each that passes and
       halved where one does not, the far half first; a single step is tested as it is. So the
       result is the single steps' sweep's, in about log2 of its tests. */
    const float end = fmin((fieldMax - lo) / (1.0f - penumbra), 1.0f - lo);
    int last = end > step ? (int)ceil(end / step) - 1 : 0;
    while (last >= 1 && !(last * step < end)) --last;
    while ((last + 1) * step < end) ++last;
    /* Steps [1, kEnd) are left; the next run has 2^run steps: one first (a blocker near the far
       end is found at once), twice as many after each run that passes. */
    int kEnd = last + 1, run = 0;
    for (int guard = 0; kEnd > 1 && guard < 4096; ++guard) {
        while ((1 << run) > kEnd - 1) --run;
        const int k0 = kEnd - (1 << run);
        const float d0 = k0 * step;
        /* A single step ends at d0 + step; a run at its last step's end, widened by a second
           reach for that end's rounding. */
        const float d1 = run == 0 ? d0 + step : kEnd * step;
        const float r = run == 0 ? reach : 2.0f * reach;
        const float2 a = fmin(g * d0, g * d1) - slack * d1 - r;
        const float2 b = fmax(g * d0, g * d1) + slack * d1 + r;
        const int x0 = (int)floor(i + a.x), x1 = (int)floor(i + 1 + b.x);
        const int y0 = (int)floor(j + a.y), y1 = (int)floor(j + 1 + b.y);
        const float top = hfx_box_top(cells, levelOffsets, levels, width, rows, x0, x1, y0, y1, run == 0);
        if (top > lo + d0 * (1.0f - penumbra) - margin) {
            if (run == 0) {
                clear = d1;
                break;
            }
            --run;
        } else {
            kEnd = k0;
            ++run;
        }
    }

    /* The first step, where no later one reaches the edge: the patches' slope along g. */
    if (clear == 0.0f) {
        const float2 a = fmin((float2)(0.0f), g * step) - slack * step - reach;
        const float2 b = fmax((float2)(0.0f), g * step) + slack * step + reach;
        const int x0 = (int)floor(i + a.x), x1 = (int)floor(i + 1 + b.x);
        const int y0 = (int)floor(j + a.y), y1 = (int)floor(j + 1 + b.y);
        float rise = -1.0f;
        for (int y = y0; y <= y1; ++y) {
            const int yy = hfx_clear_index(y, rows, HFX_WRAP_V), yy1 = hfx_clear_index(y + 1, rows, HFX_WRAP_V);
            for (int x = x0; x <= x1; ++x) {
                const int xx = hfx_clear_index(x, width, HFX_WRAP_U), xx1 = hfx_clear_index(x + 1, width, HFX_WRAP_U);
                const float h00 = height[yy * width + xx], h10 = height[yy * width + xx1];
                const float h01 = height[yy1 * width + xx], h11 = height[yy1 * width + xx1];
                /* The patch's gradient at its corners: (h10 - h00, h01 - h00) at (0, 0) and so on. */
                const float4 dx = (float4)(h10 - h00, h11 - h01, h10 - h00, h11 - h01);
                const float4 dy = (float4)(h01 - h00, h01 - h00, h11 - h10, h11 - h10);
                const float4 along = dx * g.x + dy * g.y + slack * (fabs(dx) + fabs(dy));
                rise = fmax(rise, fmax(fmax(along.x, along.y), fmax(along.z, along.w)));
            }
        }
        if (rise > 1.0f - 1e-4f) clear = step;
    }
    /* A relative margin for the shader's t = climb / (1 - h0) rounding. */
    clearance[j * width + i] = clear > 0.0f ? clear * (1.0f + 1e-5f) + 1e-6f : 0.0f;
}
