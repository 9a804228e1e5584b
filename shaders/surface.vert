#version 450 core
// Passes the world-space position and the unnormalised tangent frame (dP/du, dP/dv) so the
// fragment stage can express the view and light rays in texture units, per pixel.

#ifndef HFX_TRIPLANAR
#define HFX_TRIPLANAR 0
#endif

#include "bindings.glsl"
#include "surface/uniforms.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_tangent;
layout(location = 3) in vec3 a_bitangent;
layout(location = 4) in vec2 a_texcoord;

out vec3 v_worldPos;
out vec3 v_normal;
out vec3 v_tangent;
out vec3 v_bitangent;
out vec2 v_texcoord;
#if HFX_TRIPLANAR
out vec3 v_objectPos;    // a triplanar mapping's projections read the mesh's own position
out vec3 v_objectNormal; // and normal (surface.frag)
#endif

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_worldPos = world.xyz;
    v_normal = mat3(u_normalMatrix) * a_normal;
    v_tangent = mat3(u_model) * a_tangent;
    v_bitangent = mat3(u_model) * a_bitangent;
    v_texcoord = a_texcoord;
#if HFX_TRIPLANAR
    v_objectPos = a_position;
    v_objectNormal = a_normal;
#endif
    gl_Position = u_viewProj * world;
}
