#include "Devices.h"

#include "hfx/core/Error.h"
#include "hfx/core/GlRenderer.h"

#include <cstdio>

namespace hfx::demo {

std::string Devices::summary() const {
    return str("GL: ", gl->description(), "\nOpenCL: ", cl->description(), ": ", cl->choiceReason());
}

Devices openDevices(const DeviceOptions& options, const GlContextConfig& config, bool preferWindow) {
    GlContextConfig c = config;
    c.backend = options.gl;
    Devices devices;
    devices.gl = createContext(c, preferWindow);
    std::fprintf(stderr, "hfx: GL %s\n", devices.gl->description().c_str());
    devices.cl = std::make_unique<ClContext>(ClContextConfig{
        .device = options.clDevice, .gl = currentGlRenderer(), .glShare = devices.gl->shareHandles()});
    return devices;
}

} // namespace hfx::demo
