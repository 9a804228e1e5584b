// The fragment stage's side of the tracer contract (trace/README.md): the height accessors
// every trace/*.glsl calls, over the surface texture's w channel and the height pyramid. A
// layered surface (HFX_LAYERS > 1: the ocean's cascades) sums its layers' heights, each at its
// own scale and mip level, so the tracers trace the sum without knowing of layers. Each accessor
// counts the texture reads it makes, for the trace output.

#ifndef HFX_LAYERS
#define HFX_LAYERS 1
#endif
// HFX_BOUNDED_SEARCH 1: hfx_segment_bounds reads the layers' pyramids (SurfaceMaterial::
// boundedSearch where every traced layer has one). A define, not a uniform: a CPU rasteriser
// (llvmpipe) runs both sides of a branch even on a uniform, so a switched-off uniform path
// still cost POM its four pyramid fetches per search (about a quarter of its draw).
#ifndef HFX_BOUNDED_SEARCH
#define HFX_BOUNDED_SEARCH 0
#endif
// HFX_TEXEL_SHADOWS 1: the draw has the exact self-shadow of its light at the field's samples
// (hfx::TexelShadows, which the exact tracer's unit has hfx::TexelShadowPass draw with hier's
// walk), read by hfx_texel_shadow where the four samples around a point agree
// (surface/shadow.glsl). Their light is u_shadowLight.
#ifndef HFX_TEXEL_SHADOWS
#define HFX_TEXEL_SHADOWS 0
#endif
#ifndef HFX_TEXEL_SPREAD
#define HFX_TEXEL_SPREAD 0.25
#endif

// World from texture space at a point of the mesh: columns dP/du, dP/dv and the unit normal scaled
// to the same units (texture space's z is the depth, one unit = one texture repeat). The draw
// (surface.frag) turns its pixel's view ray into texture space with it, and ExactTracer its flat
// patch's eye for the beam prepass (trace/hier/beam.comp) and the compute pass (trace.comp): they
// must agree, or a block's start could pass a hit.
mat3 hfx_world_from_texture(vec3 unitNormal, vec3 tangent, vec3 bitangent) {
    return mat3(tangent, bitangent, unitNormal * sqrt(length(tangent) * length(bitangent)));
}

// The mip level a pixel's texcoord derivatives select (dx, dy per pixel, in texels): the draw's
// (surface.frag) and, from the screen, the compute pass's on a flat patch (trace/hier/trace.comp).
float hfx_level_of(vec2 dx, vec2 dy) {
    return 0.5 * log2(max(max(dot(dx, dx), dot(dy, dy)), 1e-12));
}

// How many pixels a texcoord offset v at the polygon spans: |J^-1 v|, J the pixel's texcoord
// derivatives (dx, dy per pixel); 0 where they are degenerate.
float hfx_screen_length(vec2 v, vec2 dx, vec2 dy) {
    const float det = dx.x * dy.y - dx.y * dy.x;
    if (abs(det) < 1e-20) return 0.0;
    return length(vec2(dy.y * v.x - dy.x * v.y, dx.x * v.y - dx.y * v.x)) / abs(det);
}

layout(binding = HFX_UNIT_SURFACE) uniform sampler2D s_surface; // normal.xyz, height w (layer 0)
// HFX_PYRAMID_ATLAS 1: the height-bounds pyramid in PyramidLayout::Atlas, llvmpipe's workaround
// (GlWorkarounds::pyramidAtlas in core/GlRenderer.h says why): every level in one RG32F image
// read with imageLoad (hfx_atlas_origin), and the level-0 cells' samples in an RGBA32F image
// (bounds.comp). 0: a mip chain, RG32F, a level k texel the (max, min) over the bilinear cells it
// covers, read with texelFetch at the lane's level; the cells' samples gathered from s_surface.
#ifndef HFX_PYRAMID_ATLAS
#define HFX_PYRAMID_ATLAS 0
#endif
#if HFX_PYRAMID_ATLAS
layout(rg32f, binding = HFX_IMAGE_PYRAMID) readonly uniform image2D i_pyramid;
// Layer 0's level-0 cells: per cell its four samples in textureGather's order (bounds.comp).
layout(rgba32f, binding = HFX_IMAGE_CELLS) readonly uniform image2D i_cells;
#else
layout(binding = HFX_UNIT_PYRAMID) uniform sampler2D s_pyramid;
#endif
#if HFX_TEXEL_SHADOWS
layout(binding = HFX_UNIT_TEXEL_SHADOWS) uniform sampler2D s_texelShadows; // R32F: the shadow at each sample
#endif
#if HFX_LAYERS > 1
layout(binding = HFX_UNIT_SURFACE1) uniform sampler2D s_surface1;
// The layers' own pyramids (bounded searches), layer i at [i - 1]: consecutive units.
#if HFX_PYRAMID_ATLAS
layout(rg32f, binding = HFX_IMAGE_PYRAMID + 1) readonly uniform image2D i_pyramids[HFX_LAYERS - 1];
#else
layout(binding = HFX_UNIT_PYRAMID1) uniform sampler2D s_pyramids[HFX_LAYERS - 1];
#endif
#endif
#if HFX_LAYERS > 2
layout(binding = HFX_UNIT_SURFACE2) uniform sampler2D s_surface2;
#endif
#if HFX_LAYERS > 3
layout(binding = HFX_UNIT_SURFACE3) uniform sampler2D s_surface3;
#endif

// A layered surface traces its first HFX_TRACED_LAYERS layers (all unless told): the others
// (the ocean's fine cascades, a few percent of the depth) stand at their rest heights in the
// trace, summed in u_untracedHeight, and still shade with their slopes.
#ifndef HFX_TRACED_LAYERS
#define HFX_TRACED_LAYERS HFX_LAYERS
#endif

#ifndef HFX_RINGS
#define HFX_RINGS 0
#endif

#if HFX_RINGS
// The impact rings at uv: x the height (h units), yz its gradient (per texcoord), w the foam.
// Each ring is a wave packet, amplitude exp(-(x/width)^2) cos(k x), x = r - radius.
vec4 hfx_rings(vec2 uv) {
    vec4 sum = vec4(0.0);
    for (int i = 0; i < u_ringCount; ++i) {
        const vec2 d = uv - u_ringShape[i].xy;
        const float r = length(d), x = r - u_ringShape[i].z, width = u_ringShape[i].w;
        if (abs(x) > 3.0 * width) continue;
        const float envelope = exp(-(x * x) / (width * width)), k = u_ringWave[i].x, a = u_ringWave[i].y;
        const float c = cos(k * x), s = sin(k * x);
        const float dr = a * envelope * (-2.0 * x / (width * width) * c - k * s);
        sum += vec4(a * envelope * c, (r > 0.0 ? d / r : vec2(0.0)) * dr, u_ringWave[i].z * envelope);
    }
    return sum;
}
#endif

float g_fetches = 0.0;

// The mip level a layer's search fetches read: the nearest whole level to the level its texels
// ask for (layer 0's `level` plus its offset), as layer 0's own is. One level is a bilinear
// fetch; a fractional one would be trilinear, two levels read per fetch (on llvmpipe the water's
// draw took 17% longer with the second layer's fractional offset).
float hfx_layer_level(float level, float offset) { return max(round(level + offset), 0.0); }

float hfx_layers_height(vec2 uv, float level);

float hfx_height(vec2 uv, float level) {
    // The rings' variant (HFX_RINGS) is drawn only while a ring lives (WaterLook::ringCount > 0):
    // their loop in every fetch nearly doubled the water's search time when it ran without rings.
#if HFX_RINGS
    return hfx_layers_height(uv, level) + hfx_rings(uv).x;
#else
    return hfx_layers_height(uv, level);
#endif
}

float hfx_layers_height(vec2 uv, float level) {
    g_fetches += float(HFX_TRACED_LAYERS);
#if HFX_LAYERS == 1
    return textureLod(s_surface, uv, level).w;
#else
    float h = u_untracedHeight +
              u_layerWeight.x * textureLod(s_surface, uv * u_layerScale.x, hfx_layer_level(level, u_layerLevel.x)).w;
#if HFX_TRACED_LAYERS > 1
    h += u_layerWeight.y * textureLod(s_surface1, uv * u_layerScale.y, hfx_layer_level(level, u_layerLevel.y)).w;
#endif
#if HFX_TRACED_LAYERS > 2
    h += u_layerWeight.z * textureLod(s_surface2, uv * u_layerScale.z, hfx_layer_level(level, u_layerLevel.z)).w;
#endif
#if HFX_TRACED_LAYERS > 3
    h += u_layerWeight.w * textureLod(s_surface3, uv * u_layerScale.w, hfx_layer_level(level, u_layerLevel.w)).w;
#endif
    return h;
#endif
}

// The hierarchical tracer's accessors read layer 0 alone: the renderer refuses it on layered
// surfaces (a sum of bilinear patches on different grids has no closed-form cell solve).
ivec2 hfx_size() { return textureSize(s_surface, 0); }

// A pyramid cell's texel at a level whose last texel is `last`: wrapped or clamped as the field's
// edges are. The pyramid's sizes are powers of two (HeightBounds), so a wrap is
// a bitwise and, negative cells included (two's complement), and a clamp after it changes nothing;
// a clamping axis ands with -1 (all bits). integer % has no vector form on a CPU rasteriser.
ivec2 hfx_pyramid_texel(ivec2 cell, ivec2 last) {
    const ivec2 mask = mix(ivec2(-1), last, greaterThanEqual(u_wrapMask, ivec2(0)));
    return clamp(cell & mask, ivec2(0), last);
}
// The same for layer 0's field at a level, from the uniforms alone (u_fieldLast, u_wrapMask: a
// power of two's last index shifted right is the level's, and -1 stays -1): the walk's per-step
// read, four instructions.
ivec2 hfx_field_texel(ivec2 cell, int level) {
    return clamp(cell & (u_wrapMask >> level), ivec2(0), u_fieldLast >> level);
}

#if HFX_PYRAMID_ATLAS
// Where a level's texel (0, 0) lies in the pyramid's image (HeightBounds::atlasOrigin):
// level 0 at the origin, level 1 at (width, 0), each further level below the one before.
ivec2 hfx_atlas_origin(ivec2 size, int level) {
    const int above = max(level - 1, 0);
    return level == 0 ? ivec2(0) : ivec2(size.x, size.y - max(size.y >> above, 1) + max(0, above - findLSB(size.y)));
}
#endif

// Layer `layer`'s pyramid at a level's texel (wrapped or clamped already); a constant layer
// folds the switch.
vec2 hfx_pyramid_load(int layer, ivec2 size, ivec2 texel, int level) {
#if HFX_PYRAMID_ATLAS
    const ivec2 at = hfx_atlas_origin(size, level) + texel;
#if HFX_LAYERS > 1
    if (layer > 0) return imageLoad(i_pyramids[layer - 1], at).rg;
#endif
    return imageLoad(i_pyramid, at).rg;
#else
#if HFX_LAYERS > 1
    if (layer > 0) return texelFetch(s_pyramids[layer - 1], texel, level).rg;
#endif
    return texelFetch(s_pyramid, texel, level).rg;
#endif
}

// A level-0 cell's four samples, in textureGather's order: the cell wrapped or clamped as the
// pyramid's level 0 is, then a gather around its centre ((i + 1) / size lies exactly between
// the four texel centres at power-of-two sizes; the sampler wraps or clamps the far samples as
// the field's edges do); in the atlas layout the cells image's copy of the same.
vec4 hfx_cell_samples(ivec2 cell) {
    g_fetches += 1.0;
    const ivec2 texel = hfx_field_texel(cell, 0);
#if HFX_PYRAMID_ATLAS
    return imageLoad(i_cells, texel);
#else
    return textureGather(s_surface, fma(vec2(texel), u_texelSize, u_texelSize), 3);
#endif
}

vec2 hfx_bounds(ivec2 cell, int level) {
    g_fetches += 1.0;
    return hfx_pyramid_load(0, u_fieldLast + 1, hfx_field_texel(cell, level), level);
}

// A light ray moving perClimb texcoords per unit of height climbed goes the way of the surface's
// shadow light (u_shadowLight: its move per climb, penumbra, slack), within its slack.
bool hfx_along_shadow_light(vec2 perClimb) {
    return all(lessThanEqual(abs(perClimb - u_shadowLight.xy), vec2(u_shadowLight.w)));
}

// The texel shadows (HFX_TEXEL_SHADOWS) for a light ray from p (cell space) of their light (its
// move per climb within the slack, the same penumbra: the samples hold that penumbra's shadow).
// The walk's shadow is 1 where a blocker stands above the ray (hard shadow) and below 1
// elsewhere, continuous in the point there. The samples are every stride-th of the field on each
// axis (TexelShadowPass; 1: all). Where the four around p are all in hard shadow, or none is and
// they differ by at most HFX_TEXEL_SPREAD, `shadow` is their bilinear blend and the walk is not
// needed; where the hard shadow's edge crosses their cell (some samples are in it, some not), or
// past the last sample on an edge that clamps, false: the ray is walked.
bool hfx_texel_shadow(vec2 p, vec2 perClimb, float penumbra, out float shadow) {
    shadow = 0.0;
#if HFX_TEXEL_SHADOWS
    if (hfx_along_shadow_light(perClimb) && abs(penumbra - u_shadowLight.z) <= 1e-6 * u_shadowLight.z) {
        // Every stride-th sample (TexelShadowPass's stride: a power of two, so q is exact).
        const ivec2 grid = textureSize(s_texelShadows, 0);
        const vec2 q = p * (vec2(grid) / vec2(hfx_size())), cell = floor(q), f = q - cell;
        // Past the last sample on an edge that clamps, nothing brackets the point (at a stride
        // above 1 the relief goes on there): walk.
        const bvec2 past = greaterThanEqual(cell, vec2(grid - 1));
        if ((past.x && u_wrapMask.x < 0) || (past.y && u_wrapMask.y < 0)) return false;
        g_fetches += 1.0;
        // x: (i, j+1), y: (i+1, j+1), z: (i+1, j), w: (i, j)
        const vec4 s = textureGather(s_texelShadows, (cell + 1.0) / vec2(grid), 0);
        const bvec4 hard = equal(s, vec4(1.0));
        shadow = mix(mix(s.w, s.z, f.x), mix(s.x, s.y, f.x), f.y);
        const float spread = max(max(s.x, s.y), max(s.z, s.w)) - min(min(s.x, s.y), min(s.z, s.w));
        return all(hard) || (!any(hard) && spread <= HFX_TEXEL_SPREAD);
    }
#endif
    return false;
}

// Bounds of the heights the searches read (hfx_height at `level`) anywhere on the texcoord segment
// from a to b: (max, min), from the pyramids where the material asks (HFX_BOUNDED_SEARCH: every
// traced layer has one); else (1, 0), the whole relief. Per layer, in its sample coordinates
// (x = u * width - 0.5, pyramid cell i between samples i and i + 1), the segment's box is widened
// by what its fetches reach: the bilinear cell at mip 0; at mip m, whose texels average 2^m-wide
// blocks, 1.5 * 2^m samples. The pyramid level whose cells are at least as wide as that box
// covers it with two cells per axis: four fetches per layer. The layers' bounds add, with the
// untraced layers' rest height and, in the ring variant, the rings' amplitudes.
vec2 hfx_layer_bounds(int layer, ivec2 size, vec2 a, vec2 b, float mip) {
    const float reach = mip > 0.0 ? 1.5 * exp2(ceil(mip)) : 0.0;
    const vec2 lo = min(a, b) * vec2(size) - 0.5 - reach, hi = max(a, b) * vec2(size) - 0.5 + reach;
    const int levels = findMSB(max(size.x, size.y)) + 1;
    const float extent = max(hi.x - lo.x, hi.y - lo.y);
    const int level = min(int(ceil(log2(max(extent, 1.0)))), levels - 1);
    // The level's texels under the box's corners (power-of-two sizes: the cell width 2^level
    // scales exactly).
    const ivec2 last = max(size >> level, ivec2(1)) - 1;
    const vec2 invWidth = vec2(size >> level) / vec2(size);
    const ivec2 c0 = hfx_pyramid_texel(ivec2(floor(lo * invWidth)), last);
    const ivec2 c1 = hfx_pyramid_texel(ivec2(floor(hi * invWidth)), last);
    g_fetches += 4.0;
    const vec2 b0 = hfx_pyramid_load(layer, size, c0, level);
    const vec2 b1 = hfx_pyramid_load(layer, size, ivec2(c1.x, c0.y), level);
    const vec2 b2 = hfx_pyramid_load(layer, size, ivec2(c0.x, c1.y), level);
    const vec2 b3 = hfx_pyramid_load(layer, size, c1, level);
    return vec2(max(max(b0.x, b1.x), max(b2.x, b3.x)), min(min(b0.y, b1.y), min(b2.y, b3.y)));
}

vec2 hfx_segment_bounds(vec2 a, vec2 b, float level) {
#if !HFX_BOUNDED_SEARCH
    return vec2(1.0, 0.0);
#else
#if HFX_LAYERS == 1
    vec2 bounds = hfx_layer_bounds(0, hfx_size(), a, b, level);
#else
    vec2 bounds = vec2(u_untracedHeight) +
                  u_layerWeight.x * hfx_layer_bounds(0, hfx_size(), a * u_layerScale.x, b * u_layerScale.x,
                                                     hfx_layer_level(level, u_layerLevel.x));
#if HFX_TRACED_LAYERS > 1
    bounds += u_layerWeight.y * hfx_layer_bounds(1, textureSize(s_surface1, 0), a * u_layerScale.y,
                                                 b * u_layerScale.y, hfx_layer_level(level, u_layerLevel.y));
#endif
#if HFX_TRACED_LAYERS > 2
    bounds += u_layerWeight.z * hfx_layer_bounds(2, textureSize(s_surface2, 0), a * u_layerScale.z,
                                                 b * u_layerScale.z, hfx_layer_level(level, u_layerLevel.z));
#endif
#if HFX_TRACED_LAYERS > 3
    bounds += u_layerWeight.w * hfx_layer_bounds(3, textureSize(s_surface3, 0), a * u_layerScale.w,
                                                 b * u_layerScale.w, hfx_layer_level(level, u_layerLevel.w));
#endif
#endif
#if HFX_RINGS
    float rings = 0.0;
    for (int i = 0; i < u_ringCount; ++i) rings += abs(u_ringWave[i].y);
    bounds += vec2(rings, -rings);
#endif
    // A margin for the storage's rounding (float16 rounds a height by up to 2^-11 of itself).
    return bounds + vec2(1e-3, -1e-3);
#endif
}
