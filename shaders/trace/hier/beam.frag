#version 450 core
// The exact tracer's beam start (hfx::SurfaceRenderer, before a hier draw of a flat patch, seen
// by a camera or, casting into a shadow map, by the light): one fragment per block of
// HFX_BEAM_BLOCK x HFX_BEAM_BLOCK pixels of the draw, writing the depth
// fraction from which on every view ray of the block may meet the relief (trace/hier.glsl,
// hfx_beam_depth); the draw's rays start there (HfxRay.start). Drawn with surface.vert into a target one texel per block, u_viewProj mapping the draw's window onto it
// (texel (i, j) covers the draw's pixels [B i, B i + B) x [B j, B j + B) of the window).
//
// The block's rays are found from the screen, not from the interpolated attributes: each of its
// corners is unprojected (u_beamInverseViewProj, at the near and the far plane: a perspective
// camera's rays or an orthographic light's alike) onto the patch's plane, which a flat patch's one
// texture frame maps to texcoords and a parallax vector exactly as surface.frag maps a pixel.
// At any depth the points of the block's rays lie in the quadrilateral of its corner rays' (the
// screen maps to each plane of constant depth projectively, keeping the block's convex outline),
// so no ray strays from the centre's further than a corner does, and a corner's offset from the
// centre is linear in the depth: the larger of its offsets at the polygon and at the bottom
// bounds it. That bound, plus a margin for the rounding of both passes, is the beam's reach.

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/heights.glsl"
#include "trace/common.glsl"
#include "trace/hier.glsl"

uniform mat4 u_beamInverseViewProj; // inverse of u_viewProj (this pass's, onto the block target)
uniform vec2 u_beamPixel;           // one texel of the block target in NDC: 2 / its size

in vec3 v_worldPos;
in vec3 v_normal;
in vec3 v_tangent;
in vec3 v_bitangent;
in vec2 v_texcoord;

layout(location = 0) out vec4 o_start;

// The ray through the window point `ndc` of the target: where it crosses the patch's plane, in
// cell space (uv * size - 0.5) at the polygon (xy) and at the bottom of the relief (zw). False
// where it does not come down onto the plane from the side the normal faces.
bool hfx_block_ray(vec2 ndc, mat3 textureFromWorld, vec3 normal, out vec4 cells) {
    // The near and far planes' depths in clip space: -1 and 1, or 1 and 0 reversed (u_reversedZ).
    const vec2 planes = u_reversedZ != 0 ? vec2(1.0, 0.0) : vec2(-1.0, 1.0);
    const vec4 nearH = u_beamInverseViewProj * vec4(ndc, planes.x, 1.0);
    const vec4 farH = u_beamInverseViewProj * vec4(ndc, planes.y, 1.0);
    const vec3 near = nearH.xyz / nearH.w;
    const vec3 along = hfx_away_from_eye(farH.xyz / farH.w - near); // (an oblique near plane's far one can lie behind the eye)
    const float across = dot(along, normal);
    cells = vec4(0.0);
    if (!(across < 0.0)) return false;
    const vec3 onPlane = near + along * (dot(v_worldPos - near, normal) / across);
    const vec2 uv = v_texcoord + (textureFromWorld * (onPlane - v_worldPos)).xy;
    const vec3 viewTS = textureFromWorld * -along;
    if (!(viewTS.z > 0.0)) return false;
    const vec2 size = vec2(hfx_size());
    const vec2 top = uv * size - 0.5;
    cells = vec4(top, top - viewTS.xy / viewTS.z * u_depthScale * size);
    return true;
}

void main() {
    const vec3 normal = normalize(v_normal);
    const mat3 textureFromWorld = inverse(hfx_world_from_texture(normal, v_tangent, v_bitangent));
    const vec2 centre = gl_FragCoord.xy * u_beamPixel - 1.0;
    vec4 ray, corner;
    bool ok = hfx_block_ray(centre, textureFromWorld, normal, ray);
    vec2 reach = vec2(0.0);
    for (int c = 0; c < 4; ++c) {
        const vec2 side = vec2(c & 1, c >> 1) - 0.5;
        ok = ok && hfx_block_ray(centre + side * u_beamPixel, textureFromWorld, normal, corner);
        const vec4 off = abs(corner - ray);
        reach = max(reach, max(off.xy, off.zw));
    }
    // The margin: a thousandth of a texel and 1% for the rounding of this pass's unprojection
    // and of the draw's interpolated rays (texcoords of a few hundred texels round to 1e-4).
    const float r = max(reach.x, reach.y) * 1.01 + 1e-3;
    o_start = vec4(ok ? hfx_beam_depth(ray.xy, ray.zw - ray.xy, r) : 0.0, 0.0, 0.0, 1.0);
}
