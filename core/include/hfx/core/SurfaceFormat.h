#pragma once
// How a surface's normal + height texels are stored on the GPU, and so how many bytes a frame's
// transfer moves. The compute side packs into the same layout (hfx::SurfacePacker), so the GL
// upload is a plain copy with no conversion in the driver.
//
// Thread: any (plain values).

#include <cstddef>
#include <string>
#include <string_view>

namespace hfx {

enum class SurfaceFormat {
    Float32, ///< RGBA32F, texel = 4 floats (16 bytes): exact
    Float16, ///< RGBA16F, texel = 4 halves (8 bytes): heights to 2^-11 near 1, round to nearest even
    /// RGBA8, texel = 4 bytes (n/2 + 1/2, h), round to nearest: heights in steps of 1/255. Its
    /// rounding can lift a height above a float pyramid's maximum, so it takes no pyramid.
    Unorm8,
    /// The device's, chosen where a surface is made (SurfacePipeline: hfx::chooseSurfaceFormat):
    /// Float16 on a GPU, Float32 on a CPU rasteriser (GlWorkarounds::float32Surfaces). Textures
    /// and packers take a resolved format only.
    Auto,
};

/// The stored formats (Auto is none).
inline constexpr SurfaceFormat kSurfaceFormats[] = {SurfaceFormat::Float32, SurfaceFormat::Float16,
                                                    SurfaceFormat::Unorm8};

/// Bytes of one texel in the format's layout; throws hfx::Error for Auto.
size_t texelBytes(SurfaceFormat format);
/// "float32", "float16", "unorm8", "auto".
const char* surfaceFormatName(SurfaceFormat format);
/// The inverse of surfaceFormatName; throws hfx::Error naming the known formats.
SurfaceFormat parseSurfaceFormat(std::string_view name);

} // namespace hfx
