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
};

inline constexpr SurfaceFormat kSurfaceFormats[] = {SurfaceFormat::Float32, SurfaceFormat::Float16,
                                                    SurfaceFormat::Unorm8};

/// Bytes of one texel in the format's layout.
size_t texelBytes(SurfaceFormat format);
/// "float32", "float16", "unorm8".
const char* surfaceFormatName(SurfaceFormat format);
/// The inverse of surfaceFormatName; throws hfx::Error naming the known formats.
SurfaceFormat parseSurfaceFormat(std::string_view name);

} // namespace hfx
