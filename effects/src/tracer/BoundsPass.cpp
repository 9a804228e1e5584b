#include "hfx/effects/tracer/BoundsPass.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <algorithm>

namespace hfx {

void BoundsPass::refresh(const SurfaceTextures& textures, HeightBounds& bounds, bool cells) {
    const SurfaceTexturesConfig& c = textures.config();
    if (!bounds.fits(c))
        throw Error(str("BoundsPass: the bounds are ", bounds.width(), "x", bounds.height(), ", ",
                        edgeModeName(bounds.edges()), "; the textures ", c.width, "x", c.height, ", ",
                        edgeModeName(c.edges)));
    const bool atlas = bounds.layout() == PyramidLayout::Atlas;
    cells = cells && atlas; // a mip chain's walk gathers the texels themselves
    if (!bounds.holds(textures) || (cells && !bounds.cellsHold(textures))) {
        const GpuScope scope("bounds");
        // Where the pyramid came from elsewhere (HeightBounds::upload) and only the cells are
        // stale, one level-0 dispatch writes them alone.
        const bool cellsOnly = bounds.holds(textures);
        const int variant = !atlas ? 0 : !cells ? 1 : cellsOnly ? 3 : 2;
        auto program = [&](bool level0) -> const ShaderProgram& {
            std::optional<ShaderProgram>& p = programs_[variant][level0 ? 1 : 0];
            if (!p)
                p = ShaderProgram::compute(surfaceStage("trace/hier/bounds.comp"),
                                           {{"HFX_PYRAMID_ATLAS", atlas ? "1" : "0"},
                                            {"HFX_BOUNDS_CELLS", cells && level0 ? "1" : "0"},
                                            {"HFX_BOUNDS_LEVEL0", level0 ? "1" : "0"},
                                            {"HFX_BOUNDS_PYRAMID", cellsOnly ? "0" : "1"}});
            return *p;
        };
        const GLuint pyramid = bounds.pyramid();
        glBindTextureUnit(HFX_UNIT_SURFACE, textures.surface());
        if (cells)
            HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_CELLS, bounds.cells(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F));
        const int levels = cellsOnly ? 1 : bounds.levels();
        if (atlas) { // every level in one image, read and written at the levels' origins
            HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_BOUNDS_FINER, pyramid, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RG32F));
            HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_BOUNDS, pyramid, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F));
        }
        for (int level = 0; level < levels; ++level) {
            const ShaderProgram& p = program(level == 0);
            p.use();
            p.set("u_wrap", wrapFlags(c.edges));
            const int w = std::max(c.width >> level, 1), h = std::max(c.height >> level, 1);
            if (atlas) {
                const auto [x, y] = HeightBounds::atlasOrigin(c.width, c.height, level);
                const auto [fx, fy] = HeightBounds::atlasOrigin(c.width, c.height, std::max(level - 1, 0));
                p.set("u_origin", glm::ivec2(x, y));
                p.set("u_finerOrigin", glm::ivec2(fx, fy));
            } else {
                p.set("u_origin", glm::ivec2(0));
                p.set("u_finerOrigin", glm::ivec2(0));
                HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_BOUNDS_FINER, pyramid, std::max(level - 1, 0), GL_FALSE, 0,
                                                GL_READ_ONLY, GL_RG32F));
                HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_BOUNDS, pyramid, level, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F));
            }
            p.set("u_size", glm::ivec2(w, h));
            p.set("u_finerSize", glm::ivec2(std::max(c.width >> std::max(level - 1, 0), 1),
                                                   std::max(c.height >> std::max(level - 1, 0), 1)));
            p.dispatchOver(w, h);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT); // the next level reads this one
        }
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT); // a mip chain's walk reads them as a texture
        glUseProgram(0); // none left current: a pass that goes first would leave a deleted program in use
        bounds.built(textures);
        if (cells) bounds.cellsBuilt(textures);
    }
    if (cells)
        HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_CELLS, bounds.cells(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F));
}

} // namespace hfx
