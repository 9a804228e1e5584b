#include "hfx/effects/ShadowCascades.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace hfx {

namespace {
bool isDepthFormat(GLint format) {
    switch (format) {
    case GL_DEPTH_COMPONENT16:
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH_COMPONENT32:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH24_STENCIL8:
    case GL_DEPTH32F_STENCIL8:
        return true;
    default:
        return false;
    }
}
} // namespace

ShadowUniforms shadowUniforms(const ShadowCascades& shadows, bool& arrayTexture) {
    const size_t count = shadows.cascades.size();
    if (count < 1 || count > size_t(kMaxShadowCascades))
        throw Error(str("ShadowCascades: 1 to ", kMaxShadowCascades, " cascades, got ", count));
    if (shadows.texture == 0 || !glIsTexture(shadows.texture))
        throw Error(str("ShadowCascades.texture ", shadows.texture, " is not a GL texture"));
    GLint target = 0, format = 0, width = 0, height = 0, layers = 0;
    glGetTextureParameteriv(shadows.texture, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D && target != GL_TEXTURE_2D_ARRAY)
        throw Error(str("ShadowCascades.texture ", shadows.texture, " must be a GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY, got "
                        "the target 0x", std::hex, target));
    glGetTextureLevelParameteriv(shadows.texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    glGetTextureLevelParameteriv(shadows.texture, 0, GL_TEXTURE_WIDTH, &width);
    glGetTextureLevelParameteriv(shadows.texture, 0, GL_TEXTURE_HEIGHT, &height);
    glGetTextureLevelParameteriv(shadows.texture, 0, GL_TEXTURE_DEPTH, &layers);
    if (!isDepthFormat(format) || width <= 0 || height <= 0)
        throw Error(str("ShadowCascades.texture ", shadows.texture, " must hold depth (a GL_DEPTH_COMPONENT format), got "
                        "the format 0x", std::hex, format, std::dec, " at ", width, "x", height));
    arrayTexture = target == GL_TEXTURE_2D_ARRAY;
    ShadowUniforms u;
    u.count = int(count);
    u.reversedZ = shadows.reversedZ ? 1 : 0;
    u.texel = 1.0f / glm::vec2(float(width), float(height));
    for (size_t i = 0; i < count; ++i) {
        const ShadowCascade& c = shadows.cascades[i];
        const glm::mat4& m = c.viewProj;
        if (!isFinite(m)) throw Error(str("ShadowCascades: cascade ", i, "'s viewProj is not finite"));
        // Orthographic: no projective row, and an invertible 3x3 (rows x and y across the light,
        // z along it).
        const glm::vec3 across(m[0][0], m[1][0], m[2][0]), up(m[0][1], m[1][1], m[2][1]), along(m[0][2], m[1][2], m[2][2]);
        if (glm::vec4(m[0][3], m[1][3], m[2][3], m[3][3]) != glm::vec4(0.0f, 0.0f, 0.0f, 1.0f) ||
            !(std::abs(glm::dot(across, glm::cross(up, along))) > 0.0f))
            throw Error(str("ShadowCascades: cascade ", i, "'s viewProj must be a directional light's orthographic "
                            "projection (a last row of 0, 0, 0, 1 and an invertible 3x3), got the last row ",
                            text(glm::vec4(m[0][3], m[1][3], m[2][3], m[3][3]))));
        const glm::vec4 t = c.tile;
        if (!isFinite(t) || !(t.z > 0.0f) || !(t.w > 0.0f) || t.x < 0.0f || t.y < 0.0f || t.x + t.z > 1.0f + 1e-6f ||
            t.y + t.w > 1.0f + 1e-6f)
            throw Error(str("ShadowCascades: cascade ", i, "'s tile must lie in the texture's [0, 1] and not be empty, got ",
                            text(t)));
        if (c.layer < 0 || c.layer >= (arrayTexture ? layers : 1))
            throw Error(str("ShadowCascades: cascade ", i, "'s layer ", c.layer, " is outside the texture's ",
                            arrayTexture ? layers : 1, arrayTexture ? " layers" : " (a 2D texture has layer 0 only)"));
        // Its texels' size in the world across the light (a clip unit is 1 / |row| world units, a
        // texel 2 / (its tile's texels) clip units), and window depth per world unit along it.
        const float texelWorld = std::max(2.0f / (glm::length(across) * t.z * float(width)),
                                          2.0f / (glm::length(up) * t.w * float(height)));
        const float depthPerWorld = glm::length(along) * (shadows.reversedZ ? 1.0f : 0.5f);
        const float offset = 1.5f * texelWorld;
        u.viewProj[i] = m;
        u.tile[i] = t;
        u.lookup[i] = {offset, offset * depthPerWorld, float(c.layer),
                       1.5f * std::max(u.texel.x / t.z, u.texel.y / t.w)};
    }
    return u;
}

} // namespace hfx
