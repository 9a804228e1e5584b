#include "hfx/effects/TransferPath.h"

#include "hfx/core/Error.h"
#include "hfx/core/Names.h"

namespace hfx {

namespace {
constexpr NamedValue<TransferPath> kNames[] = {
    {TransferPath::Auto, "auto"}, {TransferPath::Map, "map"}, {TransferPath::PixelBuffer, "pixel-buffer"}};
}

const char* transferPathName(TransferPath path) { return nameOf(kNames, path); }

TransferPath parseTransferPath(std::string_view name) { return parseName(kNames, name, "transfer path"); }

TransferPath chooseTransferPath(const ClContext& cl, TransferPath requested) {
    if (requested != TransferPath::Auto) return requested;
    const cl_bool unified = clGuard("asking the device about host memory", [&] {
        return cl.device().getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
    });
    return unified ? TransferPath::PixelBuffer : TransferPath::Map;
}

} // namespace hfx
