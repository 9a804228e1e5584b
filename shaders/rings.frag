#version 450 core
// A planet's rings (hfx::PlanetRings), drawn on an annulus in their plane after the planet, over
// it and the sky: composed in linear light over a copy of what the frame held behind them
// (s_behind: display values, or linear ones where the colours are written linear), so a thin ring adds its own light to the planet or the sky behind
// and dims them by the share it covers, as light does, not as display values would blend.
//
// Each radius is a slab of particles of normal optical depth tau (shade/rings.glsl's profile).
// Seen at cosine mu to the slab's normal it covers 1 - e^(-tau / mu) of what lies behind.
// Sunlight arriving at cosine mu0 is scattered once (hfx_ring_scattered), times the particles'
// albedo w: dense rings are bright on their lit face and dark from behind, thin ones glow on both.
// The planet's shadow takes the share of the sun's disc it covers; the ambient light lights
// what the rings cover.

//
// HFX_MOTION_OUTPUT 1 to 7: the rings' motion pass (hfx::PlanetRings::setMotionOutput), drawn
// after the colour's: where the rings cover at least half of what lies behind, the ring point's
// screen motion goes to that output; elsewhere the pixel keeps the motion of what shows through.
#ifndef HFX_MOTION_OUTPUT
#define HFX_MOTION_OUTPUT 0
#endif

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "shade/rings.glsl"

in vec3 v_worldPos;
in vec3 v_normal;
in vec3 v_tangent;
in vec3 v_bitangent;
in vec2 v_texcoord;

#if HFX_MOTION_OUTPUT
layout(location = HFX_MOTION_OUTPUT) out vec2 o_motion;
#else
layout(location = 0) out vec4 o_color;
#endif
layout(binding = HFX_UNIT_RING_BEHIND) uniform sampler2D s_behind;
uniform ivec2 u_viewportOrigin; // s_behind's texel (0, 0) in window pixels

void main() {
    const vec3 q = v_worldPos;
    const float s = hfx_ring_coordinate(length(q - u_planetCentre));
    // Filtered over the pixel's footprint (the mip chain): ringlets finer than a pixel average.
    // Read before the discard, so that every lane of the pixel's 2x2 quad is there for the
    // footprint (after a lane's discard its derivatives are undefined).
    const vec4 profile = texture(s_ringProfile, vec2(s, 0.5));
    if (s < 0.0 || s > 1.0) discard; // the annulus's polygon reaches past its circles
    const vec3 toEye = normalize(hfx_to_eye(q)), toLight = normalize(u_lightDir);
    const float viewSide = dot(toEye, u_ringAxis), lightSide = dot(toLight, u_ringAxis);
    const float mu = max(abs(viewSide), 1e-3), mu0 = max(abs(lightSide), 1e-3);
    const float tau = -log(max(1.0 - profile.a, 1e-6));
    const float cover = 1.0 - exp(-tau / mu);
#if HFX_MOTION_OUTPUT
    if (cover < 0.5) discard;
    o_motion = hfx_motion(vec4(q, 1.0));
#else
    const float scattered = hfx_ring_scattered(tau, mu, mu0, viewSide * lightSide > 0.0);
    const float sun = hfx_planet_sunlit(q, toLight);
    const vec3 color = profile.rgb * (u_lightColor * sun * scattered + u_ambient * cover);
    const vec3 stored = texelFetch(s_behind, ivec2(gl_FragCoord.xy) - u_viewportOrigin, 0).rgb;
    const vec3 behind = u_linearOutput != 0 ? stored : pow(stored, vec3(2.2));
    o_color = vec4(hfx_output(behind * (1.0 - cover) + color), 1.0);
#endif
}
