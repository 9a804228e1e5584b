#include "hfx/effects/CellsPass.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/effects/SurfaceRenderer.h"

namespace hfx {

void CellsPass::refresh(const SurfaceTextures& textures) {
    if (!textures.pyramid()) throw Error("CellsPass: these surface textures were made without a pyramid");
    if (textures.pyramidLayout() == PyramidLayout::MipChain) return; // the walk gathers the texels
    if (!textures.cellsCurrent()) {
        const GpuScope scope("cells");
        if (!program_) program_ = ShaderProgram::compute(surfaceStage("surface/cells.comp"));
        const SurfaceTexturesConfig& c = textures.config();
        program_->use();
        program_->set("u_wrap", wrapFlags(c.edges));
        glBindTextureUnit(HFX_UNIT_SURFACE, textures.surface());
        HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_CELLS, textures.cells(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F));
        HFX_GL_CHECK(glDispatchCompute(GLuint((c.width + 7) / 8), GLuint((c.height + 7) / 8), 1));
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        textures.cellsBuilt();
    }
    HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_CELLS, textures.cells(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F));
}

} // namespace hfx
