#pragma once
// The GL side of a height field: one texture holding the tangent-space normal in xyz and the
// height in w (h in [0,1], 1 = the polygon surface), so a POM step costs one fetch — RGBA32F,
// RGBA16F or RGBA8 (SurfaceFormat) — plus an RGBA8 albedo texture, an RGBA8 texture of shading
// channels (roughness, ambient occlusion; a decal's fresh fracture and its crater's shadowed
// bowl) and optionally the storage of the height-bounds pyramid, which effects' BoundsPass builds
// from the stored texels after each upload. Storage is allocated once; the upload functions
// refresh it in place every frame. The normals are those of one relief depth, normalDepth,
// which the textures record: the renderer
// rescales them to whatever depth it draws with (SurfaceMaterial::depthScale), so the material
// alone owns the depth.
//
// Owns its textures. Thread: the thread whose GL context is current.

#include "hfx/core/EdgeMode.h"
#include "hfx/core/GlObject.h"
#include "hfx/core/Image.h"
#include "hfx/core/SurfaceFormat.h"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace hfx {

/// How the height-bounds pyramid is held on the GL side (the exact tracer's, heights.glsl).
enum class PyramidLayout {
    Auto,     ///< the device's: Atlas where GlWorkarounds::pyramidAtlas says so, else MipChain
    MipChain, ///< an RG32F texture with a mip level per pyramid level, read with texelFetch; the
              ///< level-0 cells' samples gathered from the surface texture (textureGather)
    Atlas,    ///< every level in one RG32F image read with imageLoad, and the level-0 cells'
              ///< samples in an RGBA32F image (cells(), BoundsPass): llvmpipe's workaround
};

struct SurfaceTexturesConfig {
    int width = 512;
    int height = 512;
    bool mipmaps = true; ///< POM's level-of-detail switch needs them; tests of the search don't
    EdgeMode edges = EdgeMode::Wrap; ///< the textures' wrap modes, and the pyramid walk's
    /// Also a height-bounds pyramid (RG32F: max, min per cell, every level) for the hierarchical
    /// tracer and the bounded searches, built on the GL side from the texels (BoundsPass); needs
    /// power-of-two sizes.
    bool pyramid = false;
    PyramidLayout pyramidLayout = PyramidLayout::Auto; ///< tests and benches pick one side
    /// Storage of normal + height: Float16 halves the memory and the transfer, Unorm8 quarters
    /// them (docs/ACCURACY.md measures what each costs against the exact intersection).
    SurfaceFormat format = SurfaceFormat::Float32;
    /// The relief depth (texture units between h = 1 and h = 0) the stored normals were derived
    /// for. Any positive value is exact for float32; the storage formats keep the most slope
    /// precision when it is near the depth drawn.
    float normalDepth = 0.05f;
    void validate() const; ///< throws hfx::Error naming the bad field and its value
};

class SurfaceTextures {
public:
    explicit SurfaceTextures(const SurfaceTexturesConfig& config);

    /// Replaces the normal+height texels with width*height texels in the storage format's
    /// layout (SurfaceFormat: float4, half4, or RGBA8 as n/2 + 1/2 and h, as SurfacePacker writes
    /// them), row 0 at v = 0: a plain copy, no conversion. Regenerates the mip chain when there
    /// is one. With a buffer bound to GL_PIXEL_UNPACK_BUFFER, `texels` is the offset into it.
    void uploadTexels(const void* texels);
    /// Replaces the pyramid with one built elsewhere from the current texels' heights ((max, min)
    /// float pairs, every level back to back, level 0 (width x height) first, each level half the
    /// one before, as compute's BoundsPyramid lays them out) and marks it current
    /// (GlWorkarounds::pyramidFromCompute: SurfacePipeline on a CPU rasteriser). The heights
    /// must be the stored ones (a float32 surface's), or the bounds would not hold what the
    /// tracers read.
    void uploadPyramid(const float* levels);
    /// Replaces the albedo with width*height RGBA8 texels, row 0 at v = 0 (a device-coloured
    /// field), and regenerates its mip chain.
    void uploadAlbedo(const unsigned char* rgba);
    /// Replaces the albedo with an image (converted here, top row first as files store it); it
    /// must match the surface size or be 1x1 (a solid colour).
    void setAlbedo(const Image& albedo);
    /// Replaces the shading channels with width*height RGBA8 texels, row 0 at v = 0: R the
    /// roughness added to the material's (0: the material's own gloss, 1: fully diffuse), G the
    /// ambient occlusion (1: open, 0: no ambient light), B and A reserved (write 0 and 255).
    /// Until the first upload: roughness 0, occlusion 1, which draws as without the texture.
    void uploadChannels(const unsigned char* rgba);

    GLuint surface() const { return surface_.id(); }
    /// The pyramid's texture, 0 without one: an RG32F mip chain, or in the Atlas layout a
    /// single-level RG32F image holding every level side by side (pyramidAtlasOrigin). It holds
    /// the current texels' bounds once pyramidCurrent() (BoundsPass::refresh builds them).
    GLuint pyramid() const { return pyramid_.id(); }
    /// Whether the pyramid holds the current texels' bounds; pyramidBuilt() records that it does
    /// (the builder calls it: the cache's state, not the surface's, hence const).
    bool pyramidCurrent() const { return pyramidVersion_ == texelsVersion_; }
    void pyramidBuilt() const { pyramidVersion_ = texelsVersion_; }
    int pyramidLevels() const { return pyramidLevels_; }
    PyramidLayout pyramidLayout() const { return layout_; } ///< MipChain or Atlas, never Auto
    /// Binds the pyramid where heights.glsl reads layer `layer`'s (0 to 3): the texture unit
    /// pyramidUnit(layer), or in the Atlas layout image unit HFX_IMAGE_PYRAMID + `layer`,
    /// read-only (hfx/core/Bindings.h). Throws without a pyramid, or where it is older than the
    /// texels (BoundsPass::refresh first).
    void bindPyramid(int layer) const;
    /// The texture unit of layer `layer`'s mip-chain pyramid (heights.glsl's s_pyramid*).
    static GLuint pyramidUnit(int layer);
    /// Where a pyramid level's texel (0, 0) lies in the image: level 0 (width x height) at the
    /// origin, level 1 to its right at (width, 0), each further level below the one before
    /// (heights.glsl's hfx_atlas_origin computes the same). llvmpipe reads an image with
    /// imageLoad at 0.6x the cost of a texelFetch with a level per lane, which is a call.
    static std::pair<int, int> pyramidAtlasOrigin(int width, int height, int level);
    /// The image's size for a width x height pyramid: every level inside, none overlapping.
    static std::pair<int, int> pyramidAtlasSize(int width, int height);
    /// In the Atlas layout, the level-0 cells' corner samples (RGBA32F, width x height: per cell
    /// the four heights a gather around its centre reads, in that order), which the exact
    /// tracer's patch solve reads in one imageLoad. A cache of the texels, built on the GL side
    /// (effects' BoundsPass, with the pyramid) after each uploadTexels; 0 without a pyramid or in
    /// the MipChain layout (the walk gathers the texels themselves). Allocated on the first call (16 bytes a
    /// texel), so surfaces never drawn with hier (the ocean's layers) hold none.
    GLuint cells() const;
    /// Whether the cells hold the current texels; cellsBuilt() records that they do (the builder
    /// calls it: the cache's state, not the surface's, hence const).
    bool cellsCurrent() const { return cellsVersion_ == texelsVersion_; }
    void cellsBuilt() const { cellsVersion_ = texelsVersion_; }
    GLuint albedo() const { return albedo_.id(); }
    GLuint channels() const { return channels_.id(); }
    const SurfaceTexturesConfig& config() const { return config_; }
    int levels() const { return levels_; }
    /// Unique to these textures in this process (never reused): with texelsVersion(), what a
    /// cache of something derived from the texels keys on (ExactTracer's texel shadows).
    std::uint64_t uid() const { return uid_; }
    /// Counts uploadTexels: changes whenever the heights may have.
    std::uint64_t texelsVersion() const { return texelsVersion_; }

private:
    SurfaceTexturesConfig config_;
    std::uint64_t uid_;
    int levels_ = 1;
    int pyramidLevels_ = 0;
    PyramidLayout layout_ = PyramidLayout::MipChain;
    GlTexture surface_, albedo_, channels_, pyramid_;
    mutable GlTexture cells_;
    std::uint64_t texelsVersion_ = 1; ///< counts uploadTexels
    mutable std::uint64_t cellsVersion_ = 0; ///< the texels' version the cells were built from
    mutable std::uint64_t pyramidVersion_ = 0; ///< ... and the pyramid
};

} // namespace hfx
