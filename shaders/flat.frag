#version 450 core
// A solid colour with the polygon's own depth: stand-in geometry that intersects a surface.
// Lit (u_flatLit = 1): Lambert under the surface block's light, receiving its shadow map.

#include "bindings.glsl"
#include "surface/uniforms.glsl"
#include "surface/shadowmap.glsl"

in vec3 v_worldPos;
in vec3 v_normal;
in vec3 v_tangent;
in vec3 v_bitangent;
in vec2 v_texcoord;

layout(location = 0) out vec4 o_color;
uniform vec4 u_color;
uniform int u_flatLit;

void main() {
    if (u_flatLit == 0) {
        o_color = u_color;
        return;
    }
    // Two-sided: the side facing the eye.
    vec3 normal = normalize(v_normal);
    if (dot(normal, hfx_to_eye(v_worldPos)) < 0.0) normal = -normal;
    const vec3 lightDir = normalize(u_lightDir);
    const float diffuse = max(dot(normal, lightDir), 0.0);
    const float lit = diffuse > 0.0 ? hfx_shadow_map(v_worldPos, normal) : 0.0;
    const vec3 color = u_color.rgb * (u_ambient + lit * diffuse * u_lightColor);
    o_color = vec4(hfx_output(color), u_color.a);
}
