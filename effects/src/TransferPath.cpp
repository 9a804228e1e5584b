#include "hfx/effects/TransferPath.h"

#include "ExternalMemory.h"

#include "hfx/core/Error.h"
#include "hfx/core/Names.h"

namespace hfx {

namespace {
constexpr NamedValue<TransferPath> kNames[] = {{TransferPath::Auto, "auto"},
                                               {TransferPath::Map, "map"},
                                               {TransferPath::PixelBuffer, "pixel-buffer"},
                                               {TransferPath::Staged, "staged"},
                                               {TransferPath::GlSharing, "gl-sharing"},
                                               {TransferPath::ExternalMemory, "external-memory"}};
}

const char* transferPathName(TransferPath path) { return nameOf(kNames, path); }

TransferPath parseTransferPath(std::string_view name) { return parseName(kNames, name, "transfer path"); }

std::string transferPathRefusal(const ClContext& cl, TransferPath path) {
    if (path == TransferPath::GlSharing && !cl.sharesGl())
        return str("the gl-sharing transfer path needs an OpenCL context made with the GL context it draws in "
                   "(cl_khr_gl_sharing for it; ClContextConfig::glShare); ",
                   cl.description(), " shares none here (NVIDIA offers it for GLX windows, not for EGL)");
    if (path == TransferPath::ExternalMemory) return ExternalMemory::unavailable(cl);
    return "";
}

TransferPath chooseTransferPath(const ClContext& cl, TransferPath requested) {
    if (const std::string why = transferPathRefusal(cl, requested); !why.empty()) throw Error(why);
    if (requested != TransferPath::Auto) return requested;
    if (cl.sharesGl()) return TransferPath::GlSharing;
    const cl_bool unified = clGuard("asking the device about host memory", [&] {
        return cl.device().getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
    });
    if (unified) return TransferPath::PixelBuffer;
    // A discrete GPU: no host copy where GL, Vulkan and the device share memory. An H200 moved the
    // water's texels 2.7-4.0x faster that way than staged at 1024² (float16 2.42 against 8.75 ms,
    // float32 3.27 against 13.16) and 1.3-2.1x at 512².
    return transferPathRefusal(cl, TransferPath::ExternalMemory).empty() ? TransferPath::ExternalMemory
                                                                        : TransferPath::Staged;
}

std::vector<TransferPath> availableTransferPaths(const ClContext& cl) {
    std::vector<TransferPath> paths;
    for (const NamedValue<TransferPath>& n : kNames)
        if (n.value != TransferPath::Auto && transferPathRefusal(cl, n.value).empty()) paths.push_back(n.value);
    return paths;
}

} // namespace hfx
