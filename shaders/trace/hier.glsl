// Hierarchical tracer: the exact first hit of the ray with the bilinear surface, walking the
// height-bounds pyramid (hfx_bounds: max and min per cell). The walk starts at the level-0 cell
// where the ray comes down to the field's maximum (the pyramid's top texel: above it the ray meets
// nothing; skipping that stretch by climbing levels cost hier 0-9% of its draw at 45-80 degrees,
// docs/BENCHMARKS.md), or later where the caller knows no hit comes sooner (HfxRay.start: the
// beam prepass's depth for the pixel's block, hfx_beam_depth below), so a ray that meets the
// relief at once costs three fetches. A cell whose
// maximum the ray passes above is skipped whole, and where its exit is also its parent's edge
// the walk climbs a level; a cell the ray dips into is opened a level down. A level-0 cell
// the ray dips into is solved: the bilinear patch between four samples (hfx_cell_samples) in closed
// form (the height along the ray is quadratic in t); if the ray passes the patch the walk goes
// on. Cell space: x = u * width - 0.5, so cell i spans the samples i and i + 1. Exact
// self-shadows with a blocker-distance penumbra (hfx_shadow, below).
//
// A cell of any level the ray dips into and leaves below the cell's minimum surely holds the hit,
// between where the ray comes down to its maximum and where it passes its minimum. Where that
// span is no longer than ray.tolerance (the pixel budget; 0 on flat tops, whose hit is then
// exact) the walk returns its start: never below the surface, at most the tolerance above the
// hit, and no descent to level 0.
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
// one bound and nothing else, and the patch solve sits outside the walk's loop. There, too, every
// variable a step writes lives in memory and is blended under the lanes' mask: a step's state is
// p, t and the level (hfx_step; 2^level from the exponent bits), and what the solve needs is found
// again after the loop (the level-0 cell, the patch's maximum from the gathered samples). Against
// a loop that carried the cell sizes, the exit and the cell: 0-11% off hier's draw at 45-80
// degrees with the same fetches, most at 70-80 (docs/BENCHMARKS.md, fifteenth part). The bound
// is an imageLoad from one image holding every level (surface/heights.glsl): a texelFetch with
// a level per lane is a call there, which spilled every vector live across it, and cost 10-30%
// of the draw at 45-80 degrees (seventeenth part).

const int HFX_MAX_TRACE_STEPS = 1 << 18; // only against a NaN ray; the real bound is per ray
// The view walk climbs past a cell only where the ray leaves it at least this many cells' widths
// (along the ray's major axis, at the ray's descent) above the cell's maximum: nearer, the
// parent (no lower) is likely opened again at once, two fetches for nothing. Starting at the beam
// prepass's depth the rays are near the relief: 1-9% fewer view fetches than climbing wherever
// the boundary allows (1: 1-8%; 4 and 8: no better; never climbing: up to twice as many at 80
// degrees; docs/BENCHMARKS.md, fifteenth part). The light walk, rising away from the relief,
// climbs wherever it may (the same rule there changed its fetches by -1% to +4%).
const float HFX_CLIMB_CLEARANCE = 2.0;

// 2^level and 2^-level, exact, from the float's exponent bits (level in [0, 126]).
float hfx_cell_size(int level) { return intBitsToFloat((level + 127) << 23); }
float hfx_inv_cell_size(int level) { return intBitsToFloat((127 - level) << 23); }

// The cell of the level that the ray is in at p, going on along dir: its corner ahead (bound),
// where the ray meets that corner's lines (tCross; an axis the ray does not move along: far
// ahead) and leaves the cell (tExit, within [t, 1]). On a boundary: the cell ahead.
void hfx_cell_at(vec2 p0, vec2 p, vec2 invDir, bvec2 back, float t, int level, out vec2 cell, out vec2 bound,
                 out vec2 tCross, out float tExit) {
    const vec2 q = p * hfx_inv_cell_size(level);
    cell = mix(floor(q), ceil(q) - 1.0, back);
    bound = (cell + vec2(not(back))) * hfx_cell_size(level);
    tCross = (bound - p0) * invDir;
    tExit = clamp(min(tCross.x, tCross.y), t, 1.0);
}

// One step of a walk from the cell hfx_cell_at found: where the ray dips into it, down to tIn
// (p moves only if the ray does: a just-crossed axis keeps its boundary) and a level down;
// otherwise past it, onto its exit with the crossed axes snapped to the boundary, and a level up
// where the caller lets it (mayClimb) and that boundary is also the parent's: the ray only
// descends, so a parent it has dipped into is never skipped later, and testing it again is
// waste. Climbing is never needed for exactness, only for long skips.
void hfx_step(vec2 p0, vec2 dir, bool dip, float tIn, vec2 bound, vec2 tCross, float tExit, int topLevel,
              bool mayClimb, inout vec2 p, inout float t, inout int level) {
    const bvec2 crossed = lessThanEqual(tCross, vec2(tExit));
    const vec2 q = p0 + dir * (dip ? tIn : tExit);
    const vec2 parentEdge = mix(vec2(1.0), fract(bound * (0.5 * hfx_inv_cell_size(level))), crossed);
    const bool climb = mayClimb && min(parentEdge.x, parentEdge.y) == 0.0 && level < topLevel;
    p = dip ? (tIn > t ? q : p) : mix(q, bound, crossed);
    t = dip ? tIn : tExit;
    level += dip ? -1 : (climb ? 1 : 0);
}

// The four samples of a level-0 cell (x: (i, j+1), y: (i+1, j+1), z: (i+1, j), w: (i, j)).
vec4 hfx_patch_samples(vec2 cell) { return hfx_cell_samples(ivec2(cell)); }

// The bilinear patch of those samples along the ray from p (in the cell): its height at
// p + dir * s is A s^2 + B s + C, returned as (A, B, C).
vec3 hfx_patch_along(vec4 s, vec2 cell, vec2 p, vec2 dir) {
    const float a = s.w, b = s.z - s.w, c = s.x - s.w, e = s.y - s.x - s.z + s.w;
    const vec2 local = p - cell;
    return vec3(e * dir.x * dir.y, b * dir.x + c * dir.y + e * (local.x * dir.y + local.y * dir.x),
                a + b * local.x + c * local.y + e * local.x * local.y);
}

// The walk's bounds for a ray moving by dir (in texels) over t in [0, 1]: the highest level it
// climbs to (cells as wide as its footprint) and its step bound (see the header).
int hfx_top_level(vec2 dir) {
    return clamp(int(ceil(log2(max(max(abs(dir.x), abs(dir.y)), 1.0)))), 0, hfx_levels() - 1);
}
int hfx_max_steps(vec2 dir, int topLevel) {
    return int(min(4.0 * (abs(dir.x) + abs(dir.y)) + float(4 * topLevel + 24), float(HFX_MAX_TRACE_STEPS)));
}
// The highest height anywhere on the field: the pyramid's top texel (one fetch).
float hfx_field_max() { return hfx_bounds(ivec2(0), hfx_levels() - 1).x; }
vec2 hfx_inverse(vec2 dir) { return vec2(dir.x != 0.0 ? 1.0 / dir.x : 1e30, dir.y != 0.0 ? 1.0 / dir.y : 1e30); }

float hfx_trace_depth(HfxRay ray) {
    const vec2 uv0 = ray.uv, parallax = ray.parallax;
    const ivec2 size = hfx_size();
    const vec2 p0 = uv0 * vec2(size) - 0.5;
    const vec2 dir = -parallax * vec2(size);
    const bvec2 back = lessThan(dir, vec2(0.0));
    const vec2 invDir = hfx_inverse(dir);
    const int topLevel = hfx_top_level(dir);
    const int maxSteps = hfx_max_steps(dir, topLevel);
    const float major = max(abs(dir.x), abs(dir.y)); // texels per unit of t on the ray's major axis
    int level = 0;
    float t = clamp(max(1.0 - hfx_field_max(), ray.start), 0.0, 1.0);
    vec2 p = p0 + dir * t; // the ray's point at t; a just-crossed axis holds the boundary exactly
    int steps = 0;
    for (int candidate = 0; candidate < maxSteps; ++candidate) {
        // The walk: one bound per step, until a level-0 cell the ray dips into (or the end).
        bool found = false;
        for (; steps < maxSteps && t < 1.0; ++steps) {
            vec2 cell, bound, tCross;
            float tExit;
            hfx_cell_at(p0, p, invDir, back, t, level, cell, bound, tCross, tExit);
            const vec2 bounds = hfx_bounds(ivec2(cell), level);
            const float tDown = 1.0 - bounds.x; // where the ray comes down to the cell's maximum
            const float tBelow = 1.0 - bounds.y; // ... and passes its minimum: the hit is in [tIn, tBelow]
            const bool dip = tDown < tExit;
            const float tIn = max(t, tDown);
            if (dip && tBelow < tExit && tBelow - tIn <= ray.tolerance) { t = tIn; break; }
            if (dip && level == 0) { found = true; break; }
            const bool mayClimb = (tDown - tExit) * major >= HFX_CLIMB_CLEARANCE * hfx_cell_size(level);
            hfx_step(p0, dir, dip, tIn, bound, tCross, tExit, topLevel, mayClimb, p, t, level);
        }
        if (!found) return t;
        // The level-0 cell again (the same p and t: the same cell), down to the patch's maximum
        // (the largest of its four samples: the ray is above the patch before it), then the
        // patch's height minus the ray's (1 - t, falling) along the cell: A s^2 + B s + C.
        vec2 cell, bound, tCross;
        float tExit;
        hfx_cell_at(p0, p, invDir, back, t, 0, cell, bound, tCross, tExit);
        const vec4 samples = hfx_patch_samples(cell);
        const float tIn = max(t, 1.0 - max(max(samples.x, samples.y), max(samples.z, samples.w)));
        if (tIn > t) p = p0 + dir * tIn;
        t = tIn;
        const vec3 along = hfx_patch_along(samples, cell, p, dir);
        const float A = along.x, B = along.y + 1.0, C = along.z - (1.0 - t);
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
        hfx_step(p0, dir, false, t, bound, tCross, tExit, topLevel, true, p, t, level);
        ++steps;
    }
    return t;
}

HfxHit hfx_trace(HfxRay ray) { return hfx_hit_at(ray, hfx_trace_depth(ray)); }

// The beam start (SurfaceRenderer's prepass over blocks of pixels): a depth fraction at or above
// the first hit of every ray that stays within `reach` texels of the ray p0 + dir t on each axis
// for all t in [0, 1] (cell space, as hfx_trace_depth's). The walk is hfx_trace_depth's over
// levels from k up, where cells are at least `reach` wide, against the largest maximum of the 3x3
// cells around the ray's: a ray within reach is in one of them wherever this one is, at the same
// height, so where this one passes above their maximum none of them can meet the surface. It
// returns where it first comes down to such a maximum at level k (no solve); the walk per pixel
// starts there (HfxRay.start). Nine bounds per step, once per 8x8-pixel block: 1.6-3.5 ms
// at 1280x720 on llvmpipe, for 16-46% of the view walk's fetches at 45-80 degrees in bench-tracers'
// view (docs/BENCHMARKS.md, fourteenth and fifteenth parts; 4x4 blocks cost more than they saved,
// 16x16 saved less).
float hfx_beam_depth(vec2 p0, vec2 dir, float reach) {
    const bvec2 back = lessThan(dir, vec2(0.0));
    const vec2 invDir = hfx_inverse(dir);
    const int levels = hfx_levels();
    const int k = clamp(int(ceil(log2(max(reach, 1.0 / 64.0)))), 0, levels - 1);
    const int topLevel = max(hfx_top_level(dir), k);
    const int maxSteps = hfx_max_steps(dir, topLevel);
    int level = k;
    float t = clamp(1.0 - hfx_field_max(), 0.0, 1.0);
    vec2 p = p0 + dir * t;
    for (int steps = 0; steps < maxSteps && t < 1.0; ++steps) {
        vec2 cell, bound, tCross;
        float tExit;
        hfx_cell_at(p0, p, invDir, back, t, level, cell, bound, tCross, tExit);
        const ivec2 c = ivec2(cell);
        float highest = 0.0;
        for (int j = -1; j <= 1; ++j)
            for (int i = -1; i <= 1; ++i) highest = max(highest, hfx_bounds(c + ivec2(i, j), level).x);
        const float tDown = 1.0 - highest;
        const bool dip = tDown < tExit;
        const float tIn = max(t, tDown);
        if (dip && level == k) return tIn;
        hfx_step(p0, dir, dip, tIn, bound, tCross, tExit, topLevel, true, p, t, level);
    }
    return t >= 1.0 ? 1.0 : 0.0; // past the bottom, or out of steps (a NaN ray): no start
}

// Exact self-shadow: the light ray from the shaded point walked through the same pyramid. The
// ray climbs from h0 to 1 over its span; its clearance ratio r = (ray - surface) / (the ray's
// climb so far) is Tatarchuk's occlusion measure with the sign turned (blocker distance
// weighting: a blocker as high but twice as far darkens half as much). r < 0 anywhere is hard
// shadow; otherwise the penumbra is 1 - r * sharpness at the smallest r, fully lit from
// r = 1 / sharpness. The walk opens every cell whose bound reaches the cone edge (the ray
// lowered by 1 / sharpness of its climb), so every blocker that can darken the point is
// solved at level 0, where the patch's height along the ray less the ray's is quadratic in t:
// its maximum (ends and vertex) decides hard shadow exactly, and r's minimum over the cell is at
// an end or at u* = sqrt(C'/A) (d/du of f(u)/u = 0). r counts from a texel away from the point:
// nearer, it is the surface's own slope towards the light (N.L's business), and f's rounding
// over a tiny climb would speckle it. Only a blocker above the ray returns 1; the penumbra stops
// just short of it. Two cuts that keep all this exact: once a blocker has set r below
// 1 / sharpness, only cells that could set it lower are opened (the cone edge rises to the ray
// lowered by r of its climb), and the walk ends where the cone edge passes the field's maximum
// (the pyramid's top texel), or sooner where a clearance map says nothing further can darken it.
// Where the caller has this walk's shadow at the field's samples for the ray's light (texel
// shadows, hfx_texel_shadow) and the four around the point agree on the hard shadow, their blend
// is returned without a walk.
const float HFX_SHADOW_EPSILON = 1e-4; // relief depths: above the rounding of h0 and of the patch
const float HFX_PENUMBRA_MAX = 0.999;   // 1 means a blocker above the ray, nothing less

float hfx_shadow(HfxShadowRay ray) {
    const float climb = 1.0 - ray.h0;
    if (!(climb > 0.0)) return 0.0; // at the top of the relief nothing is above it
    const ivec2 size = hfx_size();
    const vec2 p0 = ray.uv * vec2(size) - 0.5;
    const vec2 dir = ray.span * vec2(size);
    const bvec2 back = lessThan(dir, vec2(0.0));
    const vec2 invDir = hfx_inverse(dir);
    const int topLevel = hfx_top_level(dir);
    const int maxSteps = hfx_max_steps(dir, topLevel);
    const float penumbra = 1.0 / max(ray.sharpness, 1e-3); // r from which on the point is lit
    const float coneSlope = climb * (1.0 - penumbra);        // the cone edge's rise per unit t
    float known;
    if (hfx_texel_shadow(p0, ray.span / climb, penumbra, known)) return known;
    int level = 0;
    float t = 0.0;
    vec2 p = p0;
    const float uNear = 1.0 / max(max(abs(dir.x), abs(dir.y)), 1.0);
    float nearest = 1e30; // the smallest clearance ratio met
    const float fieldMax = hfx_field_max();
    // A clearance map (trace/README.md) ends the walk sooner where it knows nothing further can
    // darken the point: at 0, before it starts.
    const float tClear = hfx_clearance(ivec2(floor(p0)), ray.span / climb, penumbra) / climb;
    const float tEnd = min(coneSlope > 0.0 ? min(1.0, (fieldMax - ray.h0) / coneSlope) : 1.0, tClear);
    int steps = 0;
    for (int candidate = 0; candidate < maxSteps; ++candidate) {
        bool found = false;
        for (; steps < maxSteps && t < tEnd; ++steps) {
            vec2 cell, bound, tCross;
            float tExit;
            hfx_cell_at(p0, p, invDir, back, t, level, cell, bound, tCross, tExit);
            // (A graze within HFX_SHADOW_EPSILON sets r < 0: the edge never rises above the ray.)
            const float slope = climb * (1.0 - clamp(nearest, 0.0, penumbra));
            const float coneLow = ray.h0 + min(slope * t, slope * tExit);
            const vec2 bounds = hfx_bounds(ivec2(cell), level);
            const bool dip = bounds.x >= coneLow;
            if (dip && level == 0) { found = true; break; }
            hfx_step(p0, dir, dip, t, bound, tCross, tExit, topLevel, true, p, t, level);
        }
        if (!found) break;
        // The level-0 cell again (the same p and t: the same cell).
        vec2 cell, bound, tCross;
        float tExit;
        hfx_cell_at(p0, p, invDir, back, t, 0, cell, bound, tCross, tExit);
        // f(s) = patch - ray (h0 + climb t, rising) along the cell, s in [0, S]: A s^2 + B s + C.
        const vec3 along = hfx_patch_along(hfx_patch_samples(cell), cell, p, dir);
        const float A = along.x, B = along.y - climb, C = along.z - (ray.h0 + climb * t);
        const float S = tExit - t;
        const float sv = A < 0.0 ? clamp(-0.5 * B / A, 0.0, S) : 0.0; // the maximum's place
        if (max(max(C, (A * S + B) * S + C), (A * sv + B) * sv + C) > HFX_SHADOW_EPSILON) return 1.0;
        if (tExit > uNear) {
            // In u = t + s: f = A u^2 + B' u + C', r(u) = -f / (climb u), over [max(t, uNear), tExit].
            const float B1 = B - 2.0 * A * t, C1 = C - B * t + A * t * t, u0 = max(t, uNear);
            const float uStar = A != 0.0 && C1 / A > 0.0 ? clamp(sqrt(C1 / A), u0, tExit) : u0;
            const vec3 u = vec3(u0, tExit, uStar);
            const vec3 r = -((A * u + B1) * u + C1) / (climb * u);
            nearest = min(nearest, min(min(r.x, r.y), r.z));
        }
        hfx_step(p0, dir, false, t, bound, tCross, tExit, topLevel, true, p, t, level);
        ++steps;
    }
    return clamp(1.0 - nearest * ray.sharpness, 0.0, HFX_PENUMBRA_MAX);
}
