#include "hfx/effects/tracer/TexelShadowPass.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/SurfaceUniforms.h"

#include "../GlStateGuard.h"

#include <cmath>

namespace hfx {

namespace {
ShaderProgram texelProgram(bool atlas) {
    return ShaderProgram::compute(surfaceStage("trace/hier/texelshadows.comp"),
                                  {{"HFX_LAYERS", "1"}, {"HFX_PYRAMID_ATLAS", atlas ? "1" : "0"}});
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
    for (int stride = 2; isTexelStride(stride, width, height); stride *= 2) {
        if (!(stride * pixelsPerSample <= pixelBudget)) return 0;
        if (texelShadowsPay(pixels, texels / (double(stride) * stride), drawing == stride)) return stride;
    }
    return 0;
}

void TexelShadowPass::draw(const SurfaceTextures& textures, HeightBounds& bounds, const ShadowLight& light, int stride,
                           TexelShadows& into) {
    const SurfaceTexturesConfig& config = textures.config();
    if (!bounds.fits(config))
        throw Error(str("TexelShadowPass::draw: the height bounds are ", bounds.width(), "x", bounds.height(),
                        ", the surface ", config.width, "x", config.height, " (or their edges differ)"));
    light.validate();
    if (!isTexelStride(stride, config.width, config.height))
        throw Error(str("TexelShadowPass::draw: the texel shadows' stride must be a power of two that divides the "
                        "field's ", config.width, "x", config.height, " samples, got ", stride));
    const bool atlas = bounds.layout() == PyramidLayout::Atlas;
    std::optional<ShaderProgram>& program = programs_[atlas ? 1 : 0];
    if (!program) program = texelProgram(atlas);
    const int width = config.width / stride, height = config.height / stride;
    if (!into.texture_ || into.width_ != width || into.height_ != height || into.edges_ != config.edges) {
        into = TexelShadows();
        into.texture_ = GlTexture::create();
        HFX_GL_CHECK(glTextureStorage2D(into.texture_.id(), 1, GL_R32F, width, height));
        // Read by textureGather around a point: the four samples of its cell, wrapped or clamped
        // as the heights are.
        const GLuint t = into.texture_.id();
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_WRAP_S, wrapsU(config.edges) ? GL_REPEAT : GL_CLAMP_TO_EDGE);
        glTextureParameteri(t, GL_TEXTURE_WRAP_T, wrapsV(config.edges) ? GL_REPEAT : GL_CLAMP_TO_EDGE);
        into.width_ = width;
        into.height_ = height;
        into.edges_ = config.edges;
    }
    into.drawn_ = false; // until this draw has written them
    GlStateGuard guard;
    bounds_.refresh(textures, bounds); // where stale, and the atlas layout's patch samples (its own program)
    const GpuScope scope("texel shadows");
    SurfaceUniforms u{.shadowLight = {light.uvPerClimb, light.penumbra, light.slack}};
    u.setField({config.width, config.height}, config.edges);
    updateBlock(block_, HFX_BLOCK_SURFACE, u);
    program->use();
    program->set("u_texelStride", stride);
    glBindTextureUnit(HFX_UNIT_SURFACE, textures.surface());
    bounds.bind(0);
    HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_PASS_OUTPUT, into.texture_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                                    GL_R32F));
    program->dispatchOver(width, height);
    // The surface draw gathers them; a reader may copy them out (glGetTextureImage: the tests).
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    into.stride_ = stride;
    into.light_ = light;
    into.uid_ = textures.uid();
    into.version_ = textures.texelsVersion();
    into.drawn_ = true;
}

} // namespace hfx
