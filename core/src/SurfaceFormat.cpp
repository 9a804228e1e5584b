#include "hfx/core/SurfaceFormat.h"

#include "hfx/core/Error.h"
#include "hfx/core/Names.h"

namespace hfx {

size_t texelBytes(SurfaceFormat format) {
    switch (format) {
    case SurfaceFormat::Float32: return 16;
    case SurfaceFormat::Float16: return 8;
    case SurfaceFormat::Unorm8: return 4;
    case SurfaceFormat::Auto:
        throw Error("texelBytes: the surface format auto has no layout until it is chosen (chooseSurfaceFormat)");
    }
    throw Error(str("unknown surface format ", int(format)));
}

namespace {
constexpr NamedValue<SurfaceFormat> kNames[] = {
    {SurfaceFormat::Float32, "float32"},
    {SurfaceFormat::Float16, "float16"},
    {SurfaceFormat::Unorm8, "unorm8"},
    {SurfaceFormat::Auto, "auto"}};
}

const char* surfaceFormatName(SurfaceFormat format) { return nameOf(kNames, format); }

SurfaceFormat parseSurfaceFormat(std::string_view name) { return parseName(kNames, name, "surface format"); }

} // namespace hfx
