// The fragment stage's side of the tracer contract (trace/README.md): the height accessors
// every trace/*.glsl calls, over the surface texture's w channel and the height pyramid. Each
// counts the fetches it makes, for the trace output.

layout(binding = 0) uniform sampler2D s_surface; // normal.xyz, height w
layout(binding = 3) uniform sampler2D s_pyramid; // R32F, level k texel bounds the bilinear cells it covers

float g_fetches = 0.0;

float hfx_height(vec2 uv, float level) {
    g_fetches += 1.0;
    return textureLod(s_surface, uv, level).w;
}

vec4 hfx_gather(vec2 uv) {
    g_fetches += 1.0;
    return textureGather(s_surface, uv, 3);
}

ivec2 hfx_size() { return textureSize(s_surface, 0); }

int hfx_levels() { return u_pyramidLevels; }

float hfx_bound(ivec2 cell, int level) {
    const ivec2 levelSize = max(hfx_size() >> level, ivec2(1));
    const ivec2 index = mix(clamp(cell, ivec2(0), levelSize - 1), (cell % levelSize + levelSize) % levelSize, bvec2(u_wrap));
    g_fetches += 1.0;
    return texelFetch(s_pyramid, index, level).r;
}
