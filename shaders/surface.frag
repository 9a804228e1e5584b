#version 450 core
// Surface shading of a height field: parallax occlusion mapping after Tatarchuk (I3D 2006,
// "Dynamic Parallax Occlusion Mapping with Approximate Soft Shadows"), or plain normal mapping.
//
// Variants (prepended #defines):
//   HFX_TECHNIQUE     0 = normal mapping, 1 = parallax occlusion mapping (Tatarchuk 2006),
//                     2 = parallax mapping with offset limiting (Welsh 2004), 3 = steep parallax
//                     (McGuire 2005), 4 = relief mapping, linear then binary search (Policarpo
//                     2005), 5 = linear search refined by 3 secant steps, 6 = hierarchical tracer
//                     over the per-frame maximum-height pyramid down to the exact bilinear hit
//   HFX_TRACE_OUTPUT  1 = also write (u, v, depth fraction, fetches + lit / 2) of the hit to
//                     output 1: the height fetches counted in the integer part, the self-shadow
//                     light factor (0 = shadowed) as twice the fraction
//   HFX_SHADING       0 = Blinn-Phong, 1 = water (Fresnel sky reflection, sun glint, body colour
//                     by depth, haze), 2 = planet (Blinn-Phong, soft terminator, atmosphere rim)
//
// Conventions: s_surface holds the tangent-space normal in xyz and the height h in w, h = 1 at the
// polygon and 0 at the deepest point, u_depthScale texture units below it. Texture space has
// x = u, y = v and z along the normal, one unit = one texture repeat.

#ifndef HFX_TECHNIQUE
#define HFX_TECHNIQUE 1
#endif
#ifndef HFX_TRACE_OUTPUT
#define HFX_TRACE_OUTPUT 0
#endif
#ifndef HFX_SHADING
#define HFX_SHADING 0
#endif

in vec3 v_worldPos;
in vec3 v_normal;
in vec3 v_tangent;
in vec3 v_bitangent;
in vec2 v_texcoord;

layout(location = 0) out vec4 o_color;
#if HFX_TRACE_OUTPUT
layout(location = 1) out vec4 o_trace;
#endif

uniform sampler2D s_surface;
uniform sampler2D s_albedo;
#if HFX_TECHNIQUE == 6
uniform sampler2D s_pyramid;     // R32F, level k texel bounds the bilinear cells it covers
uniform int u_pyramidLevels;
uniform ivec2 u_wrap;            // per axis: cell indices wrap (1, the field's edges wrap) or clamp
#endif

uniform mat4 u_viewProj;
uniform vec3 u_cameraPos;
uniform float u_depthScale;      // texture units between h = 1 and h = 0
uniform vec2 u_normalDecode;     // stored normal * x + y: (1, 0) for float formats, (2, -1) for unorm8
uniform float u_normalScale;     // u_depthScale / the depth the stored normals were made for
uniform int u_minSamples;        // linear-search steps looking straight down
uniform int u_maxSamples;        // ... and at grazing angles
uniform float u_lodThreshold;    // mip level from which on only normal mapping is done
uniform bool u_shadows;
uniform int u_shadowSamples;
uniform float u_shadowSharpness; // how fast a blocker's occlusion saturates
uniform bool u_clipToPatch;      // discard rays that leave u_patchBounds (finite patches)
uniform vec4 u_patchBounds;      // umin, vmin, umax, vmax
uniform vec3 u_lightDir;         // world space, towards the light, unit length
uniform vec3 u_lightColor;
uniform vec3 u_ambient;
uniform float u_specularStrength;
uniform float u_specularPower;
uniform float u_silhouetteFade;  // curved meshes: relief fades where cos(view) drops below this

#if HFX_SHADING == 1
uniform sampler2D s_environment; // equirectangular sky, when u_hasEnvironment
uniform bool u_hasEnvironment;
uniform vec3 u_deepColor;
uniform vec3 u_shallowColor;
uniform vec3 u_skyZenith;
uniform vec3 u_skyHorizon;
uniform float u_fresnelF0;
uniform float u_glintPower;
uniform float u_glintStrength;
uniform float u_hazeDistance;

// The sky seen along a world direction: the environment image, or a zenith-horizon gradient.
vec3 sky(vec3 dir) {
    if (u_hasEnvironment) {
        const float pi = 3.14159265;
        const vec2 uv = vec2(atan(dir.z, dir.x) / (2.0 * pi) + 0.5, acos(clamp(dir.y, -1.0, 1.0)) / pi);
        return textureLod(s_environment, vec2(uv.x, 1.0 - uv.y), 0.0).rgb;
    }
    return mix(u_skyHorizon, u_skyZenith, sqrt(clamp(dir.y, 0.0, 1.0)));
}
#endif

const int MAX_SAMPLES = 256;     // hard bound of every loop; the uniforms pick fewer
const int MAX_SHADOW_SAMPLES = 32;

// The search and shadow fetches read one mip level, the nearest to the level that the
// undisplaced texcoords' gradients select: computed once, so the level does not jump where the
// traced texcoords jump (silhouettes of the relief), and one level means the ray meets one
// bilinear surface, at about 60% of the cost of a trilinear textureGrad fetch on llvmpipe.
// Shading fetches keep trilinear filtering.
float g_fetches = 0.0; // height fetches of this pixel, reported by the trace output
float heightAt(vec2 uv, float searchLevel) {
    g_fetches += 1.0;
    return textureLod(s_surface, uv, searchLevel).w;
}

#if HFX_TECHNIQUE >= 1 && HFX_TECHNIQUE != 2 && HFX_TECHNIQUE != 6
// Linear search in depth fraction t (ray height 1 - t): the first of `steps` equal steps whose
// sample is at or above the ray. On a hit, [t0, t1] brackets it with d = surface - ray heights
// d0 < 0 <= d1; t0 == t1 == 0 when the ray starts inside the relief.
bool linearSearch(vec2 uv0, vec2 parallax, int steps, float level, out float t0, out float t1,
                  out float d0, out float d1) {
    const float stepSize = 1.0 / float(steps);
    t0 = 0.0;
    d0 = heightAt(uv0, level) - 1.0;
    t1 = 0.0;
    d1 = d0;
    if (d0 >= 0.0) return true;
    for (int i = 1; i <= MAX_SAMPLES; ++i) {
        if (i > steps) break;
        t1 = float(i) * stepSize;
        d1 = heightAt(uv0 - parallax * t1, level) - (1.0 - t1);
        if (d1 >= 0.0) return true;
        t0 = t1;
        d0 = d1;
    }
    return false;
}
#endif

#if HFX_TECHNIQUE == 6
const int MAX_TRACE_STEPS = 512;

// Exact first hit of the ray with the bilinear surface, walking the maximum-height pyramid:
// a cell whose bound the ray passes above is skipped whole (and the walk climbs a level), one
// the ray dips into is opened a level down; at level 0 the bilinear patch between four samples
// is intersected in closed form (the height along the ray is quadratic in t). Cell space: x =
// u * width - 0.5, so cell i spans the samples i and i + 1.
float traceHierarchical(vec2 uv0, vec2 parallax) {
    const ivec2 size = textureSize(s_surface, 0);
    const vec2 p0 = uv0 * vec2(size) - 0.5;
    const vec2 dir = -parallax * vec2(size);
    const vec2 nudge = sign(dir) * 1e-4; // puts a point on a cell boundary into the next cell
    const vec2 invDir = vec2(dir.x != 0.0 ? 1.0 / dir.x : 1e30, dir.y != 0.0 ? 1.0 / dir.y : 1e30);
    const int maxLevel = u_pyramidLevels - 1;
    int level = maxLevel;
    float t = 0.0;
    for (int iter = 0; iter < MAX_TRACE_STEPS; ++iter) {
        if (t >= 1.0) return 1.0;
        const vec2 p = p0 + dir * t;
        const float cellSize = float(1 << level);
        const vec2 cell = floor((p + nudge) / cellSize);
        const vec2 bound = (cell + step(0.0, dir)) * cellSize;
        const vec2 tCross = (bound - p0) * invDir;
        const float tExit = min(min(dir.x != 0.0 ? tCross.x : 1e30, dir.y != 0.0 ? tCross.y : 1e30), 1.0);
        const ivec2 levelSize = max(size >> level, ivec2(1));
        ivec2 index = ivec2(cell);
        index = mix(clamp(index, ivec2(0), levelSize - 1), (index % levelSize + levelSize) % levelSize, bvec2(u_wrap));
        const float bound_h = texelFetch(s_pyramid, index, level).r;
        g_fetches += 1.0;
        const float tDown = 1.0 - bound_h; // where the ray has come down to the cell's bound
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
        const vec4 q = textureGather(s_surface, (cell + 1.0) / vec2(size), 3);
        g_fetches += 1.0;
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
#endif

void main() {
    const vec3 geometricNormal = normalize(v_normal);
    // World from texture space: columns dP/du, dP/dv and the normal scaled to the same units.
    const float unitsPerTexcoord = sqrt(length(v_tangent) * length(v_bitangent));
    const mat3 worldFromTexture = mat3(v_tangent, v_bitangent, geometricNormal * unitsPerTexcoord);
    const vec3 toEye = u_cameraPos - v_worldPos;
    const float cosView = clamp(dot(geometricNormal, normalize(toEye)), 0.0, 1.0);
    // A degenerate frame (a sphere's poles, where dP/du vanishes) has no texture space: there the
    // surface is normal mapped. Silhouettes of curved meshes fade the relief out.
    const bool frameOk = length(v_tangent) > 1e-3 * length(v_bitangent) &&
                         length(v_bitangent) > 1e-3 * length(v_tangent);
    const float depthScale =
        frameOk ? u_depthScale * (u_silhouetteFade > 0.0 ? smoothstep(0.0, u_silhouetteFade, cosView) : 1.0)
                : 0.0;
#if HFX_TECHNIQUE >= 1
    const mat3 textureFromWorld = frameOk ? inverse(worldFromTexture) : mat3(1.0);
    const vec3 viewTS = textureFromWorld * toEye;
#endif

    const vec2 uv0 = v_texcoord;
    const vec2 dx = dFdx(uv0), dy = dFdy(uv0);
    const vec2 texels = vec2(textureSize(s_surface, 0));
    const vec2 dxTexels = dx * texels, dyTexels = dy * texels;
    const float mipLevel = 0.5 * log2(max(max(dot(dxTexels, dxTexels), dot(dyTexels, dyTexels)), 1e-12));
    const float searchLevel = max(round(mipLevel), 0.0);

    vec2 uv = uv0;
    float depthFraction = 0.0; // of u_depthScale, along the view ray, at the hit

#if HFX_TECHNIQUE >= 1
    if (mipLevel <= u_lodThreshold && viewTS.z > 0.0 && depthScale > 0.0) {
        // Parallax offset vector: where the ray has moved in uv when it reaches h = 0.
        const vec2 parallax = viewTS.xy / viewTS.z * depthScale;
#if HFX_TECHNIQUE == 2
        // Welsh: one fetch, the offset the height there would give, limited to the height (the
        // view vector's xy unscaled by 1/z), so grazing views do not swim.
        depthFraction = 1.0 - heightAt(uv0, searchLevel);
        const vec2 uvHit = uv0 - normalize(viewTS).xy * depthScale * depthFraction;
#elif HFX_TECHNIQUE == 6
        depthFraction = traceHierarchical(uv0, parallax);
        const vec2 uvHit = uv0 - parallax * depthFraction;
#else
        // Dynamic sample rate: more steps the more grazing the view.
        const int steps = clamp(int(mix(float(u_maxSamples), float(u_minSamples), cosView)), 1,
                                MAX_SAMPLES);
        float t0, t1, d0, d1;
        const bool hit = linearSearch(uv0, parallax, steps, searchLevel, t0, t1, d0, d1);
        if (!hit) {
            depthFraction = 1.0;
        } else if (t1 == 0.0) {
            depthFraction = 0.0;
        } else {
#if HFX_TECHNIQUE == 1
            // Intersect the ray with the segment between the last two samples (piecewise-linear
            // height profile) rather than taking the nearest sample.
            depthFraction = t0 + (t1 - t0) * d0 / (d0 - d1);
#elif HFX_TECHNIQUE == 3
            depthFraction = t1; // steep parallax: the first sample under the surface
#elif HFX_TECHNIQUE == 4
            // Relief mapping: halve the bracket 6 times, keep its middle.
            for (int i = 0; i < 6; ++i) {
                const float mid = 0.5 * (t0 + t1);
                if (heightAt(uv0 - parallax * mid, searchLevel) >= 1.0 - mid) t1 = mid;
                else t0 = mid;
            }
            depthFraction = 0.5 * (t0 + t1);
#elif HFX_TECHNIQUE == 5
            // Three secant steps inside the bracket, then the last secant estimate.
            for (int i = 0; i < 3; ++i) {
                const float tm = t0 + (t1 - t0) * d0 / (d0 - d1);
                const float dm = heightAt(uv0 - parallax * tm, searchLevel) - (1.0 - tm);
                if (dm >= 0.0) { t1 = tm; d1 = dm; } else { t0 = tm; d0 = dm; }
            }
            depthFraction = t0 + (t1 - t0) * d0 / (d0 - d1);
#endif
        }
        const vec2 uvHit = uv0 - parallax * depthFraction;
#endif
        // Level of detail: within one mip level of the threshold, fade the parallax out so the
        // change to normal mapping is not seen as a seam.
        const float blend = clamp(mipLevel - (u_lodThreshold - 1.0), 0.0, 1.0);
        uv = mix(uvHit, uv0, blend);
        depthFraction = mix(depthFraction, 0.0, blend);
    }
#endif

    // Silhouettes of finite patches: a ray that left the patch hit nothing of it.
    if (u_clipToPatch && (any(lessThan(uv, u_patchBounds.xy)) || any(greaterThan(uv, u_patchBounds.zw))))
        discard;

    const vec3 displacedTS = vec3(uv - uv0, -depthFraction * depthScale);
    const vec3 displacedWorld = v_worldPos + worldFromTexture * displacedTS;
#if HFX_TECHNIQUE >= 1
    // Depth of the displaced point, so geometry crossing the relief is clipped at the relief.
    // (Normal mapping keeps the polygon's depth and with it early depth testing.)
    const vec4 clip = u_viewProj * vec4(displacedWorld, 1.0);
    const float ndcDepth = clip.z / clip.w;
    gl_FragDepth = 0.5 * (gl_DepthRange.diff * ndcDepth + gl_DepthRange.near + gl_DepthRange.far);
#endif

    const vec4 surfaceSample = textureLod(s_surface, uv, mipLevel);
    const vec3 albedo = textureLod(s_albedo, uv, mipLevel).rgb;
    const vec3 tangentUnit = frameOk ? normalize(v_tangent) : vec3(0.0);
    const vec3 bitangentUnit = frameOk ? normalize(v_bitangent) : vec3(0.0);
    // The stored normal is that of z = normalDepth * h; the one of z = depthScale * h has its
    // slopes (x/z, y/z) scaled by their ratio: exact, so the material alone sets the depth.
    const vec3 decoded = surfaceSample.xyz * u_normalDecode.x + u_normalDecode.y;
    const vec3 storedNormal = vec3(decoded.xy * u_normalScale, decoded.z);
    const vec3 normal = normalize(tangentUnit * storedNormal.x + bitangentUnit * storedNormal.y +
                                  geometricNormal * storedNormal.z);
    const vec3 lightDir = normalize(u_lightDir);
    const float nDotL = dot(normal, lightDir);

    // Soft self-shadows: heights along the light ray from the displaced point; a blocker's
    // occlusion is its rise above the ray relative to the ray's own climb there, so a close
    // blocker (small climb) darkens sharply and a far one softly. Skipped facing away. Steep
    // parallax and relief mapping take the same samples as hard shadows (any blocker: dark).
    float lit = 1.0;
#if HFX_TECHNIQUE != 0 && HFX_TECHNIQUE != 2
    const vec3 lightTS = textureFromWorld * lightDir;
    const float h0 = 1.0 - depthFraction;
    if (u_shadows && lightTS.z > 0.0 && dot(geometricNormal, lightDir) > 0.0 && nDotL > 0.0 &&
        h0 < 1.0 && mipLevel <= u_lodThreshold && depthScale > 0.0) {
        const vec2 lightSpan = lightTS.xy / lightTS.z * depthScale * (1.0 - h0);
        const int samples = clamp(u_shadowSamples, 1, MAX_SHADOW_SAMPLES);
        float occlusion = 0.0;
        for (int i = 1; i <= MAX_SHADOW_SAMPLES; ++i) {
            if (i > samples) break;
            const float f = float(i) / float(samples + 1);
            const float rayHeight = h0 + f * (1.0 - h0);
            const float blocker = heightAt(uv + lightSpan * f, searchLevel) - rayHeight;
            occlusion = max(occlusion, blocker / (f * (1.0 - h0)));
        }
        // Fade in from the geometric terminator, where the N.L skip above would otherwise cut
        // from fully shadowed (grazing light) to unshadowed in one pixel.
#if HFX_TECHNIQUE == 3 || HFX_TECHNIQUE == 4
        const float shadow = occlusion > 0.0 ? 1.0 : 0.0;
#else
        const float shadow = clamp(occlusion * u_shadowSharpness, 0.0, 1.0);
#endif
        lit = 1.0 - shadow * smoothstep(0.0, 0.15, dot(geometricNormal, lightDir));
    }
#endif

    // Blinn-Phong on the offset texcoords.
    const vec3 viewDir = normalize(u_cameraPos - displacedWorld);
    const vec3 halfway = normalize(lightDir + viewDir);
    const float diffuse = max(nDotL, 0.0);
    const float specular = nDotL > 0.0 ? pow(max(dot(normal, halfway), 0.0), u_specularPower) : 0.0;
#if HFX_SHADING == 1
    // Water: the body colour deepens in the troughs, the sky is reflected by Schlick's Fresnel
    // weight, the sun leaves a sharp glint, and distance fades everything into the horizon.
    const vec3 body = mix(u_deepColor, u_shallowColor, surfaceSample.w * surfaceSample.w) *
                      (u_ambient + lit * diffuse * u_lightColor);
    vec3 reflected = reflect(-viewDir, normal);
    reflected.y = abs(reflected.y); // a ray reflected downwards sees the next wave's sky
    const float fresnel =
        u_fresnelF0 + (1.0 - u_fresnelF0) * pow(1.0 - clamp(dot(normal, viewDir), 0.0, 1.0), 5.0);
    const float glint = u_glintStrength * pow(max(dot(reflected, lightDir), 0.0), u_glintPower);
    vec3 color = mix(body, sky(reflected), fresnel) + lit * glint * u_lightColor;
    const float distance = length(u_cameraPos - displacedWorld);
    color = mix(color, u_skyHorizon, distance / (distance + u_hazeDistance));
#elif HFX_SHADING == 2
    // Planet: the sphere's own normal sets day and night (a soft terminator), the relief's
    // normal the detail; an atmosphere brightens the lit limb.
    const float day = smoothstep(-0.05, 0.3, dot(geometricNormal, lightDir));
    const float rim = 0.5 * pow(1.0 - cosView, 3.0) * day;
    vec3 color = albedo * u_ambient +
                 day * lit * u_lightColor * (albedo * diffuse + u_specularStrength * specular) +
                 rim * vec3(0.35, 0.55, 1.0) * u_lightColor;
#else
    const vec3 color = albedo * u_ambient +
                       lit * u_lightColor * (albedo * diffuse + u_specularStrength * specular);
#endif
    o_color = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
#if HFX_TRACE_OUTPUT
    // w: the fetch count in its integer part, the light (0..1) in half of its fraction.
    o_trace = vec4(uv, depthFraction, g_fetches + 0.5 * clamp(lit, 0.0, 0.998));
#endif
}
