#version 450 core
// Surface shading of a height field: the common part of every technique. Its parts, included
// below in this order (the renderer names the two slots):
//   surface/uniforms.glsl   the per-draw uniform block (hfx::SurfaceUniforms)
//   surface/heights.glsl    the height accessors over the surface texture and the pyramid
//   surface/shadowmap.glsl  receiving a light's shadow map (hfx::ShadowMap)
//   trace/common.glsl       ray, hit and shadow-ray types, the linear search, shadow occlusion
//   <tracer>                hfx_trace and hfx_shadow: trace/<technique>.glsl (trace/README.md)
//   shade/common.glsl       the shaded point
//   shade/sky.glsl          the sky (reflections, haze), its look's uniform block
//   <shading>               hfx_shade and hfx_emission: shade/<model>.glsl, one per shading
//                           model (lit, water, planet)
//   surface.frag            this file: the texture-space frame, level of detail, depth output
// Prepended #defines, from the C++ technique table (hfx::techniqueInfo) and the draw:
//   HFX_TRACES        1 when the technique displaces the texcoords (all but normal mapping):
//                     the view ray goes into texture space and gl_FragDepth is written
//   HFX_SELF_SHADOW   1 when it has self-shadows and the material asks for them (hfx_shadow is
//                     called)
//   HFX_LAYERS        1 to 4: the surface's layers (the ocean's cascades), summed in height and
//                     slope (surface/heights.glsl); 1 is an ordinary surface
//   HFX_TRACED_LAYERS 1 to HFX_LAYERS: the leading layers the tracers see; the rest only shade
//   HFX_RINGS         1 for water with impact rings (HfxRings) in height, slope and foam (the
//                     renderer picks it while WaterLook::ringCount > 0)
//   HFX_BOUNDED_SEARCH 1 when the searches are bounded by the layers' pyramids (surface/heights.glsl)
//   HFX_SHADOW_MAP    1 or 2 when the light's shadow maps are received, from a 2D or a 2D array
//                     texture (surface/shadowmap.glsl)
//   HFX_SHADOW_CASTER 1 = draw into a shadow map (hfx::ShadowMap's, or an engine's): the view
//                     is the light's (its eye's rays, u_viewProj), only the traced depth is
//                     written, nothing is shaded
//   HFX_BEAM_START    1 when the exact tracer's rays start where its beam prepass
//                     (trace/hier/beam.comp) found for their block of HFX_BEAM_BLOCK pixels
//                     (bindings.glsl)
//   HFX_TEXEL_SHADOWS 1 when the exact tracer's shadow is read from its texel shadows where they
//                     hold it (surface/shadow.glsl)
//   HFX_DEFERRED_SHADOWS 1 with HFX_TEXEL_SHADOWS: a light ray they do not hold is appended for the
//                     pass after the draw (trace/hier/deferred.glsl) instead of walked here
//   HFX_COMPUTE_TRACE 1 or 2: the exact tracer's walks in a compute pass between two draws
//                     (trace/hier/trace.glsl): 1 = the rays draw, which stores each pixel's view ray
//                     and shades nothing; 2 = the shading draw, which reads the hit and its shadow
//   HFX_TRACE_LIGHTS  1: the rays draw stores each pixel's light ray too (the light is not one for
//                     the draw: a curved mesh, a silhouette fade)
//   HFX_SKY           the sky the water reflects (hfx::SkyKind, shade/sky.glsl): 0 a gradient, 1 with
//                     clouds (WaterLook::cloudCover) and their shadows, 2 an equirectangular image
//                     (WaterLook::environment); 0 where nothing is shaded (a caster, the rays draw)
//   HFX_REVERSED_Z    1 for a reversed-Z camera (hfx::Camera::reversedZ): the traced depth is
//                     written for GL's [0, 1] clip depth, drawn with GL_GREATER
//   HFX_PYRAMID_ATLAS 1 on llvmpipe: the pyramids in one image each (surface/heights.glsl,
//                     GlWorkarounds::pyramidAtlas); the only define a device picks
//   HFX_TRACE_OUTPUT  1 = also write (u, v, depth fraction, fetches + lit / 2) of the hit to
//                     output 1: the height fetches counted in the integer part, the self-shadow
//                     light factor (0 = shadowed) as twice the fraction; and to output 2 the
//                     texcoords the ray entered at, as the rasteriser interpolated them
//   HFX_MOTION_OUTPUT 1 to 7: the output (draw buffer) the traced point's screen motion since the
//                     previous frame goes to (hfx::SurfaceRenderer::setMotionOutput); 0 none
//   HFX_NORMAL_OUTPUT, HFX_ALBEDO_OUTPUT, HFX_MATERIAL_OUTPUT, HFX_EMISSION_OUTPUT 1 to 7: the
//                     outputs a deferred engine's lighting reads (hfx::SurfaceOutputs); 0 none
//   HFX_TRIPLANAR     1: the texcoords and frame come from the mesh's own position projected
//                     along each of its axes, each projection with a weight traced and shaded,
//                     the results blended (hfx::TriplanarMapping); 0: the mesh's texcoords
// Switches are defines (hfx::SurfaceVariant), not uniforms: llvmpipe runs both sides of a branch,
// even one on a uniform, so a feature switched off by a uniform still costs its fetches.
//
// Conventions: s_surface holds the tangent-space normal in xyz and the height h in w, h = 1 at the
// polygon and 0 at the deepest point, u_depthScale texture units below it. Texture space has
// x = u, y = v and z along the normal, one unit = one texture repeat.

#ifndef HFX_TRACES
#define HFX_TRACES 1
#endif
#ifndef HFX_SELF_SHADOW
#define HFX_SELF_SHADOW 1
#endif
#ifndef HFX_TRACE_OUTPUT
#define HFX_TRACE_OUTPUT 0
#endif
#ifndef HFX_MOTION_OUTPUT
#define HFX_MOTION_OUTPUT 0
#endif
#ifndef HFX_NORMAL_OUTPUT
#define HFX_NORMAL_OUTPUT 0
#endif
#ifndef HFX_ALBEDO_OUTPUT
#define HFX_ALBEDO_OUTPUT 0
#endif
#ifndef HFX_MATERIAL_OUTPUT
#define HFX_MATERIAL_OUTPUT 0
#endif
#ifndef HFX_SHADOW_CASTER
#define HFX_SHADOW_CASTER 0
#endif
#ifndef HFX_BEAM_START
#define HFX_BEAM_START 0
#endif
#ifndef HFX_DEFERRED_SHADOWS
#define HFX_DEFERRED_SHADOWS 0
#endif
#ifndef HFX_COMPUTE_TRACE
#define HFX_COMPUTE_TRACE 0
#endif
#ifndef HFX_REVERSED_Z
#define HFX_REVERSED_Z 0
#endif
#ifndef HFX_TRIPLANAR
#define HFX_TRIPLANAR 0
#endif
#if HFX_TRIPLANAR && (HFX_TEXEL_SHADOWS || HFX_BEAM_START || HFX_LAYERS > 1)
#error "HFX_TRIPLANAR traces each projection in its own frame: not with the texel shadows, the beam start or layers"
#endif
#if HFX_COMPUTE_TRACE && (HFX_DEFERRED_SHADOWS || !HFX_TRACES)
#error "HFX_COMPUTE_TRACE walks the view rays in a compute pass: not with HFX_DEFERRED_SHADOWS, only for a tracer"
#endif
#if HFX_DEFERRED_SHADOWS && (HFX_TRACE_OUTPUT || HFX_SHADOW_CASTER || !HFX_TEXEL_SHADOWS)
#error "HFX_DEFERRED_SHADOWS defers the walks HFX_TEXEL_SHADOWS leave, of a drawn colour: not with HFX_TRACE_OUTPUT or HFX_SHADOW_CASTER"
#endif
#if HFX_TRACES
// Conservative depth: the hit lies on the view ray at or behind the polygon, so the depth written
// is never less than the fragment's own (clamped to it against rounding, and for parallax
// mapping's offset-limited point). A GPU then keeps its early and hierarchical depth tests
// against what is already drawn, where a plain gl_FragDepth write turns them off. The renderer
// draws with GL_LESS, which needs a depth range whose near lies below its far; a reversed-Z view
// (HFX_REVERSED_Z) with GL_GREATER, its traced depth never greater.
#if HFX_REVERSED_Z
layout(depth_less) out float gl_FragDepth;
#else
layout(depth_greater) out float gl_FragDepth;
#endif
#endif

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/heights.glsl"
#include "surface/shadowmap.glsl"
#include "trace/common.glsl"
#include <tracer>
#if HFX_DEFERRED_SHADOWS
#include "trace/hier/deferred.glsl"
#endif
#include "surface/shadow.glsl"
#if HFX_COMPUTE_TRACE
#include "trace/hier/trace.glsl"
#endif
#if HFX_COMPUTE_TRACE == 1
// Only the fragments that pass the depth test store their ray (and the draw writes no depth).
layout(early_fragment_tests) in;
#endif
#include "shade/common.glsl"
#include "shade/sky.glsl"
#include <shading>

in vec3 v_worldPos;
in vec3 v_normal;
in vec3 v_tangent;
in vec3 v_bitangent;
in vec2 v_texcoord;
#if HFX_TRIPLANAR
in vec3 v_objectPos;    // the mesh's own position
in vec3 v_objectNormal; // and normal
#endif

layout(location = 0) out vec4 o_color;
#if HFX_TRACE_OUTPUT
layout(location = 1) out vec4 o_trace;
layout(location = 2) out vec2 o_entry;
#endif
#if HFX_MOTION_OUTPUT
layout(location = HFX_MOTION_OUTPUT) out vec2 o_motion;
#endif
#if HFX_NORMAL_OUTPUT
layout(location = HFX_NORMAL_OUTPUT) out vec4 o_normal;
#endif
#if HFX_ALBEDO_OUTPUT
layout(location = HFX_ALBEDO_OUTPUT) out vec4 o_albedo;
#endif
#if HFX_MATERIAL_OUTPUT
layout(location = HFX_MATERIAL_OUTPUT) out vec4 o_material;
#endif
#ifndef HFX_EMISSION_OUTPUT
#define HFX_EMISSION_OUTPUT 0
#endif
#if HFX_EMISSION_OUTPUT
layout(location = HFX_EMISSION_OUTPUT) out vec4 o_emission;
#endif

layout(binding = HFX_UNIT_ALBEDO) uniform sampler2D s_albedo;
// Layer 0's shading channels: roughness, ambient occlusion, (reserved), heat.
layout(binding = HFX_UNIT_CHANNELS) uniform sampler2D s_channels;
#if HFX_BEAM_START
layout(binding = HFX_UNIT_BEAM_START) uniform sampler2D s_beamStart;
#endif
#if HFX_LAYERS > 1
layout(binding = HFX_UNIT_ALBEDO1) uniform sampler2D s_albedo1;
#endif
#if HFX_LAYERS > 2
layout(binding = HFX_UNIT_ALBEDO2) uniform sampler2D s_albedo2;
#endif
#if HFX_LAYERS > 3
layout(binding = HFX_UNIT_ALBEDO3) uniform sampler2D s_albedo3;
#endif

// Toksvig: the mip-averaged unit normals shorten where the slopes they average differ; the
// shortening estimates the variance of those slopes (in the stored normal's own units), less
// what the storage format's rounding alone shows.
float hfx_slope_variance(vec3 averaged) {
    const float len = max(length(averaged), 1e-3);
    return max((1.0 - len) / len - u_varianceFloor, 0.0);
}

#if HFX_LAYERS > 1
// One layer's share of the shaded point: its slopes (the normal's x/z, y/z, in its own
// texcoords and depth, turned into the surface's by slopeShare) and their variance, its height;
// and, returned, its own height and its albedo's alpha and red (the ocean's foam of that layer
// and the foam's young part).
vec3 hfx_add_layer(sampler2D s, sampler2D a, vec2 uv, float level, float scale, float weight,
                   float slopeShare, inout vec2 slope, inout float variance, inout float height) {
    const vec4 t = textureLod(s, uv * scale, level);
    const vec3 n = t.xyz * u_normalDecode.x + u_normalDecode.y;
    slope += slopeShare * n.xy / max(n.z, 1e-3);
    variance += slopeShare * slopeShare * hfx_slope_variance(n);
    height += weight * t.w;
    const vec4 albedo = textureLod(a, uv * scale, level);
    return vec3(t.w, albedo.a, albedo.r);
}
#endif

// The search and shadow fetches read one mip level, the nearest to the level that the
// undisplaced texcoords' gradients select: computed once, so the level does not jump where the
// traced texcoords jump (silhouettes of the relief), and one level means the ray meets one
// bilinear surface, cheaper than a trilinear textureGrad fetch (about 1.5x the POM
// draw on llvmpipe). Shading fetches keep trilinear filtering.

// The pixel budget (u_pixelBudget > 0) picks the tracers' effort from the screen. A texcoord
// offset v at the polygon covers |J^-1 v| pixels, J the pixel's texcoord derivatives (dx, dy per
// pixel); the relief lies farther from the eye, where the same offset covers fewer, so what holds
// at the polygon holds there too. Returns 0 where there is no budget, the derivatives are
// degenerate, or in the shadow map (its texels are no screen pixels): the caller then does the
// full work.
float hfx_screen_pixels(vec2 v, vec2 dx, vec2 dy) {
#if HFX_SHADOW_CASTER
    return 0.0;
#else
    return u_pixelBudget > 0.0 ? hfx_screen_length(v, dx, dy) : 0.0;
#endif
}

// The sampled tracers' steps under the budget: no more than keep each step within the budget on
// the screen (the whole ray, or light ray, spans `pixels`), never more than the caller's count.
int hfx_budget_samples(int samples, float pixels) {
    return pixels > 0.0 ? clamp(int(ceil(pixels / u_pixelBudget)), 1, samples) : samples;
}

// The mip level that covers what the pixel shows of the surface: its entry's (`entryLevel`, from
// the polygon's texcoords), or where the traced hits of neighbouring pixels lie further apart (a
// crest's or a wall's silhouette, a slope seen edge on) the hits' spread, up to
// HFX_FOOTPRINT_LEVELS above. Read there, the normals' variance (Toksvig) spreads a glint over
// the pixel's share of the surface, where a texel's glint, or its reflection of the horizon, lit
// or missed the pixel by chance and flickered as the view moved (a rough sea's crests at middle
// distance: OceanShading's footprint test). dx, dy: the hits' texcoords' derivatives, in texels.
// `texelAspect`: the texels' shorter side on the surface over their longer (1 on a plane; a
// sphere's cos(latitude)). Near a pole, where the frame degenerates, the hits of neighbouring
// pixels lie far apart in u though close on the surface: there the levels above the entry's fade
// out (from a tenth to a fiftieth), or the shading read texels that average the bands round the
// pole into a dark dot (history/tuning.md, the planet's poles).
const float HFX_FOOTPRINT_LEVELS = 3.0;
float hfx_shade_level(float entryLevel, vec2 dx, vec2 dy, float texelAspect) {
    const float hitLevel = hfx_level_of(dx, dy);
    return clamp(hitLevel, entryLevel, entryLevel + HFX_FOOTPRINT_LEVELS * smoothstep(0.02, 0.1, texelAspect));
}

// The polygon's texture space from the world's (the identity for a degenerate frame, whose
// depth scale is 0 and which is normal mapped).
mat3 hfx_texture_from_world(bool frameOk, mat3 worldFromTexture) {
    return frameOk ? inverse(worldFromTexture) : mat3(1.0);
}

// The parallax offset vector: where the view ray (towards the eye, in texture space) has moved in
// uv when it reaches h = 0; none for a ray from below the surface.
vec2 hfx_parallax(vec3 viewTS, float depthScale) {
    return viewTS.z > 0.0 ? viewTS.xy / viewTS.z * depthScale : vec2(0.0);
}

// The texture frame a pixel is traced and shaded in: the mesh's (its texcoords and tangent frame),
// or one projection of a triplanar mapping.
struct HfxFrame {
    vec2 uv0;                // the texcoords at the polygon
    vec2 dx, dy;             // their derivatives across the screen, per pixel
    vec3 tangent, bitangent; // dP/du, dP/dv, world space
    int plane;               // the compute pass's plane of slots: a triplanar projection's axis, else 0
    bool decides;            // its slot says whether the pixel was drawn: the mesh's, the heaviest projection's
};

#if HFX_TRIPLANAR
// Triplanar mapping (hfx::TriplanarMapping). Projection `axis` makes the texcoords from the mesh's
// own position along the two other axes, u_triplanarScale per unit: x (y, z), y (x, -z), z (x, y),
// u negated on a face turned to the axis's negative side, so that T x B points out of every face
// and none reads its texture mirrored (+y's is makePlane's). Its frame, dP/du and dP/dv: the
// directions along the surface (n . t = 0) that move the projected point by one texcoord. A weight
// is 0 where |n_axis| is under the dead zone, so no frame divides by less than it.
const float HFX_TRIPLANAR_DEAD_ZONE = 0.3;
HfxFrame hfx_projected_frame(int axis, vec3 n, vec3 dpdx, vec3 dpdy) {
    const float side = n[axis] < 0.0 ? -1.0 : 1.0;
    const vec3 ea = vec3(equal(ivec3(axis), ivec3(0, 1, 2)));
    const vec3 eu = axis == 0 ? vec3(0.0, side, 0.0) : vec3(side, 0.0, 0.0);
    const vec3 ev = axis == 0 ? vec3(0.0, 0.0, 1.0) : axis == 1 ? vec3(0.0, 0.0, -1.0) : vec3(0.0, 1.0, 0.0);
    HfxFrame f;
    f.uv0 = u_triplanarScale * vec2(dot(eu, v_objectPos), dot(ev, v_objectPos));
    f.dx = u_triplanarScale * vec2(dot(eu, dpdx), dot(ev, dpdx));
    f.dy = u_triplanarScale * vec2(dot(eu, dpdy), dot(ev, dpdy));
    const mat3 model = mat3(u_model);
    f.tangent = model * (eu - dot(n, eu) / n[axis] * ea) / u_triplanarScale;
    f.bitangent = model * (ev - dot(n, ev) / n[axis] * ea) / u_triplanarScale;
    f.plane = axis;
    f.decides = false; // (main: true for the heaviest)
    return f;
}
#endif

#if HFX_TRACES
// The depth a traced point writes, so geometry crossing the relief is clipped at the relief.
// (Normal mapping keeps the polygon's depth and with it early depth testing.)
float hfx_depth_of(vec3 position) {
    const vec4 clip = u_viewProj * vec4(position, 1.0);
    const float ndcDepth = clip.z / clip.w;
#if HFX_REVERSED_Z
    // GL's [0, 1] clip depth (GL_ZERO_TO_ONE), nearer greater.
    const float hitDepth = gl_DepthRange.diff * ndcDepth + gl_DepthRange.near;
    return min(hitDepth, gl_FragCoord.z);
#else
    const float hitDepth = 0.5 * (gl_DepthRange.diff * ndcDepth + gl_DepthRange.near + gl_DepthRange.far);
    return max(hitDepth, gl_FragCoord.z);
#endif
}
#endif

// What a pixel's trace and shading in one frame give its outputs (main writes them; the depth
// hfx_surface writes, but for a triplanar mapping's blend).
struct HfxShaded {
    vec3 color;    // linear radiance
    vec3 position; // the traced point, world space (its depth, its motion)
    vec4 normal;   // the shading normal, the slopes' variance (hfx::SurfaceOutputs)
    vec4 albedo;   // the albedo, layer 0's alpha (the foam where an effect writes it)
    vec4 material; // roughness, ambient occlusion, the self-shadow's light, the height
    vec3 emission; // the light the point emits itself, linear (the shading model's hfx_emission)
    vec4 trace;    // the hit's texcoords, its depth fraction, the light (HFX_TRACE_OUTPUT)
    vec2 entry;    // the texcoords the ray entered at
};
const HfxShaded HFX_UNSHADED = HfxShaded(vec3(0.0), vec3(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec3(0.0), vec4(0.0),
                                          vec2(0.0));

// The pixel traced and shaded in frame `f`. Called in uniform control flow, but for a triplanar
// mapping's projections, whose branches take no derivatives (below).
HfxShaded hfx_surface(HfxFrame f) {
    HfxShaded s = HFX_UNSHADED;
    // The polygon's frame, for the view ray (after the walk: geometricNormal, worldFromTexture).
    const vec3 entryNormal = normalize(v_normal);
    const mat3 entryFrame = hfx_world_from_texture(entryNormal, f.tangent, f.bitangent);
    const vec3 toEye = hfx_to_eye(v_worldPos); // (a caster's eye: its light's)
    const float cosView = clamp(dot(entryNormal, normalize(toEye)), 0.0, 1.0);
    // A degenerate frame (a sphere's poles, where dP/du vanishes) has no texture space: there the
    // surface is normal mapped. Silhouettes of curved meshes fade the relief out.
    const bool frameOk = length(f.tangent) > 1e-3 * length(f.bitangent) &&
                         length(f.bitangent) > 1e-3 * length(f.tangent);
    const float depthScale =
        frameOk ? u_depthScale * (u_silhouetteFade > 0.0 ? smoothstep(0.0, u_silhouetteFade, cosView) : 1.0)
                : 0.0;
#if HFX_TRACES
    const mat3 textureFromWorld = hfx_texture_from_world(frameOk, entryFrame);
    const vec3 viewTS = textureFromWorld * toEye;
    const vec2 parallax = hfx_parallax(viewTS, depthScale);
#if HFX_SELF_SHADOW
    // The light in texture space, here: the inverse frame (nine registers) then dies before the
    // view walk instead of living through it (below, the frame after the walk).
    const vec3 lightTS = textureFromWorld * normalize(u_lightDir);
#endif
#endif

    const vec2 uv0 = f.uv0, dx = f.dx, dy = f.dy;
    const vec2 texels = vec2(hfx_size());
    const vec2 dxTexels = dx * texels, dyTexels = dy * texels;
    const float mipLevel = hfx_level_of(dxTexels, dyTexels);
    const float searchLevel = max(round(mipLevel), 0.0);

    vec2 uv = uv0;
    float depthFraction = 0.0; // of u_depthScale, along the view ray, at the hit
#if HFX_COMPUTE_TRACE
    const int slot = hfx_trace_slot(ivec2(gl_FragCoord.xy), f.plane);
#endif
#if HFX_COMPUTE_TRACE == 1
    uvec2 traceInfo = uvec2(0u, hfx_trace_mark(false)); // normal mapped, unless traced below
#elif HFX_COMPUTE_TRACE == 2
    // The walks pass's hit (the ray this pixel's fragment of the rays draw stored): 1 where the slot
    // holds this draw's traced ray, 2 where it holds this draw's normal-mapped pixel or the
    // fragment is a back face's (it stored none: normal mapped), 0 where it holds neither (a
    // helper lane past the mesh's edge, below; on llvmpipe every helper lane, whose loads return
    // zeros: a GPU's helper lane where a quad straddles two triangles reads the other's hit).
    const uvec2 traceInfo = hfx_traceInfo[slot];
    const uint mark = traceInfo.y & 0xffff0000u;
    const uint computed = !gl_FrontFacing              ? 2u
                          : mark == hfx_trace_mark(true)  ? 1u
                          : mark == hfx_trace_mark(false) ? 2u
                                                          : 0u;
    float computedShadow = -1.0; // the walks' self-shadow before the fade, -1: none walked
    if (computed == 1u) {
        const vec4 hit = hfx_traceRays[slot];
        uv = hit.xy;
        depthFraction = hit.z;
        computedShadow = hit.w;
        g_fetches += float(traceInfo.x);
    }
#endif

#if HFX_TRACES
    if (mipLevel <= u_lodThreshold && viewTS.z > 0.0 && depthScale > 0.0) {
        HfxRay ray;
        ray.uv = uv0;
        ray.parallax = parallax;
        ray.cosTheta = normalize(viewTS).z;
        ray.level = searchLevel;
        // Dynamic sample rate: more steps the more grazing the view.
        ray.samples = clamp(int(mix(float(u_maxSamples), float(u_minSamples), cosView)), 1, HFX_MAX_SAMPLES);
        // The budget: hier stops short of the hit by at most its share of the ray's screen length
        // (a depth fraction dt moves the point shown by parallax * dt), the searches take no more
        // steps than keep each within it.
        const float rayPixels = hfx_screen_pixels(ray.parallax, dx, dy);
        ray.tolerance = rayPixels > 0.0 ? u_pixelBudget / rayPixels : 0.0;
        ray.samples = hfx_budget_samples(ray.samples, rayPixels);
#if HFX_BEAM_START
        ray.start = texelFetch(s_beamStart, ivec2(gl_FragCoord.xy) / HFX_BEAM_BLOCK, 0).r;
#else
        ray.start = 0.0;
#endif
        // Level of detail: within one mip level of the threshold, fade the parallax out so the
        // change to normal mapping is not seen as a seam.
        const float blend = clamp(mipLevel - (u_lodThreshold - 1.0), 0.0, 1.0);
#if HFX_COMPUTE_TRACE == 1
        // The light ray is walked where the shading draw's test below holds at the entry (the
        // walks pass tests the hit's height).
        bool walksLight = false;
#if HFX_SELF_SHADOW && !HFX_SHADOW_CASTER // (a caster's pass walks no light ray: it shades nothing)
        walksLight = lightTS.z > 0.0 && dot(entryNormal, normalize(u_lightDir)) > 0.0;
#if HFX_TRACE_LIGHTS
        if (walksLight) hfx_traceLights[slot] = lightTS.xy / lightTS.z * depthScale;
#endif
#endif
        traceInfo = uvec2(floatBitsToUint(ray.tolerance) | (walksLight ? HFX_TRACE_WALKS_LIGHT : 0u),
                          hfx_trace_mark(true) | (packUnorm2x16(vec2(blend, 0.0)) & 0xffffu));
        hfx_traceRays[slot] = vec4(ray.uv, ray.parallax);
#elif HFX_COMPUTE_TRACE == 2
        // (The walks pass's hit, read above.)
#else
        const HfxHit hit = hfx_trace(ray);
        uv = mix(hit.uv, uv0, blend);
        depthFraction = mix(hit.depth, 0.0, blend);
#endif
    }
#endif
#if HFX_COMPUTE_TRACE == 1
    hfx_traceInfo[slot] = traceInfo;
    return s; // the walks pass takes it from here
#elif HFX_COMPUTE_TRACE == 2 && !HFX_TRIPLANAR
    // A helper lane past the mesh's edge has no slot. The hits' spread below (the shading's level)
    // needs its hit: its own ray at the depth of a quad neighbour that has one, across, else
    // above or below (a lane of a 2x2 quad at even window coordinates finds its neighbour's value
    // from the difference and which side it is on). Walking it here would cost this program the
    // walk's registers. (A triplanar projection's spread is its entry's: its lane needs none.)
    const float known = computed != 0u ? 1.0 : 0.0, knownDepth = known * depthFraction;
    const bool left = (int(gl_FragCoord.x) & 1) == 0, below = (int(gl_FragCoord.y) & 1) == 0;
    const vec2 acrossKnown = vec2(dFdxFine(known), dFdxFine(knownDepth)) * (left ? 1.0 : -1.0);
    const vec2 upKnown = vec2(dFdyFine(known), dFdyFine(knownDepth)) * (below ? 1.0 : -1.0);
    if (computed == 0u) {
        const float t = known + acrossKnown.x > 0.5 ? knownDepth + acrossKnown.y
                        : known + upKnown.x > 0.5   ? knownDepth + upKnown.y
                                                    : 0.0;
        depthFraction = t;
        // The view in texture space, turned here, where only such a lane needs it: a warp
        // without one skips the inverse frame (RDNA2: 498 instructions outside this branch, 566
        // when every lane turned it; scripts/gpu_compiler_stats.py). The light needs no turn in
        // this draw (its self-shadow, below).
        uv = uv0 - hfx_parallax(hfx_texture_from_world(frameOk, entryFrame) * toEye, depthScale) * t;
    }
#endif

#if HFX_TRACES && defined(HFX_FRAME_AFTER_TRACE) && !HFX_TRIPLANAR
    // After a tracer that asks for it (hier's walk), the polygon's frame and position are
    // interpolated again (interpolateAtOffset at offset 0: the pixel centre's values, a few
    // instructions) instead of kept through the walk. A GPU's compiler then holds fewer vector
    // registers across it, and a SIMD more waves to hide its fetches: with the light turned
    // before the walk and the walk carrying no more than its start (HfxWalk), hier's fragment
    // shader needs 56 where it needed 72 on RDNA2 (AMD's compiler, scripts/gpu_compiler_stats.py;
    // docs/BENCHMARKS.md). POM's search holds few registers: it keeps the frame (48 either way).
    const vec3 position = interpolateAtOffset(v_worldPos, vec2(0.0));
    const vec3 geometricNormal = normalize(interpolateAtOffset(v_normal, vec2(0.0)));
    const vec3 tangent = interpolateAtOffset(v_tangent, vec2(0.0));
    const vec3 bitangent = interpolateAtOffset(v_bitangent, vec2(0.0));
    const mat3 worldFromTexture = hfx_world_from_texture(geometricNormal, tangent, bitangent);
#else
    const vec3 position = v_worldPos, geometricNormal = entryNormal, tangent = f.tangent, bitangent = f.bitangent;
    const mat3 worldFromTexture = entryFrame;
#endif

    // The traced hits' spread to the next pixel (derivatives: here, in uniform control flow; a
    // triplanar projection's branch takes none, and the entry's spread stands for its hits'). Fine
    // ones, as every derivative here: dFdx leaves fine or coarse to the driver, and a coarse one
    // would give the four pixels of a quad one shading level.
#if HFX_TRIPLANAR
    const vec2 hitDx = dx, hitDy = dy;
#else
    const vec2 hitDx = dFdxFine(uv), hitDy = dFdyFine(uv);
#endif
    // The texels' sides on the surface squared, both times (texels.x * texels.y)^2: their ratio is
    // all that counts. Dividing by texels held 1/texels in two registers through the layers'
    // reads, and the sides' lengths shared the frame check's square roots, held through the
    // search (RDNA2: the ocean's program 66 registers, 12 waves a SIMD; POM's without
    // self-shadows 20, the triplanar mappings' 12 and 8: docs/BENCHMARKS.md).
    const float tangentTexel = dot(tangent, tangent) * texels.y * texels.y;
    const float bitangentTexel = dot(bitangent, bitangent) * texels.x * texels.x;
    const float texelAspect = sqrt(min(tangentTexel, bitangentTexel) / max(max(tangentTexel, bitangentTexel), 1e-30));
    const float shadeLevel = hfx_shade_level(mipLevel, hitDx * texels, hitDy * texels, texelAspect);
    const float footprint = max(length(hitDx), length(hitDy));

#if HFX_COMPUTE_TRACE == 2
    // A fragment whose slot holds no ray of this draw's failed the rays draw's depth test at the
    // polygon: its hit lies behind what is there (its depth here passed by a rounding). A
    // triplanar mapping's heaviest projection says so for the pixel; another's slot may hold none
    // where the rays draw, another program, weighed it 0 and this one a rounding above (a weight
    // at the dead zone's edge): it is normal mapped, its weight next to nothing.
    if (computed == 0u && f.decides) discard;
#endif
    // Silhouettes of finite patches: a ray that left the patch hit nothing of it.
    if (u_clipToPatch != 0 && (any(lessThan(uv, u_patchBounds.xy)) || any(greaterThan(uv, u_patchBounds.zw))))
        discard;

    const vec3 displacedTS = vec3(uv - uv0, -depthFraction * depthScale);
    const vec3 displacedWorld = position + worldFromTexture * displacedTS;
    s.position = displacedWorld;
#if HFX_TRACES && !HFX_TRIPLANAR
    gl_FragDepth = hfx_depth_of(displacedWorld); // (here: a deferred light walk records it)
#endif
#if HFX_SHADOW_CASTER
    return s; // the map holds the traced depth; nothing to shade
#endif

#if HFX_LAYERS == 1
    const vec4 surfaceSample = textureLod(s_surface, uv, shadeLevel);
    const vec4 albedoSample = textureLod(s_albedo, uv, shadeLevel);
    const vec3 albedo = albedoSample.rgb;
    const float alpha = albedoSample.a;
    // The stored normal is that of z = normalDepth * h; the one of z = depthScale * h has its
    // slopes (x/z, y/z) scaled by their ratio: exact, so the material alone sets the depth.
    const vec3 decoded = surfaceSample.xyz * u_normalDecode.x + u_normalDecode.y;
    const vec3 storedNormal = vec3(decoded.xy * u_normalScale, decoded.z);
    const float slopeVariance = u_normalScale * u_normalScale * hfx_slope_variance(decoded);
    const float height = surfaceSample.w;
    const vec4 layerFoam = vec4(alpha, 0.0, 0.0, 0.0), layerDetail = vec4(height, 0.5, 0.5, 0.5);
    const vec4 layerYoung = vec4(min(albedo.r, alpha), 0.0, 0.0, 0.0);
#else
    // Slopes add: each layer's, scaled to the surface's texcoords and depth (u_layerSlope), and
    // so do their variances (independent layers).
    vec2 slope = vec2(0.0);
    float slopeVariance = 0.0, height = 0.0;
    vec3 l0 = hfx_add_layer(s_surface, s_albedo, uv, shadeLevel + u_layerLevel.x, u_layerScale.x, u_layerWeight.x,
                            u_layerSlope.x, slope, slopeVariance, height);
    vec3 l1 = hfx_add_layer(s_surface1, s_albedo1, uv, shadeLevel + u_layerLevel.y, u_layerScale.y, u_layerWeight.y,
                            u_layerSlope.y, slope, slopeVariance, height);
    vec3 l2 = vec3(0.5, 0.0, 0.0), l3 = vec3(0.5, 0.0, 0.0);
#if HFX_LAYERS > 2
    l2 = hfx_add_layer(s_surface2, s_albedo2, uv, shadeLevel + u_layerLevel.z, u_layerScale.z, u_layerWeight.z,
                       u_layerSlope.z, slope, slopeVariance, height);
#endif
#if HFX_LAYERS > 3
    l3 = hfx_add_layer(s_surface3, s_albedo3, uv, shadeLevel + u_layerLevel.w, u_layerScale.w, u_layerWeight.w,
                       u_layerSlope.w, slope, slopeVariance, height);
#endif
    // Each layer's foam is broken up by the relief of the next two finer layers (the finest by
    // its own): a lace of two scales rather than the blobs of one.
    const vec4 layerFoam = vec4(l0.y, l1.y, l2.y, l3.y);
    const vec4 layerYoung = min(vec4(l0.z, l1.z, l2.z, l3.z), layerFoam);
    const float d2 = HFX_LAYERS > 2 ? l2.x : l1.x, d3 = HFX_LAYERS > 3 ? l3.x : d2;
    const vec4 layerDetail = vec4(l1.x + 0.7 * (d2 - 0.5), d2 + 0.7 * (d3 - 0.5), d3, d3);
    const vec3 storedNormal = vec3(slope, 1.0);
    const vec3 albedo = textureLod(s_albedo, uv * u_layerScale.x, shadeLevel + u_layerLevel.x).rgb;
#endif
#if HFX_RINGS
    // The impact rings: their slope (slope form: x/z, y/z of the normal) and foam on top.
    // (This variant is drawn only while a ring lives: WaterLook::ringCount > 0.)
    const vec4 rings = hfx_rings(uv);
    vec3 ringNormal = storedNormal;
    ringNormal.xy -= depthScale * rings.yz * storedNormal.z;
    // Their foam is young: a splash's.
    vec4 ringFoam = layerFoam, ringYoung = layerYoung;
    ringFoam.x = max(ringFoam.x, rings.w);
    ringYoung.x = max(ringYoung.x, rings.w);
#define HFX_SHADED_NORMAL ringNormal
#define HFX_SHADED_FOAM ringFoam
#define HFX_SHADED_YOUNG ringYoung
#else
#define HFX_SHADED_NORMAL storedNormal
#define HFX_SHADED_FOAM layerFoam
#define HFX_SHADED_YOUNG layerYoung
#endif
    const vec3 tangentUnit = frameOk ? normalize(tangent) : vec3(0.0);
    const vec3 bitangentUnit = frameOk ? normalize(bitangent) : vec3(0.0);
    const vec3 normal = normalize(tangentUnit * HFX_SHADED_NORMAL.x + bitangentUnit * HFX_SHADED_NORMAL.y +
                                  geometricNormal * HFX_SHADED_NORMAL.z);
    const vec3 lightDir = normalize(u_lightDir);
    const float nDotL = dot(normal, lightDir);

    // Self-shadows: the technique's, from the displaced point towards the light, skipped where the
    // polygon faces away, and faded in from the geometric terminator, where that skip would
    // otherwise cut from fully shadowed (grazing light) to unshadowed in one pixel. Not skipped
    // where the shading normal faces away: it is smoothed over texels (Sobel, mip levels), so at
    // the foot of a wall it turns away while the light ray, traced, still meets the wall.
    float lit = 1.0;
    int deferred = -1; // where the light walk left to the pass after the draw is (HFX_DEFERRED_SHADOWS)
#if HFX_SELF_SHADOW && HFX_COMPUTE_TRACE == 2
    // The walks pass walked the light ray where the test in the branch below held (the rays
    // draw's flag and its hit's height) and left -1 elsewhere: its shadow alone says it, without
    // the light turned into texture space here.
    lit = 1.0 - max(computedShadow, 0.0) * smoothstep(0.0, 0.15, dot(geometricNormal, lightDir));
#elif HFX_SELF_SHADOW
    const float h0 = 1.0 - depthFraction;
    if (lightTS.z > 0.0 && dot(geometricNormal, lightDir) > 0.0 && h0 < 1.0 &&
        mipLevel <= u_lodThreshold && depthScale > 0.0) {
        HfxShadowRay shadowRay;
        shadowRay.uv = uv;
        shadowRay.h0 = h0;
        shadowRay.span = lightTS.xy / lightTS.z * depthScale * (1.0 - h0);
        shadowRay.level = searchLevel;
        // On the screen the light ray runs from the point to its top: a point (x, h) shows where the
        // view ray through x + parallax * (1 - h) does, so its extent is span - parallax * (1 - h0).
        shadowRay.samples = hfx_budget_samples(u_shadowSamples, hfx_screen_pixels(shadowRay.span - parallax * (1.0 - h0), dx, dy));
        shadowRay.sharpness = u_shadowSharpness;
        const float fade = smoothstep(0.0, 0.15, dot(geometricNormal, lightDir));
        lit = 1.0 - hfx_surface_shadow(shadowRay, fade, deferred) * fade;
    }
#endif
    const float selfLit = lit;

    // Other geometry's shadow (and the relief's own at a distance, through the map's rounding).
    const float mapLit = hfx_shadow_map(displacedWorld, geometricNormal);
    lit *= mapLit;

    HfxSurfacePoint point;
    point.albedo = albedo;
    point.normal = normal;
    point.geometricNormal = geometricNormal;
    point.position = displacedWorld;
    point.texcoord = uv;
    point.footprint = footprint;
    point.viewDir = normalize(hfx_to_eye(displacedWorld));
    point.lightDir = lightDir;
    point.height = height;
    point.lit = lit;
    point.cosView = cosView;
    point.diffuse = max(nDotL, 0.0);
    // Toksvig: the lobe widens with the slopes' variance and keeps its energy.
    point.slopeVariance = slopeVariance;
    point.foam = HFX_SHADED_FOAM;
    point.foamYoung = HFX_SHADED_YOUNG;
    point.foamDetail = layerDetail;
    const vec4 channels = textureLod(s_channels, uv * u_layerScale.x, shadeLevel + u_layerLevel.x);
    point.roughness = channels.r;
    point.occlusion = channels.g;
    point.glow = channels.a;
    // Roughness as a slope deviation of its own: it widens the lobe like the variance does.
    const float power = u_specularPower / (1.0 + u_specularPower * (slopeVariance + channels.r * channels.r));
    point.specular = nDotL > 0.0 ? (power + 2.0) / (u_specularPower + 2.0) *
                                       pow(max(dot(normal, normalize(lightDir + point.viewDir)), 0.0), power)
                                 : 0.0;
    // A deferred walk's pixel (HFX_DEFERRED_SHADOWS, shadings affine in the light factor: hfx::
    // shadingAffineInLight): the colour is affine in that factor, so
    // shaded with no direct light (with the others, in step) and then with it unshadowed, any
    // self-shadow's colour follows; the pass after the draw finds it from these two. Until then
    // the texel shadows' blend.
#if HFX_DEFERRED_SHADOWS
    if (deferred >= 0) point.lit = 0.0;
    vec3 color = hfx_shade(point);
    if (deferred >= 0) {
        const vec3 dark = color;
        point.lit = mapLit;
        const vec3 direct = hfx_shade(point) - dark;
        const int at = HFX_DEFERRED_VEC4S * deferred;
        hfx_deferredRays[at + 2].yzw = dark;
        hfx_deferredRays[at + 3] = vec4(direct, 0.0);
        color = dark + selfLit * direct;
    }
#else
    const vec3 color = hfx_shade(point);
#endif
    s.color = color;
    // What a deferred engine's lighting reads of the traced point.
    s.normal = vec4(point.normal, point.slopeVariance);
    s.albedo = vec4(point.albedo, point.foam.x);
    // The light that reaches the point: its self-shadow's share, and on water under clouds the
    // clouds' (water's main).
    float reaching = selfLit;
#if HFX_SKY == 1
    reaching *= g_cloudSunlight;
#endif
    s.material = vec4(point.roughness, point.occlusion, reaching, height);
    s.emission = hfx_emission(point);
    s.trace = vec4(uv, depthFraction, lit);
    s.entry = uv0;
    return s;
}

void main() {
#if HFX_SKY == 1
    // The clouds' shadow on the water, at the polygon's point and over its pixel there: the
    // relief's depth is nothing beside the clouds' height (shade/sky.glsl's g_cloudSunlight).
    g_cloudSunlight = hfx_cloud_sunlight(v_worldPos, max(length(dFdxFine(v_worldPos)), length(dFdyFine(v_worldPos))));
#endif
#if HFX_COMPUTE_TRACE == 1
    // A back face stores nothing (trace/hier/trace.glsl): its pixel's front face does, if any.
    // (gl_FrontFacing is its primitive's: a 2x2 quad leaves together.)
    if (!gl_FrontFacing) return;
#endif
#if HFX_TRIPLANAR
    // Each projection with a weight traces and shades the pixel in its own frame, and the results
    // blend by weight: the colour, the traced point (its depth and motion), what a deferred
    // engine reads; the trace output is the heaviest one's. The weights, from the mesh's own
    // normal: |n| less the dead zone, to the power u_triplanarSharpness, summing to 1 (the
    // largest component of a unit normal, at least 0.577, always has one).
    const vec3 n = length(v_objectNormal) > 1e-6 ? normalize(v_objectNormal) : vec3(0.0, 1.0, 0.0);
    const vec3 dpdx = dFdxFine(v_objectPos), dpdy = dFdyFine(v_objectPos);
    vec3 weights = pow(max(abs(n) - HFX_TRIPLANAR_DEAD_ZONE, 0.0), vec3(u_triplanarSharpness));
    weights /= weights.x + weights.y + weights.z;
    const int heaviest = weights.x >= weights.y && weights.x >= weights.z ? 0 : weights.y >= weights.z ? 1 : 2;
    HfxShaded s = HFX_UNSHADED;
    // A loop over the projections left, as many trips as the lane has projections: a warp (or
    // llvmpipe's row of lanes, which runs every branch's body for all of them) takes as many as
    // its lane with the most, where a loop over the three axes with a branch on each weight ran
    // all three on llvmpipe (its POM draw of the noise on a rounded box took 1.25-1.28x, hier's
    // 1.21-1.27x this loop's; the same registers on RDNA2: docs/BENCHMARKS.md).
    uint left = uint(weights.x > 0.0) | uint(weights.y > 0.0) << 1 | uint(weights.z > 0.0) << 2;
    while (left != 0u) {
        const int axis = findLSB(left);
        left &= left - 1u;
        const float w = weights[axis];
        HfxFrame f = hfx_projected_frame(axis, n, dpdx, dpdy);
        f.decides = axis == heaviest;
        const HfxShaded a = hfx_surface(f);
        s.color += w * a.color;
        s.position += w * a.position;
        s.normal += w * a.normal;
        s.albedo += w * a.albedo;
        s.material += w * a.material;
        s.emission += w * a.emission;
        if (axis == heaviest) {
            s.trace = a.trace;
            s.entry = a.entry;
        }
    }
    s.normal.xyz = normalize(s.normal.xyz);
#else
    // The fine differences, each along the pixel's own row and column of its quad, as the compute
    // pass takes them from the screen (trace.comp): dFdx leaves fine or coarse to the driver, and
    // a coarse one would move the level of detail and a pixel budget's tolerance off the pass's.
    // (llvmpipe's dFdx is fine: the same frames to the byte.)
    const HfxShaded s =
        hfx_surface(HfxFrame(v_texcoord, dFdxFine(v_texcoord), dFdyFine(v_texcoord), v_tangent, v_bitangent, 0, true));
#endif
#if HFX_COMPUTE_TRACE == 1
    return; // the rays draw stored its ray
#endif
#if HFX_TRACES && HFX_TRIPLANAR
    gl_FragDepth = hfx_depth_of(s.position); // (the blended point's)
#endif
#if HFX_SHADOW_CASTER
    return; // the map holds the traced depth; nothing to shade
#endif
    o_color = vec4(hfx_output(s.color), 1.0);
#if HFX_MOTION_OUTPUT
    // The traced point's, carried by the mesh (the relief's parallax moves it against the polygon).
    o_motion = hfx_motion(vec4(s.position, 1.0));
#endif
#if HFX_NORMAL_OUTPUT
    o_normal = s.normal;
#endif
#if HFX_ALBEDO_OUTPUT
    o_albedo = s.albedo;
#endif
#if HFX_MATERIAL_OUTPUT
    o_material = s.material;
#endif
#if HFX_EMISSION_OUTPUT
    o_emission = vec4(s.emission, 1.0);
#endif
#if HFX_TRACE_OUTPUT
    // w: the fetch count in its integer part, the light (0..1) in half of its fraction.
    o_trace = vec4(s.trace.xyz, g_fetches + 0.5 * clamp(s.trace.w, 0.0, 0.998));
    o_entry = s.entry;
#endif
}
