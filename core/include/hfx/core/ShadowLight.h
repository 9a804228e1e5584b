#pragma once
// A directional light as the exact shadow walk sees it on a flat surface (the same light ray
// direction at every point): what the texel shadows (effects' TexelShadowPass) are drawn for and
// what the renderer checks a shadow ray against before it reads them (shaders/surface/
// heights.glsl: a ray whose direction or penumbra they were not drawn for is walked).
//
// Thread: any (plain values).

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>

namespace hfx {

struct ShadowLight {
    /// The light ray's move per unit of height climbed, in the surface's texcoords: for tangent-
    /// space light L, L.xy / L.z * SurfaceMaterial::depthScale (shaders/surface.frag's span).
    glm::vec2 uvPerClimb{0.0f};
    /// 1 / SurfaceMaterial::shadowSharpness: rays with this penumbra read the texel shadows.
    float penumbra = 0.5f;
    /// Rays whose uvPerClimb is within this of the light's on each axis read them (interpolated
    /// tangent frames round).
    float slack = 0.0f;

    /// The light of a material whose shadow sharpness is `sharpness`, with a slack of 1e-3 of
    /// the move (a flat mesh's tangent frames agree to about 1e-7).
    static ShadowLight of(glm::vec2 uvPerClimb, float sharpness) {
        const float move = std::max(std::abs(uvPerClimb.x), std::abs(uvPerClimb.y));
        return {uvPerClimb, 1.0f / sharpness, 1e-3f * move + 1e-7f}; // validate() refuses a sharpness <= 1
    }
    void validate() const {
        if (!isFinite(uvPerClimb)) throw Error(str("ShadowLight.uvPerClimb must be finite, got ", text(uvPerClimb)));
        if (!(penumbra >= 0.0f && penumbra <= 0.999f))
            throw Error(str("ShadowLight.penumbra must be in [0, 0.999] (a shadow sharpness above 1), got ",
                            penumbra));
        if (!(slack >= 0.0f) || !std::isfinite(slack))
            throw Error(str("ShadowLight.slack must be finite and not negative, got ", slack));
    }
    bool operator==(const ShadowLight&) const = default;
};

} // namespace hfx
