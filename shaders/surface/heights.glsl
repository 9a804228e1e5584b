// The fragment stage's side of the tracer contract (trace/README.md): the height accessors
// every trace/*.glsl calls, over the surface texture's w channel and the height pyramid. A
// layered surface (HFX_LAYERS > 1: the ocean's cascades) sums its layers' heights, each at its
// own scale and mip level, so the tracers trace the sum without knowing of layers. Each accessor
// counts the texture reads it makes, for the trace output.

#ifndef HFX_LAYERS
#define HFX_LAYERS 1
#endif

layout(binding = 0) uniform sampler2D s_surface; // normal.xyz, height w (layer 0)
layout(binding = 3) uniform sampler2D s_pyramid; // RG32F: level k texel's (max, min) over the bilinear cells it covers
#if HFX_LAYERS > 1
layout(binding = 4) uniform sampler2D s_surface1;
#endif
#if HFX_LAYERS > 2
layout(binding = 5) uniform sampler2D s_surface2;
#endif
#if HFX_LAYERS > 3
layout(binding = 6) uniform sampler2D s_surface3;
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
    float h = u_untracedHeight + u_layerWeight.x * textureLod(s_surface, uv * u_layerScale.x, level + u_layerLevel.x).w;
#if HFX_TRACED_LAYERS > 1
    h += u_layerWeight.y * textureLod(s_surface1, uv * u_layerScale.y, level + u_layerLevel.y).w;
#endif
#if HFX_TRACED_LAYERS > 2
    h += u_layerWeight.z * textureLod(s_surface2, uv * u_layerScale.z, level + u_layerLevel.z).w;
#endif
#if HFX_TRACED_LAYERS > 3
    h += u_layerWeight.w * textureLod(s_surface3, uv * u_layerScale.w, level + u_layerLevel.w).w;
#endif
    return h;
#endif
}

// The hierarchical tracer's accessors read layer 0 alone: the renderer refuses it on layered
// surfaces (a sum of bilinear patches on different grids has no closed-form cell solve).
vec4 hfx_gather(vec2 uv) {
    g_fetches += 1.0;
    return textureGather(s_surface, uv, 3);
}

ivec2 hfx_size() { return textureSize(s_surface, 0); }

int hfx_levels() { return u_pyramidLevels; }

vec2 hfx_bounds(ivec2 cell, int level) {
    const ivec2 levelSize = max(hfx_size() >> level, ivec2(1));
    // Wrapped in float (exact for these integers): integer % has no vector form on a CPU
    // rasteriser and costs a divide per lane.
    const vec2 c = vec2(cell), n = vec2(levelSize);
    const ivec2 index = mix(clamp(cell, ivec2(0), levelSize - 1), ivec2(c - n * floor(c / n)), bvec2(u_wrap));
    g_fetches += 1.0;
    return texelFetch(s_pyramid, index, level).rg;
}
