#include "hfx/core/SurfaceFormat.h"

#include "hfx/core/Error.h"

namespace hfx {

size_t texelBytes(SurfaceFormat format) {
    switch (format) {
    case SurfaceFormat::Float32: return 16;
    case SurfaceFormat::Float16: return 8;
    case SurfaceFormat::Unorm8: return 4;
    }
    throw Error(str("unknown surface format ", int(format)));
}

const char* surfaceFormatName(SurfaceFormat format) {
    switch (format) {
    case SurfaceFormat::Float32: return "float32";
    case SurfaceFormat::Float16: return "float16";
    case SurfaceFormat::Unorm8: return "unorm8";
    }
    return "unknown";
}

SurfaceFormat parseSurfaceFormat(std::string_view name) {
    for (SurfaceFormat f : kSurfaceFormats)
        if (name == surfaceFormatName(f)) return f;
    throw Error(str("unknown surface format '", name, "' (known: float32, float16, unorm8)"));
}

} // namespace hfx
