#pragma once
// A directional light as the exact shadow walk sees it on a flat surface (the same light ray
// direction at every point): what a clearance map (compute/ClearanceMap.h) is built for and
// what the renderer checks a shadow ray against before it trusts the map (shaders/trace/
// hier.glsl: a ray whose direction or penumbra the map was not built for walks without it).
//
// Thread: any (plain values).

#include "hfx/core/Error.h"

#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>

namespace hfx {

struct ClearanceLight {
    /// The light ray's move per unit of height climbed, in the surface's texcoords: for tangent-
    /// space light L, L.xy / L.z * SurfaceMaterial::depthScale (shaders/surface.frag's span).
    glm::vec2 uvPerClimb{0.0f};
    /// 1 / SurfaceMaterial::shadowSharpness: rays with this penumbra or a narrower one use the map.
    float penumbra = 0.5f;
    /// Rays whose uvPerClimb is within this of the map's on each axis use it (interpolated
    /// tangent frames round); the map is built for all of them.
    float slack = 0.0f;

    /// The light of a material whose shadow sharpness is `sharpness`, with a slack of 1e-3 of
    /// the move (a flat mesh's tangent frames agree to about 1e-7).
    static ClearanceLight of(glm::vec2 uvPerClimb, float sharpness) {
        const float move = std::max(std::abs(uvPerClimb.x), std::abs(uvPerClimb.y));
        return {uvPerClimb, 1.0f / sharpness, 1e-3f * move + 1e-7f}; // validate() refuses a sharpness <= 1
    }
    void validate() const {
        if (!std::isfinite(uvPerClimb.x) || !std::isfinite(uvPerClimb.y))
            throw Error(str("ClearanceLight.uvPerClimb must be finite, got (", uvPerClimb.x, ", ", uvPerClimb.y, ")"));
        if (!(penumbra >= 0.0f && penumbra <= 0.999f))
            throw Error(str("ClearanceLight.penumbra must be in [0, 0.999] (a shadow sharpness above 1), got ",
                            penumbra));
        if (!(slack >= 0.0f) || !std::isfinite(slack))
            throw Error(str("ClearanceLight.slack must be finite and not negative, got ", slack));
    }
    bool operator==(const ClearanceLight&) const = default;
};

} // namespace hfx
