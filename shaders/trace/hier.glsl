// Hierarchical tracer: the exact first hit of the ray with the bilinear surface, walking the
// maximum-height pyramid (hfx_bound). The walk starts at the entry's level-0 cell (a ray that
// meets the relief at once costs two fetches, as POM's does); a cell whose bound the ray passes
// above is skipped whole, and where its exit is also its parent's edge the walk climbs a level;
// a cell the ray dips into is opened a level down. A level-0 cell the ray dips into is solved:
// the bilinear patch between four samples (hfx_gather) in closed form (the height along the ray
// is quadratic in t); if the ray passes the patch the walk goes on. Cell space:
// x = u * width - 0.5, so cell i spans the samples i and i + 1. Soft self-shadows.
//
// Why it cannot step over a surface (tests/TracerContractTest.cpp, a million rays):
// - a point on a cell boundary belongs to the cell ahead (floor going +, ceil - 1 going -), and
//   an axis the ray has just crossed keeps the boundary's exact (integer) coordinate, so a skip
//   always lands in the next cell, however far the coordinates run from the origin;
// - the ray only descends, so a cell it has dipped into stays open: the walk never climbs back
//   into a parent it has opened, and climbs no higher than the level whose cells are as wide as
//   the ray's footprint;
// - every step skips a cell (past at least one texel boundary), opens one (at most one per
//   climb) or solves one, so the walk needs at most about three steps per texel boundary the
//   ray crosses: the loop's bound is computed from the ray, not a fixed count that long grazing
//   rays run out of (the old walk's 512 steps left 0.04% of the pixels of a 512x512 brick map at
//   80 degrees up to 73 texels short).
//
// On a CPU rasteriser (llvmpipe) a divergent branch costs both sides, so the walk's steps fetch
// one bound and nothing else, and the patch solve sits outside the walk's loop.

const int HFX_MAX_TRACE_STEPS = 1 << 18; // only against a NaN ray; the real bound is per ray

// Past the current cell: onto its exit, the crossed axes snapped to the boundary. A level up
// only where the boundary is also the parent's: the ray only descends, so a parent it has dipped
// into is never skipped later, and testing it again is waste.
void hfx_pass_cell(vec2 p0, vec2 dir, vec2 bound, vec2 tCross, float tExit, int topLevel, inout vec2 p, inout float t,
                   inout int level, inout float cellSize, inout float invCellSize) {
    const bvec2 crossed = lessThanEqual(tCross, vec2(tExit));
    p = mix(p0 + dir * tExit, bound, crossed);
    t = tExit;
    const vec2 parentEdge = mix(vec2(1.0), fract(bound * (0.5 * invCellSize)), crossed);
    if (min(parentEdge.x, parentEdge.y) == 0.0 && level < topLevel) {
        ++level;
        cellSize *= 2.0;
        invCellSize *= 0.5;
    }
}

float hfx_trace_depth(vec2 uv0, vec2 parallax) {
    const ivec2 size = hfx_size();
    const vec2 p0 = uv0 * vec2(size) - 0.5;
    const vec2 dir = -parallax * vec2(size);
    const bvec2 back = lessThan(dir, vec2(0.0));
    const vec2 ahead = vec2(not(back));
    const vec2 invDir = vec2(dir.x != 0.0 ? 1.0 / dir.x : 1e30, dir.y != 0.0 ? 1.0 / dir.y : 1e30);
    const vec2 span = abs(dir);
    const int topLevel = clamp(int(ceil(log2(max(max(span.x, span.y), 1.0)))), 0, hfx_levels() - 1);
    const int maxSteps = int(min(4.0 * (span.x + span.y) + float(4 * topLevel + 24), float(HFX_MAX_TRACE_STEPS)));
    int level = 0;
    float cellSize = 1.0, invCellSize = 1.0; // 2^level and its inverse
    float t = 0.0;
    vec2 p = p0; // the ray's point at t; a just-crossed axis holds the boundary exactly
    int steps = 0;
    for (int candidate = 0; candidate < maxSteps; ++candidate) {
        // The walk: one bound per step, until a level-0 cell the ray dips into (or the end).
        vec2 cell, bound, tCross;
        float tExit;
        bool found = false;
        for (; steps < maxSteps; ++steps) {
            if (t >= 1.0) return 1.0;
            const vec2 q = p * invCellSize;
            cell = mix(floor(q), ceil(q) - 1.0, back); // on a boundary: the cell ahead
            bound = (cell + ahead) * cellSize;
            tCross = (bound - p0) * invDir; // an axis the ray does not move along: far ahead
            tExit = clamp(min(tCross.x, tCross.y), t, 1.0);
            const float tDown = 1.0 - hfx_bound(ivec2(cell), level); // where the ray comes down to the bound
            if (tDown < tExit) {
                const float tIn = max(t, tDown);
                if (tIn > t) p = p0 + dir * tIn;
                t = tIn;
                if (level == 0) { found = true; break; }
                --level;
                cellSize *= 0.5;
                invCellSize *= 2.0;
            } else {
                hfx_pass_cell(p0, dir, bound, tCross, tExit, topLevel, p, t, level, cellSize, invCellSize);
            }
        }
        if (!found) return t;
        // Level 0: the four samples of the cell in one gather (x: (i, j+1), y: (i+1, j+1),
        // z: (i+1, j), w: (i, j)), at the point all four texels share.
        const vec4 s = hfx_gather((cell + 1.0) / vec2(size));
        const float a = s.w, b = s.z - s.w, c = s.x - s.w, e = s.y - s.x - s.z + s.w;
        const vec2 local = p - cell;
        const float A = e * dir.x * dir.y;
        const float B = b * dir.x + c * dir.y + e * (local.x * dir.y + local.y * dir.x) + 1.0;
        const float C = a + b * local.x + c * local.y + e * local.x * local.y - (1.0 - t);
        if (C >= 0.0) return t;
        float root = 1e30;
        if (abs(A) < 1e-9) {
            if (B > 0.0) root = -C / B;
        } else {
            const float disc = B * B - 4.0 * A * C;
            if (disc >= 0.0) {
                const float qq = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
                const float r1 = qq / A, r2 = qq != 0.0 ? C / qq : 1e30;
                root = min(r1 >= 0.0 ? r1 : 1e30, r2 >= 0.0 ? r2 : 1e30);
            }
        }
        if (root <= tExit - t) return t + root;
        // The ray passes over the patch: on past the cell, as a skip.
        hfx_pass_cell(p0, dir, bound, tCross, tExit, topLevel, p, t, level, cellSize, invCellSize);
        ++steps;
    }
    return t;
}

HfxHit hfx_trace(HfxRay ray) { return hfx_hit_at(ray, hfx_trace_depth(ray.uv, ray.parallax)); }
float hfx_shadow(HfxShadowRay ray) { return clamp(hfx_occlusion(ray) * ray.sharpness, 0.0, 1.0); }
