#include "hfx/effects/TexelShadowPass.h"

#include "hfx/core/Error.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/SurfaceUniforms.h"

#include "GlStateGuard.h"

namespace hfx {

namespace {
ShaderProgram texelProgram(bool clearance) {
    return ShaderProgram({surfaceShader("sky.vert")},
                         {surfaceShader("surface/uniforms.glsl"), surfaceShader("surface/heights.glsl"),
                          surfaceShader("trace/common.glsl"), surfaceShader("trace/hier.glsl"),
                          surfaceShader("surface/texelshadows.frag")},
                         {{"HFX_LAYERS", "1"}, {"HFX_CLEARANCE", clearance ? "1" : "0"}, {"HFX_TEXEL_SHADOWS", "0"}});
}
} // namespace

bool texelShadowsPay(double pixels, double texels, bool drawing) {
    if (!(texels > 0.0) || !(pixels >= 0.0)) return false;
    return pixels >= (drawing ? 1.5 : 1.75) * texels;
}

TexelShadowPass::TexelShadowPass() : framebuffer_(GlFramebuffer::create()), empty_(GlVertexArray::create()) {}

void TexelShadowPass::draw(SurfaceTextures& textures, const ClearanceLight& light) {
    if (!textures.pyramid())
        throw Error("TexelShadowPass::draw: the surface needs its height pyramid (SurfaceOptions::pyramid)");
    light.validate();
    const bool clearance = textures.clearanceLight() == light;
    std::optional<ShaderProgram>& program = programs_[clearance ? 1 : 0];
    if (!program) program = texelProgram(clearance);
    const SurfaceTexturesConfig& config = textures.config();
    const GLuint target = textures.texelShadowTarget();
    GlStateGuard guard;
    attachPassTarget(framebuffer_, target, config.width, config.height, "R32F", "TexelShadowPass");
    const PassTarget pass(framebuffer_, config.width, config.height); // whatever blending or scissor the caller left
    SurfaceUniforms u{.pyramidLevels = textures.pyramidLevels(),
                      .wrap = {wrapsU(config.edges) ? 1 : 0, wrapsV(config.edges) ? 1 : 0},
                      .clearance = {light.uvPerClimb, light.penumbra, light.slack}};
    updateBlock(block_, 0, u);
    glDisable(GL_DEPTH_TEST);
    program->use();
    glBindTextureUnit(0, textures.surface());
    glBindTextureUnit(3, textures.pyramid());
    glBindTextureUnit(15, clearance ? textures.clearance() : 0);
    glBindVertexArray(empty_.id());
    HFX_GL_CHECK(glDrawArrays(GL_TRIANGLES, 0, 3));
    textures.texelShadowsDrawn(light);
}

} // namespace hfx
