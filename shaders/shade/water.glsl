// Water: the body colour deepens in the troughs, the sky is reflected by Schlick's Fresnel
// weight, the sun leaves a sharp glint, and distance fades everything into the horizon. Its look
// is a second std140 block, mirrored by hfx::WaterUniforms (effects/src/SurfaceUniforms.h).

layout(std140, binding = 1) uniform HfxWater {
    vec3 u_deepColor;     // troughs: light travels far in the water
    float u_fresnelF0;    // reflectance seen head-on
    vec3 u_shallowColor;  // crests: thin water scatters the sun
    float u_glintPower;   // sharpness of the sun's reflection
    vec3 u_skyZenith;     // procedural sky, used without an environment
    float u_glintStrength;
    vec3 u_skyHorizon;
    float u_hazeDistance; // world units where half the colour is haze
    int u_hasEnvironment; // 1: s_environment holds an equirectangular sky
};
layout(binding = 2) uniform sampler2D s_environment;

// The sky seen along a world direction: the environment image, or a zenith-horizon gradient.
vec3 hfx_sky(vec3 dir) {
    if (u_hasEnvironment != 0) {
        const float pi = 3.14159265;
        const vec2 uv = vec2(atan(dir.z, dir.x) / (2.0 * pi) + 0.5, acos(clamp(dir.y, -1.0, 1.0)) / pi);
        return textureLod(s_environment, vec2(uv.x, 1.0 - uv.y), 0.0).rgb;
    }
    return mix(u_skyHorizon, u_skyZenith, sqrt(clamp(dir.y, 0.0, 1.0)));
}

vec3 hfx_shade(HfxSurfacePoint p) {
    const vec3 body = mix(u_deepColor, u_shallowColor, p.height * p.height) * (u_ambient + p.lit * p.diffuse * u_lightColor);
    vec3 reflected = reflect(-p.viewDir, p.normal);
    reflected.y = abs(reflected.y); // a ray reflected downwards sees the next wave's sky
    const float fresnel = u_fresnelF0 + (1.0 - u_fresnelF0) * pow(1.0 - clamp(dot(p.normal, p.viewDir), 0.0, 1.0), 5.0);
    const float glint = u_glintStrength * pow(max(dot(reflected, p.lightDir), 0.0), u_glintPower);
    const vec3 color = mix(body, hfx_sky(reflected), fresnel) + p.lit * glint * u_lightColor;
    const float distance = length(u_cameraPos - p.position);
    return mix(color, u_skyHorizon, distance / (distance + u_hazeDistance));
}
