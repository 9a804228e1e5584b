// Hierarchical tracer: the exact first hit of the ray with the bilinear surface, walking the
// maximum-height pyramid (hfx_bound). A cell whose bound the ray passes above is skipped whole
// (and the walk climbs a level), one the ray dips into is opened a level down; at level 0 the
// bilinear patch between four samples (hfx_gather) is intersected in closed form (the height
// along the ray is quadratic in t). Cell space: x = u * width - 0.5, so cell i spans the samples
// i and i + 1. Soft self-shadows.

const int HFX_MAX_TRACE_STEPS = 512;

float hfx_trace_depth(vec2 uv0, vec2 parallax) {
    const ivec2 size = hfx_size();
    const vec2 p0 = uv0 * vec2(size) - 0.5;
    const vec2 dir = -parallax * vec2(size);
    const vec2 nudge = sign(dir) * 1e-4; // puts a point on a cell boundary into the next cell
    const vec2 invDir = vec2(dir.x != 0.0 ? 1.0 / dir.x : 1e30, dir.y != 0.0 ? 1.0 / dir.y : 1e30);
    const int maxLevel = hfx_levels() - 1;
    int level = maxLevel;
    float t = 0.0;
    for (int iter = 0; iter < HFX_MAX_TRACE_STEPS; ++iter) {
        if (t >= 1.0) return 1.0;
        const vec2 p = p0 + dir * t;
        const float cellSize = float(1 << level);
        const vec2 cell = floor((p + nudge) / cellSize);
        const vec2 bound = (cell + step(0.0, dir)) * cellSize;
        const vec2 tCross = (bound - p0) * invDir;
        const float tExit = min(min(dir.x != 0.0 ? tCross.x : 1e30, dir.y != 0.0 ? tCross.y : 1e30), 1.0);
        const float tDown = 1.0 - hfx_bound(ivec2(cell), level); // where the ray has come down to the bound
        if (tDown >= tExit) {
            t = tExit;
            level = min(level + 1, maxLevel);
            continue;
        }
        const float tIn = max(t, tDown);
        if (level > 0) {
            t = tIn;
            --level;
            continue;
        }
        // Level 0: the four samples of the cell in one gather (x: (i, j+1), y: (i+1, j+1),
        // z: (i+1, j), w: (i, j)), at the point all four texels share.
        const vec4 q = hfx_gather((cell + 1.0) / vec2(size));
        const float a = q.w, b = q.z - q.w, c = q.x - q.w, e = q.y - q.x - q.z + q.w;
        const vec2 local = p0 + dir * tIn - cell;
        const float A = e * dir.x * dir.y;
        const float B = b * dir.x + c * dir.y + e * (local.x * dir.y + local.y * dir.x) + 1.0;
        const float C = a + b * local.x + c * local.y + e * local.x * local.y - (1.0 - tIn);
        const float len = tExit - tIn;
        if (C >= 0.0) return tIn;
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
        if (root <= len) return tIn + root;
        t = tExit;
        level = min(level + 1, maxLevel);
    }
    return t;
}

HfxHit hfx_trace(HfxRay ray) { return hfx_hit_at(ray, hfx_trace_depth(ray.uv, ray.parallax)); }
float hfx_shadow(HfxShadowRay ray) { return clamp(hfx_occlusion(ray) * ray.sharpness, 0.0, 1.0); }
