#version 450 core
// The sky behind everything (SurfaceRenderer::drawSky): each pixel's view direction through
// hfx_sky (shade/sky.glsl), the same sky the water reflects and fades into.

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "shade/sky.glsl"

#ifndef HFX_MOTION_OUTPUT
#define HFX_MOTION_OUTPUT 0
#endif

in vec2 v_ndc;
layout(location = 0) out vec4 o_color;
#if HFX_MOTION_OUTPUT
layout(location = HFX_MOTION_OUTPUT) out vec2 o_motion; // hfx::SurfaceRenderer::setMotionOutput
#endif
uniform mat4 u_inverseViewProj;

void main() {
    // The far plane's clip depth: 1, or 0 for a reversed-Z camera (whose 1 is the near plane, a
    // hair from the eye). An oblique near plane's tilted far plane can lie behind the eye.
    const vec4 far = u_inverseViewProj * vec4(v_ndc, u_reversedZ != 0 ? 0.0 : 1.0, 1.0);
    const vec3 dir = normalize(hfx_away_from_eye(-hfx_to_eye(far.xyz / far.w)));
    // The clouds are filtered over the pixel's width (the directions to its neighbours).
    const float spread = max(length(dFdxFine(dir)), length(dFdyFine(dir)));
    o_color = vec4(hfx_output(hfx_sky(dir, spread)), 1.0);
#if HFX_MOTION_OUTPUT
    o_motion = hfx_motion(vec4(dir, 0.0)); // a direction: the sky moves as the view turns
#endif
}
