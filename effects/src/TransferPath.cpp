#include "hfx/effects/TransferPath.h"

#include "hfx/core/Error.h"

namespace hfx {

const char* transferPathName(TransferPath path) {
    switch (path) {
    case TransferPath::Auto: return "auto";
    case TransferPath::Map: return "map";
    case TransferPath::PixelBuffer: return "pixel-buffer";
    }
    return "unknown";
}

TransferPath parseTransferPath(std::string_view name) {
    for (TransferPath p : {TransferPath::Auto, TransferPath::Map, TransferPath::PixelBuffer})
        if (name == transferPathName(p)) return p;
    throw Error(str("unknown transfer path '", name, "' (known: auto, map, pixel-buffer)"));
}

TransferPath chooseTransferPath(const ClContext& cl, TransferPath requested) {
    if (requested != TransferPath::Auto) return requested;
    const cl_bool unified = clGuard("asking the device about host memory", [&] {
        return cl.device().getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
    });
    return unified ? TransferPath::PixelBuffer : TransferPath::Map;
}

} // namespace hfx
