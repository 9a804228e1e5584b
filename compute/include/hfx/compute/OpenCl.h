#pragma once
// The Khronos C++ bindings, configured once by hfx::compute's compile definitions
// (exceptions enabled, OpenCL 1.2 API).
//
// Thread: any (configuration of the C++ bindings only).

#include <CL/opencl.hpp>

#include <string>

namespace hfx {
/// "CL_OUT_OF_RESOURCES (-5)" for an OpenCL status code.
std::string clErrorName(cl_int code);
} // namespace hfx
