// What every tracer (trace/*.glsl) shares: the ray and hit types of the contract in
// trace/README.md, and the linear search and shadow occlusion built on the harness's
// hfx_height. Texture space: x = u, y = v, heights h in [0,1] with 1 at the polygon; a ray enters
// at h = 1 and reaches h = 0 after moving by its parallax vector in texcoords.

struct HfxRay {
    vec2 uv;        // entry texcoords: where the view ray crosses the polygon (h = 1)
    vec2 parallax;  // the ray's texcoord offset from h = 1 down to h = 0 (P = V.xy / V.z * depthScale)
    float cosTheta; // z of the unit texture-space vector towards the eye (offset limiting)
    float level;    // mip level the search's fetches read
    int samples;    // linear-search steps for this pixel (the dynamic sample rate, the caller's)
    float tolerance; // depth fraction the hit may lie above the exact one (the exact tracer's
                     // pixel budget; 0: exact); tracers that are not exact ignore it
    float start;     // a depth fraction the caller knows lies at or above the first hit (0: none;
                     // the exact tracer's beam start, trace/hier.glsl); the others ignore it
};

struct HfxHit {
    vec2 uv;     // texcoords of the hit
    float depth; // how far below the polygon, as a fraction of the relief depth (0..1)
};

struct HfxShadowRay {
    vec2 uv;         // the displaced point
    float h0;        // its height
    vec2 span;       // texcoord offset from the point to where the light ray climbs to h = 1
    float level;     // mip level of the fetches
    int samples;     // heights sampled along the light ray
    float sharpness; // how fast a blocker's occlusion saturates (soft shadows)
};

const int HFX_MAX_SAMPLES = 256;       // hard bound of every search loop; rays ask for fewer
const int HFX_MAX_SHADOW_SAMPLES = 32;

// The height-bounds pyramid's level count (hfx_bounds' levels 0 .. hfx_levels() - 1): the last
// level is one texel over the whole power-of-two field.
int hfx_levels() {
    const ivec2 size = hfx_size();
    return findMSB(max(size.x, size.y)) + 1;
}

HfxHit hfx_hit_at(HfxRay ray, float t) { return HfxHit(ray.uv - ray.parallax * t, t); }

// Linear search in depth fraction t (ray height 1 - t): the first of its equal steps whose sample
// is at or above the ray. On a hit, [t0, t1] brackets it with d = surface - ray heights
// d0 < 0 <= d1; t0 == t1 when the ray meets the relief at its first sample. The search spans
// only the depths where the heights on the ray's path can be (hfx_segment_bounds: the ray
// reaches their maximum at 1 - max and is below every height from 1 - min on), in steps no longer
// than 1 / ray.samples: where the bounds are tight that is fewer steps, each as fine as before.
// Without bounds (1, 0) it is the plain search of [0, 1].
bool hfx_linear_search(HfxRay ray, out float t0, out float t1, out float d0, out float d1) {
    const vec2 bounds = hfx_segment_bounds(ray.uv, ray.uv - ray.parallax, ray.level);
    const float tStart = clamp(1.0 - bounds.x, 0.0, 1.0), tEnd = clamp(1.0 - bounds.y, tStart, 1.0);
    const int steps = max(int(ceil(float(ray.samples) * (tEnd - tStart))), 1);
    const float stepSize = (tEnd - tStart) / float(steps);
    t0 = tStart;
    d0 = hfx_height(ray.uv - ray.parallax * tStart, ray.level) - (1.0 - tStart);
    t1 = t0;
    d1 = d0;
    if (d0 >= 0.0) return true;
    for (int i = 1; i <= HFX_MAX_SAMPLES; ++i) {
        if (i > steps) break;
        t1 = i == steps ? tEnd : tStart + float(i) * stepSize;
        d1 = hfx_height(ray.uv - ray.parallax * t1, ray.level) - (1.0 - t1);
        if (d1 >= 0.0) return true;
        t0 = t1;
        d0 = d1;
    }
    // Below the bounds' minimum the ray is under the surface: a sample found short of it there
    // can only be the storage's rounding. Without bounds the ray has left the relief.
    if (tEnd < 1.0) {
        d1 = 0.0;
        return true;
    }
    return false;
}

// Tatarchuk's occlusion: heights along the light ray from the displaced point; a blocker's
// occlusion is its rise above the ray relative to the ray's own climb there, so a close blocker
// (small climb) counts fully and a far one weakly. The largest over the samples; > 0 means some
// sample stood above the ray. The samples lie where a blocker can be: on the part of the ray
// below the heights' maximum on its path (hfx_segment_bounds), none where it is above them, and
// no farther apart than ray.samples over the whole ray would be.
//
// The ray starts on the surface above the point (one fetch): a sampled search's hit can lie under
// the surface (up to a step deep for steep parallax, less for POM's segment where the relief
// bends), and a light ray from there started inside the relief, where the surface right above
// read as a blocker (steep's flat tops came out dark almost everywhere). Its span shrinks to the
// climb left; at the top of the relief nothing is above it.
float hfx_occlusion(HfxShadowRay ray) {
    const float surface = max(ray.h0, hfx_height(ray.uv, ray.level));
    if (surface >= 1.0) return 0.0;
    ray.span *= (1.0 - surface) / (1.0 - ray.h0);
    ray.h0 = surface;
    const float top = hfx_segment_bounds(ray.uv, ray.uv + ray.span, ray.level).x;
    const float reach = clamp((top - ray.h0) / max(1.0 - ray.h0, 1e-6), 0.0, 1.0);
    const int samples = clamp(int(ceil(float(ray.samples) * reach)), 0, HFX_MAX_SHADOW_SAMPLES);
    float occlusion = 0.0;
    for (int i = 1; i <= HFX_MAX_SHADOW_SAMPLES; ++i) {
        if (i > samples) break;
        const float f = reach * float(i) / float(samples + 1);
        const float rayHeight = ray.h0 + f * (1.0 - ray.h0);
        const float blocker = hfx_height(ray.uv + ray.span * f, ray.level) - rayHeight;
        occlusion = max(occlusion, blocker / (f * (1.0 - ray.h0)));
    }
    return occlusion;
}
