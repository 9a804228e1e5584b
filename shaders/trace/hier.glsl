// Hierarchical tracer: the exact first hit of the ray with the bilinear surface, walking the
// height-bounds pyramid (hfx_bounds: max and min per cell). The walk starts at the level-0 cell
// where the ray comes down to the field's maximum (the pyramid's top texel: above it the ray meets
// nothing), or later where the caller knows no hit comes sooner (HfxRay.start: the beam
// prepass's depth for the pixel's block, hfx_beam_depth below), so a ray that meets the relief at
// once costs three fetches. A cell whose maximum the ray passes above is skipped whole, and where
// its exit is also its parent's edge the walk climbs a level; a cell the ray dips into is opened
// a level down. A level-0 cell the ray dips into is solved: the bilinear patch between four
// samples (hfx_cell_samples) in closed form (the height along the ray is quadratic in t); if the
// ray passes the patch the walk goes on. Cell space: x = u * width - 0.5, so cell i spans the
// samples i and i + 1. Exact self-shadows with a blocker-distance penumbra (hfx_shadow, below).
//
// A cell of any level the ray dips into and leaves at or below the cell's minimum surely holds the hit,
// between where the ray comes down to its maximum and where it passes its minimum. Where that
// span is no longer than ray.tolerance (the pixel budget; 0 on flat tops, whose hit is then
// exact) the walk returns its start: never below the surface, at most the tolerance above the
// hit, and no descent to level 0. A ray that enters on a patch's top within the float rounding of
// its position (HFX_TOUCH_ULPS: a plateau at h = 1 touched at the entry) has hit it.
//
// The walk (HfxWalk, written once for the view ray, the light ray and the beam prepass) is one
// loop with one bound fetch per step, shaped for a GPU, where a warp waits for its slowest lane
// and a uniform branch runs one side: integer cells in a frame where the ray moves towards +x and
// +y (a back axis is mirrored: frame cell c is field cell ~c), relative to an even multiple of the
// field's size, zero where the entry's texcoords lie in [0, 2) (coordinates stay small however far
// the texcoords run, and the cells the accessors get need no offset: a wrapping field's are the
// same cells after the wrap, a clamped field's, entered within [0, 1], its own); per axis the depth where
// the ray leaves its cell, from the cell's integer corner in one multiply-add (no floor, no drift
// from adding steps); descending picks the child by comparing the entry with the middle
// boundary, climbing halves the cell. The patch solve is the rare branch inside the loop.
//
// Why it cannot step over a surface (tests/TracerContractTest.cpp, a million rays):
// - the cells are integers and the ray's depth at each cell's far boundary grows with the cell:
//   a skip moves into the next cell across every axis whose boundary the exit reaches, a point
//   on a boundary belongs to the cell ahead, and no rounding of a position can land the walk in
//   any cell but the next;
// - the ray only descends, so a cell it has dipped into stays open: the walk never climbs back
//   into a parent it has opened, and climbs no higher than the level whose cells are as wide as
//   the ray's footprint;
// - every step skips a cell (past at least one texel boundary), opens one (at most one per
//   climb) or solves one, so the walk needs at most about three steps per texel boundary the
//   ray crosses: the loop's bound is computed from the ray, not a fixed count that long grazing
//   rays run out of.
//
// What a step costs: `python3 scripts/walk_instructions.py` counts it in the compiled shader. The
// bound's texel is the frame cell's bits flipped (the accessors wrap or clamp it); the view
// walk's climb needs no level cap of its own (its clearance test fails at the top level); the
// depths that only a dipped-into cell needs are worked out inside that branch. On an NVIDIA H200
// the walks are the draw's cost (without them it is 0.5-0.7x POM's) and are bound by the
// instructions they issue, not by their fetches' waits: a level-0 step reading the cell's samples
// (fewer fetches, more instructions) was slower, the solves gathered after the bounds' loop much
// slower, and fetching the next cell of a level with each one a few per cent faster on most views
// and slower on others (docs/history/tuning.md, issue 36's part). A cheaper pixel needs fewer steps.

// To the fragment stage (surface.frag): interpolate the polygon's frame again after the trace
// rather than keep it through the walk, whose state and patch solve hold many registers.
#define HFX_FRAME_AFTER_TRACE 1

const int HFX_MAX_TRACE_STEPS = 1 << 18; // only against a NaN ray; the real bound is per ray
// The view walk climbs past a cell only where the ray leaves it at least this many cells' widths
// (along the ray's major axis, at the ray's descent) above the cell's maximum: nearer, the
// parent (no lower) is likely opened again at once, two fetches for nothing. The light walk,
// rising away from the relief, climbs wherever it may, up to its top level.
const float HFX_CLIMB_CLEARANCE = 2.0;
// A ray entering a patch at the polygon (t = 0) above it by no more than the patch rises over a
// couple of roundings of the ray's position (HFX_TOUCH_ULPS of its largest cell-space coordinate, and
// of 1) has touched it: the fragment stage's texcoords carry that rounding, and a ray entering on a
// plateau's top (h = 1) at a sample where the surface falls away would otherwise walk on. Deeper
// down a pass above a patch is a miss, however close (a thin wall's top).
const float HFX_TOUCH_ULPS = 2.0;

// A walk of the ray p0 + dir t (cell space, t in [0, 1]) through the pyramid's cells.
struct HfxWalk {
    vec2 q0;     // the ray's start in the walk's frame: relative to base, each back axis mirrored
    vec2 start;  // ... and unmirrored (the patch solve's coordinates)
    vec2 rate;   // 1 / the ray's move per unit t along each axis, in cells (1e30: it does not move)
    ivec2 flip;  // per axis: ~0 where the ray moves back (frame cell c is field cell ~c), else 0
    ivec2 cell;  // the cell of `level` the ray is in, in the frame
    int level;
    vec2 tNext;  // the ray's depth where it leaves that cell across each axis
    float t;     // the ray's depth: the walk has passed everything before it
};

// Where the ray crosses the frame's lines x = edge.x and y = edge.y (edges in level-0 cells).
vec2 hfx_walk_cross(HfxWalk w, ivec2 edge) { return (vec2(edge) - w.q0) * w.rate; }

HfxWalk hfx_walk_begin(vec2 p0, vec2 dir, float t, int level) {
    HfxWalk w;
    const ivec2 size = hfx_size();
    // The frame's origin in the field: an even multiple of its size (every level's cells align),
    // 0 for texcoords in [0, 2). Not kept, nor is p0: the start relative to it is what the patch
    // solve needs (two registers fewer through the loop: docs/history/tuning.md).
    const ivec2 base = ivec2(floor((p0 + 0.5) / vec2(2 * size))) * (2 * size);
    const bvec2 back = lessThan(dir, vec2(0.0));
    w.flip = -ivec2(back);
    const vec2 start = p0 - vec2(base), speed = abs(dir);
    w.q0 = mix(start, -start, back);
    w.start = start;
    w.rate = vec2(speed.x > 0.0 ? 1.0 / speed.x : 1e30, speed.y > 0.0 ? 1.0 / speed.y : 1e30);
    w.level = level;
    w.t = t;
    w.cell = ivec2(floor(w.q0 + speed * t)) >> level;
    w.tNext = hfx_walk_cross(w, (w.cell + 1) << level);
    return w;
}

// The walk's cell in the field relative to the frame's origin (the accessors wrap or clamp it; the
// origin is a multiple of every level's size, and 0 where a clamped field is entered), and the
// ray's point at depth t relative to the corner of the walk's level-0 cell, unmirrored (the patch
// solve's coordinates: the cell spans [0, 1]).
ivec2 hfx_walk_texel(HfxWalk w) { return w.cell ^ w.flip; }
vec2 hfx_walk_local(HfxWalk w, vec2 dir, float t) { return w.start + dir * t - vec2(hfx_walk_texel(w)); }

// Where the walk leaves its cell (within [t, 1]).
float hfx_walk_exit(HfxWalk w) { return clamp(min(w.tNext.x, w.tNext.y), w.t, 1.0); }

// Into the child of the cell that the ray is in at tIn (at or after t, before the exit), a level
// down; on the middle line, the child ahead.
void hfx_walk_descend(inout HfxWalk w, float tIn) {
    w.level -= 1;
    const ivec2 first = w.cell << 1;
    const vec2 tMiddle = hfx_walk_cross(w, (first + 1) << w.level);
    const bvec2 ahead = greaterThanEqual(vec2(tIn), tMiddle);
    w.cell = first + ivec2(ahead);
    w.tNext = mix(tMiddle, w.tNext, ahead);
    w.t = tIn;
}

// Past the cell to its exit tExit: into the next cell across every axis the ray leaves it by
// there, and a level up where mayClimb and a crossed line is also the parent's edge (the ray only
// descends, so a parent it has dipped into is never entered again), no higher than topLevel
// where `capped` (a constant: a walk whose mayClimb already fails at its top passes false).
void hfx_walk_skip(inout HfxWalk w, float tExit, bool mayClimb, const bool capped, int topLevel) {
    const ivec2 crossed = ivec2(lessThanEqual(w.tNext, vec2(tExit)));
    w.cell += crossed;
    bool climbs = mayClimb && any(notEqual(crossed & ~w.cell, ivec2(0)));
    if (capped) climbs = climbs && w.level < topLevel;
    const int up = int(climbs);
    w.cell >>= up;
    w.level += up;
    w.tNext = hfx_walk_cross(w, (w.cell + 1) << w.level);
    w.t = tExit;
}

// The bilinear patch of a level-0 cell's samples (x: (i, j+1), y: (i+1, j+1), z: (i+1, j),
// w: (i, j)) along the ray from `local` (the point in the cell, relative to its corner (i, j)):
// its height at local + dir * s is A s^2 + B s + C, returned as (A, B, C).
vec3 hfx_patch_along(vec4 s, vec2 local, vec2 dir) {
    const float a = s.w, b = s.z - s.w, c = s.x - s.w, e = s.y - s.x - s.z + s.w;
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

float hfx_trace_depth(HfxRay ray) {
    const ivec2 size = hfx_size();
    const vec2 p0 = ray.uv * vec2(size) - 0.5;
    const vec2 dir = -ray.parallax * vec2(size);
    const int topLevel = hfx_top_level(dir);
    const int maxSteps = hfx_max_steps(dir, topLevel);
    // The climb's clearance at level 0 in depth: HFX_CLIMB_CLEARANCE cells along the ray's major
    // axis (texels per unit of t), doubling a level up. Raised where the ray is longer than the
    // field, so that at the top level it is over 1, more than any depth: the walk climbs no higher.
    const float major = max(abs(dir.x), abs(dir.y));
    const float climbGap = max(HFX_CLIMB_CLEARANCE / major, exp2(1.0 - float(topLevel)));
    const float touch = HFX_TOUCH_ULPS * exp2(-23.0) * (max(abs(p0.x), abs(p0.y)) + 1.0); // cells
    HfxWalk w = hfx_walk_begin(p0, dir, clamp(max(1.0 - hfx_field_max(), ray.start), 0.0, 1.0), 0);
    for (int steps = 0; steps < maxSteps && w.t < 1.0; ++steps) {
        const float tExit = hfx_walk_exit(w);
        const vec2 bounds = hfx_bounds(hfx_walk_texel(w), w.level);
        const float tDown = 1.0 - bounds.x; // where the ray comes down to the cell's maximum
        if (tDown < tExit) {
            const float tBelow = 1.0 - bounds.y; // ... and passes its minimum: the hit is in [tIn, tBelow]
            const float tIn = max(w.t, tDown);
            // (At tExit itself the ray is still over the cell's closed patch: the bounds hold there.)
            if (tBelow <= min(tExit, tIn + ray.tolerance)) return tIn;
            if (w.level > 0) {
                hfx_walk_descend(w, tIn);
                continue;
            }
            const vec4 s = hfx_cell_samples(hfx_walk_texel(w));
            // A level-0 cell (s: its samples): from tIn (the ray is above the patch before it,
            // which is no higher than its largest sample) the patch's height minus the ray's
            // (1 - t, falling) along the cell, A s^2 + B s + C; its first root within the cell, if any.
            const vec3 along = hfx_patch_along(s, hfx_walk_local(w, dir, tIn), dir);
            const float A = along.x, B = along.y + 1.0, C = along.z - (1.0 - tIn);
            // The patch's rise over a move of `touch` on both axes: |b| + |e| and |c| + |e| at most.
            const vec3 rise = abs(vec3(s.z - s.w, s.x - s.w, s.y - s.x - s.z + s.w));
            if (C >= (tIn > 0.0 ? 0.0 : -touch * (rise.x + rise.y + 2.0 * rise.z))) return tIn;
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
            if (root <= tExit - tIn) return tIn + root;
            // The ray passes over the patch: on past the cell.
        }
        hfx_walk_skip(w, tExit, tDown - tExit >= ldexp(climbGap, w.level), false, topLevel);
    }
    return w.t;
}

HfxHit hfx_trace(HfxRay ray) { return hfx_hit_at(ray, hfx_trace_depth(ray)); }

// The beam start (SurfaceRenderer's prepass over blocks of pixels): a depth fraction at or above
// the first hit of every ray that stays within `reach` texels of the ray p0 + dir t on each axis
// for all t in [0, 1] (cell space, as hfx_trace_depth's). The walk is hfx_trace_depth's over
// levels from k up, where cells are at least `reach` wide, against the largest maximum of the 3x3
// cells around the ray's: a ray within reach is in one of them wherever this one is, at the same
// height, so where this one passes above their maximum none of them can meet the surface. It
// returns where it first comes down to such a maximum at level k (no solve); the walk per pixel
// starts there (HfxRay.start). Nine bounds per step, once per 8x8-pixel block.
float hfx_beam_depth(vec2 p0, vec2 dir, float reach) {
    const int levels = hfx_levels();
    const int k = clamp(int(ceil(log2(max(reach, 1.0 / 64.0)))), 0, levels - 1);
    const int topLevel = max(hfx_top_level(dir), k);
    const int maxSteps = hfx_max_steps(dir, topLevel);
    HfxWalk w = hfx_walk_begin(p0, dir, clamp(1.0 - hfx_field_max(), 0.0, 1.0), k);
    for (int steps = 0; steps < maxSteps && w.t < 1.0; ++steps) {
        const float tExit = hfx_walk_exit(w);
        const ivec2 c = hfx_walk_texel(w);
        float highest = 0.0;
        for (int j = -1; j <= 1; ++j)
            for (int i = -1; i <= 1; ++i) highest = max(highest, hfx_bounds(c + ivec2(i, j), w.level).x);
        const float tDown = 1.0 - highest;
        const float tIn = max(w.t, tDown);
        if (tDown < tExit) {
            if (w.level == k) return tIn;
            hfx_walk_descend(w, tIn);
        } else {
            hfx_walk_skip(w, tExit, true, true, topLevel);
        }
    }
    return w.t >= 1.0 ? 1.0 : 0.0; // past the bottom, or out of steps (a NaN ray): no start
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
// (the pyramid's top texel). (The renderer reads this walk's shadow from the texel shadows
// instead where they hold it: surface/shadow.glsl.)
const float HFX_SHADOW_EPSILON = 1e-4; // relief depths: above the rounding of h0 and of the patch
const float HFX_PENUMBRA_MAX = 0.999;   // 1 means a blocker above the ray, nothing less

float hfx_shadow(HfxShadowRay ray) {
    const float climb = 1.0 - ray.h0;
    if (!(climb > 0.0)) return 0.0; // at the top of the relief nothing is above it
    const ivec2 size = hfx_size();
    const vec2 p0 = ray.uv * vec2(size) - 0.5;
    const vec2 dir = ray.span * vec2(size);
    const int topLevel = hfx_top_level(dir);
    const int maxSteps = hfx_max_steps(dir, topLevel);
    const float penumbra = 1.0 / max(ray.sharpness, 1e-3); // r from which on the point is lit
    const float coneSlope = climb * (1.0 - penumbra);        // the cone edge's rise per unit t
    const float uNear = 1.0 / max(max(abs(dir.x), abs(dir.y)), 1.0);
    float nearest = 1e30; // the smallest clearance ratio met
    // The cone edge's rise per unit t, climb (1 - the clearance ratio it stands for: the smallest
    // met, at most the penumbra's), and whether it rises (its lowest point over a cell is then
    // where the ray enters it, else where it leaves): both change only where nearest does.
    float slope = coneSlope;
    bool rising = slope >= 0.0;
    const float fieldMax = hfx_field_max();
    const float tEnd = coneSlope > 0.0 ? min(1.0, (fieldMax - ray.h0) / coneSlope) : 1.0;
    HfxWalk w = hfx_walk_begin(p0, dir, 0.0, 0);
    for (int steps = 0; steps < maxSteps && w.t < tEnd; ++steps) {
        const float tExit = hfx_walk_exit(w);
        // (A graze within HFX_SHADOW_EPSILON sets r < 0: the edge never rises above the ray.)
        const float coneLow = fma(slope, rising ? w.t : tExit, ray.h0);
        const vec2 bounds = hfx_bounds(hfx_walk_texel(w), w.level);
        if (bounds.x >= coneLow) {
            if (w.level > 0) {
                hfx_walk_descend(w, w.t);
                continue;
            }
            // f(s) = patch - ray (h0 + climb t, rising) along the cell, s in [0, S]: A s^2 + B s + C.
            const float t = w.t;
            const vec4 s = hfx_cell_samples(hfx_walk_texel(w));
            const vec3 along = hfx_patch_along(s, hfx_walk_local(w, dir, t), dir);
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
                slope = climb * (1.0 - clamp(nearest, 0.0, penumbra));
                rising = slope >= 0.0;
            }
        }
        hfx_walk_skip(w, tExit, true, true, topLevel);
    }
    return clamp(1.0 - nearest * ray.sharpness, 0.0, HFX_PENUMBRA_MAX);
}
