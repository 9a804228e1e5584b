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

TransferPath chooseTransferPath(const ClContext& cl, TransferPath requested) {
    if (requested == TransferPath::GlSharing && !cl.sharesGl())
        throw Error(str("the gl-sharing transfer path needs an OpenCL context made with the GL context it draws in "
                        "(cl_khr_gl_sharing for it; ClContextConfig::glShare); ",
                        cl.description(), " shares none here (NVIDIA offers it for GLX windows, not for EGL)"));
    if (requested == TransferPath::ExternalMemory)
        if (const std::string why = ExternalMemory::unavailable(cl); !why.empty())
            throw Error(why);
    if (requested != TransferPath::Auto) return requested;
    if (cl.sharesGl()) return TransferPath::GlSharing;
    const cl_bool unified = clGuard("asking the device about host memory", [&] {
        return cl.device().getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
    });
    return unified ? TransferPath::PixelBuffer : TransferPath::Staged;
}

std::vector<TransferPath> availableTransferPaths(const ClContext& cl) {
    std::vector<TransferPath> paths{TransferPath::Map, TransferPath::PixelBuffer, TransferPath::Staged};
    if (cl.sharesGl()) paths.push_back(TransferPath::GlSharing);
    if (ExternalMemory::unavailable(cl).empty()) paths.push_back(TransferPath::ExternalMemory);
    return paths;
}

} // namespace hfx
