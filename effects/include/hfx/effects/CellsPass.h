#pragma once
// In the atlas layout (PyramidLayout::Atlas, llvmpipe's), builds a surface's level-0 cells image
// (SurfaceTextures::cells, shaders/surface/cells.comp) from its stored texels when they have
// changed since the last build, and binds it where the exact tracer reads it; in the mip-chain
// layout the walk gathers the texels themselves, and it does nothing. SurfaceRenderer and TexelShadowPass run it before every hier draw and
// pass; a program of your own over surface/heights.glsl (a compute harness, say) runs it too.
//
// Owns its compute program. Thread: the thread whose GL context is current.

#include "hfx/core/ShaderProgram.h"
#include "hfx/core/SurfaceTextures.h"

#include <optional>

namespace hfx {

class CellsPass {
public:
    /// Atlas layout: rebuilds the cells of `textures` if their texels changed since (compiling
    /// the program on first use), then binds them to image unit HFX_IMAGE_CELLS, read-only; also changes
    /// texture unit 0 and the current program. Mip chain: nothing. Throws for textures without a
    /// pyramid.
    void refresh(const SurfaceTextures& textures);

private:
    std::optional<ShaderProgram> program_;
};

} // namespace hfx
