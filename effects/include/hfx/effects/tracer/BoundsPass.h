#pragma once
// Builds a surface's height bounds (HeightBounds: the pyramid) on the GL side from its stored
// texels (shaders/trace/hier/bounds.comp) when they have changed since the last build, and in
// the atlas layout (PyramidLayout::Atlas, llvmpipe's) the level-0 cells' samples the walk reads
// instead of a gather (HeightBounds::cells). Built from what the GL side holds, the bounds hold
// exactly the heights the tracers read (a float16 surface's rounding included), and nothing but
// the surface crosses from the compute device (on a CPU rasteriser a float32 surface's pyramid
// comes from the device instead, GlWorkarounds::pyramidFromCompute, and the pass builds only the
// cells). ExactTracer runs it before every draw and pass that reads bounds; a program of your
// own over surface/heights.glsl (a compute harness, say) runs it too.
//
// Owns its compute programs. Thread: the thread whose GL context is current.

#include "hfx/core/ShaderProgram.h"
#include "hfx/core/SurfaceTextures.h"
#include "hfx/effects/tracer/HeightBounds.h"

#include <optional>

namespace hfx {

class BoundsPass {
public:
    /// Rebuilds `bounds` from `textures` where they do not hold its current texels (compiling
    /// the program on first use); with `cells`, in the atlas layout, the cells image too and
    /// binds it to image unit HFX_IMAGE_CELLS, read-only (the exact tracer's patch solve reads
    /// it). Changes texture unit HFX_UNIT_SURFACE and image units HFX_IMAGE_BOUNDS_FINER,
    /// HFX_IMAGE_BOUNDS and HFX_IMAGE_CELLS; after a build no program is current. Throws where
    /// the bounds do not fit the textures (HeightBounds::fits).
    void refresh(const SurfaceTextures& textures, HeightBounds& bounds, bool cells = true);

private:
    /// By what it writes (mip chain; atlas; atlas and cells; cells alone), then [1] for level 0
    /// (from the texels)
    std::optional<ShaderProgram> programs_[4][2];
};

} // namespace hfx
