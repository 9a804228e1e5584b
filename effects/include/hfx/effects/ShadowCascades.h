#pragma once
// A directional light's shadow maps of an engine's own (the cascades of its sun's shadow, in the
// tiles of an atlas or the layers of an array texture), for the surfaces and lit flat meshes that
// HFX draws under the light (DirectionalLight::cascades) to receive the engine's shadows, as they
// receive a ShadowMap's. The engine draws its casters into them, HFX's relief among them
// (SurfaceRenderer::drawShadow with each cascade's view as a Camera).
//
// A value type over the caller's cascades (a span: the caller keeps them alive while drawing).
// Thread: any; shadowUniforms() reads the texture's size and format from GL (the context's thread).

#include "hfx/core/Gl.h"
#include "hfx/effects/SurfaceUniforms.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <span>

namespace hfx {

/// One cascade: the orthographic view-projection its casters were drawn with, where in the
/// texture they were drawn, and the layer of an array texture.
struct ShadowCascade {
    glm::mat4 viewProj{1.0f}; ///< world to its clip space: an orthographic projection (a directional light's)
    /// The viewport its casters were drawn in, as x, y, width, height in the texture's [0, 1]
    /// coordinates: a tile of an atlas (the whole texture by default).
    glm::vec4 tile{0.0f, 0.0f, 1.0f, 1.0f};
    int layer = 0; ///< its layer of a GL_TEXTURE_2D_ARRAY (0 for a GL_TEXTURE_2D)
};

struct ShadowCascades {
    /// The engine's depth texture (GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY, a depth format), read
    /// through a comparison sampler of HFX's own: its own filtering and compare state are left as
    /// they are.
    GLuint texture = 0;
    /// The depth convention its casters were drawn with: GL's default (depth cleared to 1, nearer
    /// less), or reversed (GL_ZERO_TO_ONE, cleared to 0, nearer greater). The depth range 0 to 1.
    bool reversedZ = false;
    /// 1 to kMaxShadowCascades cascades, finest first: a point reads the first whose tile holds it
    /// with the filter's reach (1.5 texels), and is lit where none does.
    std::span<const ShadowCascade> cascades;
};

/// The receiving block of a draw under `shadows`: each cascade's transform and tile, its normal
/// offset and depth bias (1.5 of its texels, as a ShadowMap's), its layer. Throws hfx::Error
/// naming the problem: no cascade or more than kMaxShadowCascades, a matrix not finite or not
/// orthographic, a tile outside the texture or empty, a layer outside the array (or not 0 for a
/// 2D texture), a name that is no texture, a texture neither 2D nor 2D array, or not of a depth
/// format. Also returns its kind through `arrayTexture` (HFX_SHADOW_MAP 2 where it is an array).
ShadowUniforms shadowUniforms(const ShadowCascades& shadows, bool& arrayTexture);

} // namespace hfx
