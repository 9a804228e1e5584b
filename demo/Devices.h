#pragma once
// The two devices every run of the demo opens, in one place: the GL context (a window, EGL or
// OSMesa) and the OpenCL device chosen beside it (a GPU first, then one sharing the GL context,
// then one on the GL renderer's hardware: ClDeviceChoice.h). Both are named on stderr.

#include "hfx/compute/ClContext.h"
#include "hfx/platform/GlContext.h"

#include <memory>
#include <string>

namespace hfx::demo {

/// --gl and --cl-device.
struct DeviceOptions {
    GlBackend gl = GlBackend::Auto; ///< auto: HFX_GL, else a window where one may open, else EGL, else OSMesa
    std::string clDevice;           ///< a substring of the CL device's label; empty: HFX_CL_DEVICE
};

struct Devices {
    std::unique_ptr<GlContext> gl;
    std::unique_ptr<ClContext> cl;
    /// "GL: EGL surfaceless: OpenGL 4.5 ..., llvmpipe (...)\nOpenCL: 'cpu-...' (...): a CPU", for the top of a
    /// bench's table.
    std::string summary() const;
};

/// Opens GL (a window when `preferWindow`, the backend is auto and a display exists; else off
/// screen) and then the CL device for it.
Devices openDevices(const DeviceOptions& options, const GlContextConfig& config, bool preferWindow);

} // namespace hfx::demo
