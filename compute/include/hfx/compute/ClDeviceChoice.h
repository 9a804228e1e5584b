#pragma once
// Which OpenCL device a ClContext takes, as a rule over plain descriptions, so that the policy is
// tested on device lists no machine has (tests/ClContextTest.cpp).
//
// Among the devices that match both filters, in order of preference:
//   1. a GPU, then an accelerator, then any other kind, then a CPU: the kernels are data-parallel
//      (the water step at 512² took 21.8 ms on PoCL with 16 cores, 0.50 ms on an H200);
//   2. a device that shares objects with the caller's GL context (cl_khr_gl_sharing for it);
//   3. a device on the hardware that runs the GL renderer: the same vendor, or a CPU device
//      beside a software renderer (llvmpipe): both work in host memory;
//   4. the order the platforms and devices were listed in.
//
// Thread: any (pure functions).

#include "hfx/compute/OpenCl.h"
#include "hfx/core/GlRenderer.h"

#include <string>
#include <string_view>
#include <vector>

namespace hfx {

/// What the choice knows of one OpenCL device.
struct ClDeviceInfo {
    std::string platform; ///< CL_PLATFORM_NAME
    std::string name;     ///< CL_DEVICE_NAME
    std::string vendor;   ///< CL_DEVICE_VENDOR
    cl_device_type type = CL_DEVICE_TYPE_DEFAULT;
    bool sharesGl = false; ///< offers cl_khr_gl_sharing for the caller's GL context
    /// "'NVIDIA H200' (GPU) on 'NVIDIA CUDA'": what the device filter is matched against.
    std::string label() const;
};

struct ClDeviceChoice {
    int index = -1;     ///< into the list; -1 when no device matches the filters
    std::string reason; ///< "a GPU, on the GL renderer's hardware", for the start-up log
};

/// Chooses by the rule at the top of this file. `platformFilter` is a case-insensitive substring
/// of the platform name, `deviceFilter` one of the device's label() (so "h200", "gpu", "cpu",
/// "nvidia" or "portable" all select); empty filters match every device.
ClDeviceChoice chooseClDevice(const std::vector<ClDeviceInfo>& devices, std::string_view platformFilter,
                              std::string_view deviceFilter, const GlRendererInfo& gl = {});

/// "GPU", "CPU", "accelerator", "custom device".
const char* clDeviceTypeName(cl_device_type type);

} // namespace hfx
