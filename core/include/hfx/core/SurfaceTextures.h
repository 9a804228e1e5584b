#pragma once
// The GL side of a height field: one texture holding the tangent-space normal in xyz and the
// height in w (h in [0,1], 1 = the polygon surface), so a POM step costs one fetch — RGBA32F,
// RGBA16F or RGBA8 (SurfaceFormat) — plus an RGBA8 albedo texture and an RGBA8 texture of shading
// channels (roughness, ambient occlusion; a decal's fresh fracture and its crater's shadowed
// bowl). What a technique derives from them per frame (the exact tracer's height bounds) is the
// technique's (effects' tracer/). Storage is allocated once; the upload functions
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
#include "hfx/core/Uid.h"

#include <cstdint>
#include <vector>

namespace hfx {

struct SurfaceTexturesConfig {
    int width = 512;
    int height = 512;
    bool mipmaps = true; ///< POM's level-of-detail switch needs them; tests of the search don't
    EdgeMode edges = EdgeMode::Wrap; ///< the textures' wrap modes, and the pyramid walk's
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
    /// Replaces the albedo with width*height RGBA8 texels, row 0 at v = 0 (a device-coloured
    /// field), and regenerates its mip chain.
    void uploadAlbedo(const unsigned char* rgba);
    /// Replaces the albedo with an image (converted here, top row first as files store it); it
    /// must match the surface size or be 1x1 (a solid colour).
    void setAlbedo(const Image& albedo);
    /// Replaces the shading channels with width*height RGBA8 texels, row 0 at v = 0: R the
    /// roughness added to the material's (0: the material's own gloss, 1: fully diffuse), G the
    /// ambient occlusion (1: open, 0: no ambient light), B reserved (write 0), A the heat the
    /// lit shading emits as embers (0: none, 1: yellow white; a decal's fresh crater).
    /// Until the first upload: roughness 0, occlusion 1, no heat, which draws as without it.
    void uploadChannels(const unsigned char* rgba);

    GLuint surface() const { return surface_.id(); }
    GLuint albedo() const { return albedo_.id(); }
    GLuint channels() const { return channels_.id(); }
    const SurfaceTexturesConfig& config() const { return config_; }
    int levels() const { return levels_; }
    /// Unique to these textures in this process (never reused): with texelsVersion(), what a
    /// cache of something derived from the texels keys on (the exact tracer's bounds and texel
    /// shadows).
    std::uint64_t uid() const { return uid_.value(); }
    /// Counts uploadTexels: changes whenever the heights may have.
    std::uint64_t texelsVersion() const { return texelsVersion_; }

private:
    SurfaceTexturesConfig config_;
    Uid uid_;
    int levels_ = 1;
    GlTexture surface_, albedo_, channels_;
    std::uint64_t texelsVersion_ = 1; ///< counts uploadTexels
};

} // namespace hfx
