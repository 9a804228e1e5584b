#pragma once
// The exact tracer's per-frame data beside a surface's textures: the height-bounds pyramid
// ((max, min) over every cell of every level, level 0 one cell between four texel centres) of
// one SurfaceTextures' current texels, and in the atlas layout (llvmpipe's) the level-0 cells'
// corner samples. hier walks it; the bounded searches read four of its texels per layer.
//
// ExactTracer owns the bounds of every surface it draws (built by BoundsPass from the stored
// texels when they changed); SurfacePipeline owns one per texture pair only where the compute
// device builds them (GlWorkarounds::pyramidFromCompute) and hands them with its layers
// (SurfaceLayer::bounds). A harness of its own over surface/heights.glsl makes one and
// BoundsPass::refresh builds it:
//
//   HeightBounds bounds(textures.config());
//   BoundsPass pass;
//   pass.refresh(textures, bounds); // also binds the atlas layout's cells
//   bounds.bind(0);                 // heights.glsl's layer 0
//
// Its storage is made by the first build or upload. Thread: the thread whose GL context is current.

#include "hfx/core/GlObject.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/core/SurfaceTextures.h"

#include <cstdint>
#include <utility>

namespace hfx {

/// How the bounds are held on the GL side (heights.glsl reads either).
enum class PyramidLayout {
    Auto,     ///< the device's: Atlas where GlWorkarounds::pyramidAtlas says so, else MipChain
    MipChain, ///< an RG32F texture with a mip level per pyramid level, read with texelFetch; the
              ///< level-0 cells' samples gathered from the surface texture (textureGather)
    Atlas,    ///< every level in one RG32F image read with imageLoad, and the level-0 cells'
              ///< samples in an RGBA32F image (cells()): llvmpipe's workaround, where a
              ///< texelFetch with a level per lane is a call
};

/// `layout`, or for Auto the current GL context's (GlWorkarounds::pyramidAtlas).
PyramidLayout resolvedLayout(PyramidLayout layout);
/// `layout`, or for Auto the one `device` says (a caller that holds its context's workarounds).
PyramidLayout resolvedLayout(PyramidLayout layout, const GlWorkarounds& device);

/// Why textures of `config` cannot carry height bounds, empty where they can: the pyramid halves
/// power-of-two sizes, and unorm8 heights round up to 1/510 above a bound, so the exact tracer
/// would miss.
std::string boundsRefusal(const SurfaceTexturesConfig& config);
/// Whether textures of `config` can carry height bounds (boundsRefusal's empty case, without
/// building its message: the tracer asks every draw).
bool carriesBounds(const SurfaceTexturesConfig& config);

class HeightBounds {
public:
    /// Bounds for width x height texels wrapped or clamped as `edges`, in `layout` (Auto: the
    /// current GL context's). Throws hfx::Error naming the size where it is not a power of two.
    HeightBounds(int width, int height, EdgeMode edges, PyramidLayout layout = PyramidLayout::Auto);
    /// Bounds for textures of `config`; throws boundsRefusal's reason where they cannot carry any.
    explicit HeightBounds(const SurfaceTexturesConfig& config, PyramidLayout layout = PyramidLayout::Auto);

    int width() const { return width_; }
    int height() const { return height_; }
    EdgeMode edges() const { return edges_; }
    int levels() const { return levels_; }
    PyramidLayout layout() const { return layout_; } ///< MipChain or Atlas, never Auto
    /// Whether they fit textures of `config`: their size and edges.
    bool fits(const SurfaceTexturesConfig& config) const;
    /// The GL storage they hold, bytes: the pyramid and the cells once made (0 before).
    size_t bytes() const;

    /// The pyramid's texture (made here on first call): an RG32F mip chain, or in the Atlas
    /// layout a single-level RG32F image holding every level side by side (atlasOrigin).
    GLuint pyramid() const;
    /// The Atlas layout's level-0 cells' corner samples (RGBA32F, width x height: per cell the four
    /// heights a gather around its centre reads, in that order), which hier's patch solve reads
    /// in one imageLoad; made on first call, 16 bytes a texel, so bounds only ever searched
    /// hold none. 0 in the MipChain layout (the walk gathers the texels themselves).
    GLuint cells() const;

    /// Whether the pyramid holds the bounds of `textures`' current texels (and the cells their
    /// samples).
    bool holds(const SurfaceTextures& textures) const { return built_ == key(textures); }
    bool cellsHold(const SurfaceTextures& textures) const { return cellsBuilt_ == key(textures); }
    /// Records that the pyramid (the cells) now hold `textures`' current texels: BoundsPass calls it.
    void built(const SurfaceTextures& textures) { built_ = key(textures); }
    void cellsBuilt(const SurfaceTextures& textures) { cellsBuilt_ = key(textures); }
    /// Replaces the pyramid with one built elsewhere from `textures`' current heights ((max, min)
    /// float pairs, every level back to back, level 0 first, each level half the one before, as
    /// compute's BoundsPyramid lays them out; with a buffer bound to GL_PIXEL_UNPACK_BUFFER, an
    /// offset into it) and records it built from them. The heights must be the stored ones (a
    /// float32 surface's), or the bounds would not hold what the tracers read.
    void upload(const void* levels, const SurfaceTextures& textures);

    /// Binds the pyramid where heights.glsl reads layer `layer`'s (0 to 3): texture unit
    /// unit(layer), or in the Atlas layout image unit HFX_IMAGE_PYRAMID + `layer`, read-only.
    /// Throws before the first build.
    void bind(int layer) const;
    /// The texture unit of layer `layer`'s mip-chain pyramid (heights.glsl's s_pyramid*).
    static GLuint unit(int layer);
    /// Where a level's texel (0, 0) lies in the atlas: level 0 (width x height) at the origin,
    /// level 1 to its right at (width, 0), each further level below the one before
    /// (heights.glsl's hfx_atlas_origin computes the same).
    static std::pair<int, int> atlasOrigin(int width, int height, int level);
    /// The atlas's size for width x height bounds: every level inside, none overlapping.
    static std::pair<int, int> atlasSize(int width, int height);

    /// A draw looked for these bounds (the tracer notes it, built or not); takeWanted() says
    /// whether one did since the last call: SurfacePipeline has the device build them only
    /// while they are read.
    void noteWanted() const { wanted_ = true; }
    bool takeWanted() { return std::exchange(wanted_, false); }

private:
    struct Key {
        std::uint64_t uid = 0, version = 0;
        bool operator==(const Key&) const = default;
    };
    static Key key(const SurfaceTextures& t) { return {t.uid(), t.texelsVersion()}; }

    int width_, height_, levels_;
    EdgeMode edges_;
    PyramidLayout layout_;
    mutable GlTexture pyramid_, cells_;
    Key built_, cellsBuilt_;
    mutable bool wanted_ = false;
};

} // namespace hfx
