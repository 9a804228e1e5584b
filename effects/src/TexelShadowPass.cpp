#include "hfx/effects/TexelShadowPass.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/SurfaceUniforms.h"

#include "GlStateGuard.h"

#include <cmath>

namespace hfx {

namespace {
ShaderProgram texelProgram(bool clearance, bool atlas) {
    return ShaderProgram(surfaceStage("sky.vert"), surfaceStage("surface/texelshadows.frag"),
                         {{"HFX_LAYERS", "1"}, {"HFX_CLEARANCE", clearance ? "1" : "0"}, {"HFX_TEXEL_SHADOWS", "0"},
                          {"HFX_PYRAMID_ATLAS", atlas ? "1" : "0"}});
}
} // namespace

bool texelShadowsPay(double pixels, double texels, bool drawing) {
    if (!(texels > 0.0) || !(pixels >= 0.0)) return false;
    return pixels >= (drawing ? 1.5 : 1.75) * texels;
}

int texelShadowStride(double pixels, int width, int height, float pixelBudget, int drawing) {
    if (width < 1 || height < 1 || !(pixels >= 0.0)) return 0;
    const double texels = double(width) * height;
    if (texelShadowsPay(pixels, texels, drawing == 1)) return 1;
    const double pixelsPerSample = std::sqrt(pixels / texels); // on each axis, at stride 1
    for (int stride = 2; SurfaceTextures::isTexelStride(stride, width, height); stride *= 2) {
        if (!(stride * pixelsPerSample <= pixelBudget)) return 0;
        if (texelShadowsPay(pixels, texels / (double(stride) * stride), drawing == stride)) return stride;
    }
    return 0;
}

TexelShadowPass::TexelShadowPass() : framebuffer_(GlFramebuffer::create()), empty_(GlVertexArray::create()) {}

void TexelShadowPass::draw(SurfaceTextures& textures, const ClearanceLight& light, int stride) {
    if (!textures.pyramid())
        throw Error("TexelShadowPass::draw: the surface needs its height pyramid (SurfaceOptions::pyramid)");
    light.validate();
    const bool clearance = textures.clearanceLight() == light;
    const bool atlas = textures.pyramidLayout() == PyramidLayout::Atlas;
    std::optional<ShaderProgram>& program = programs_[clearance ? 1 : 0][atlas ? 1 : 0];
    if (!program) program = texelProgram(clearance, atlas);
    const SurfaceTexturesConfig& config = textures.config();
    const GLuint target = textures.texelShadowTarget(stride); // throws for a bad stride
    const int width = config.width / stride, height = config.height / stride;
    GlStateGuard guard;
    bounds_.refresh(textures); // the pyramid, and the atlas layout's patch samples (uses its own program)
    const GpuScope scope("texel shadows");
    attachPassTarget(framebuffer_, target, width, height, "R32F", "TexelShadowPass");
    const PassTarget pass(framebuffer_, width, height); // whatever blending or scissor the caller left
    SurfaceUniforms u{.pyramidLevels = textures.pyramidLevels(),
                      .wrap = wrapFlags(config.edges),
                      .clearance = {light.uvPerClimb, light.penumbra, light.slack}};
    updateBlock(block_, HFX_BLOCK_SURFACE, u);
    glDisable(GL_DEPTH_TEST);
    program->use();
    program->set("u_texelStride", stride);
    glBindTextureUnit(HFX_UNIT_SURFACE, textures.surface());
    textures.bindPyramid(0);
    glBindTextureUnit(HFX_UNIT_CLEARANCE, clearance ? textures.clearance() : 0);
    glBindVertexArray(empty_.id());
    HFX_GL_CHECK(glDrawArrays(GL_TRIANGLES, 0, 3));
    textures.texelShadowsDrawn(light);
}

} // namespace hfx
