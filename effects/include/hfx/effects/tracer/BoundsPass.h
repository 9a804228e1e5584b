#pragma once
// Builds a surface's height-bounds pyramid (SurfaceTextures::pyramid) on the GL side from its
// stored texels (shaders/trace/hier/bounds.comp) when they have changed since the last build, and
// in the atlas layout (PyramidLayout::Atlas, llvmpipe's) the level-0 cells' samples the walk
// reads instead of a gather (SurfaceTextures::cells). Built from what the GL side holds, the
// bounds hold exactly the heights the tracers read (a float16 surface's rounding included), and
// nothing but the surface crosses from the compute device (on a CPU rasteriser a float32
// surface's pyramid comes from the device instead, GlWorkarounds::pyramidFromCompute, and the
// pass builds only the cells). SurfaceRenderer and TexelShadowPass run it before every draw and
// pass that reads a pyramid; a program of your own over surface/heights.glsl (a compute harness,
// say) runs it too.
//
// Owns its compute programs. Thread: the thread whose GL context is current.

#include "hfx/core/ShaderProgram.h"
#include "hfx/core/SurfaceTextures.h"

#include <optional>

namespace hfx {

class BoundsPass {
public:
    /// Rebuilds the pyramid of `textures` if their texels changed since (compiling the program
    /// on first use); with `cells`, in the atlas layout, the cells image too and binds it to
    /// image unit HFX_IMAGE_CELLS, read-only (the exact tracer's patch solve reads it). Changes
    /// texture unit HFX_UNIT_SURFACE and image units HFX_IMAGE_BOUNDS_FINER, HFX_IMAGE_BOUNDS and
    /// HFX_IMAGE_CELLS; after a build no program is current. Throws for textures without a pyramid.
    void refresh(const SurfaceTextures& textures, bool cells = true);

private:
    /// By what it writes (mip chain; atlas; atlas and cells; cells alone), then [1] for level 0
    /// (from the texels)
    std::optional<ShaderProgram> programs_[4][2];
};

} // namespace hfx
