#include "support/Fixtures.h"

#include "hfx/compute/ClDeviceChoice.h"
#include "hfx/core/Error.h"

#include <cstdlib>

namespace hfx::test {
namespace {

class ClContextTest : public ClTest {};

TEST_F(ClContextTest, KernelThatFailsToBuildReportsTheBuildLog) {
    try {
        cl().programFromSource("broken.cl", "__kernel void k(__global float* x) {\n"
                                            "    x[0] = not_a_function(1.0f);\n}\n");
        FAIL() << "a broken kernel built";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("broken.cl"), std::string::npos) << message;
        EXPECT_NE(message.find("failed to build"), std::string::npos) << message;
        EXPECT_NE(message.find("not_a_function"), std::string::npos) << message; // the log
    }
}

TEST_F(ClContextTest, ProgramsAreBuiltOncePerOptions) {
    const cl::Program& a = cl().program("sobel.cl", edgeOptions(EdgeMode::Wrap));
    const cl::Program& b = cl().program("sobel.cl", edgeOptions(EdgeMode::Wrap));
    const cl::Program& c = cl().program("sobel.cl", edgeOptions(EdgeMode::Clamp));
    EXPECT_EQ(a(), b());
    EXPECT_NE(a(), c());
}

// Every embedded kernel file, in every variant the module builds, compiles without a warning:
// -Werror turns one into a build failure that names it. (A cold start used to print "N warnings
// generated": those came from the FFT library's generated kernels, see VkFft.cpp.)
TEST_F(ClContextTest, EveryKernelBuildsWithoutWarnings) {
    // The device honours -Werror: a kernel with an implicit float-to-int conversion fails.
    EXPECT_NE(messageOf([&] {
                  cl().programFromSource("warns.cl", "__kernel void k(__global int* x) { int a = 3.5f; x[0] = a; }\n",
                                         "-Werror");
              }).find("warns.cl"),
              std::string::npos);
    std::vector<std::pair<const char*, std::string>> builds = {
        {"waves.cl", ""}, {"ocean.cl", ""}, {"colorize.cl", ""}, {"pack.cl", ""}, {"detail.cl", ""}};
    for (EdgeMode edges : kEdgeModes) {
        for (const char* file : {"sobel.cl", "pyramid.cl"}) builds.emplace_back(file, edgeOptions(edges));
        builds.emplace_back("decals.cl", "-DTILE=16 " + edgeOptions(edges));
        if (edges != EdgeMode::Clamp) builds.emplace_back("gas.cl", edgeOptions(edges));
        for (int kind = 0; kind < 3; ++kind)
            for (int fractal = 0; fractal < 3; ++fractal)
                builds.emplace_back("noise.cl", str("-cl-fp32-correctly-rounded-divide-sqrt -DKIND=", kind,
                                                    " -DFRACTAL=", fractal, " ", edgeOptions(edges)));
    }
    for (const auto& build : builds) {
        // (Not a structured binding: clang before 16 cannot capture one in a lambda.)
        const std::string& file = build.first;
        const std::string& options = build.second;
        const std::string m = messageOf([&] { cl().program(file, options + " -Werror"); });
        EXPECT_EQ(m, "(no error)") << file << " " << options;
    }
}

TEST_F(ClContextTest, UnknownKernelFileIsAClearError) {
    try {
        cl().program("no_such_kernel.cl");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no_such_kernel.cl"), std::string::npos);
    }
}

TEST(ClDeviceChoice, UnmatchedFilterListsTheDevices) {
    try {
        ClContext context({.device = "no-such-device-xyz", .log = false});
        FAIL() << "a filter matching nothing picked a device";
    } catch (const Error& e) {
        const std::string message = e.what();
        // With no OpenCL at all the message says what to install instead.
        const bool listsDevices = message.find("no-such-device-xyz") != std::string::npos &&
                                  message.find("devices present") != std::string::npos;
        const bool saysInstall = message.find("pocl-opencl-icd") != std::string::npos;
        EXPECT_TRUE(listsDevices || saysInstall) << message;
    }
}

// The device policy on lists no machine here has (the H200 machine listed PoCL's CPU device
// first and NVIDIA's GPU second; the old rule took PoCL).
namespace devices {
const ClDeviceInfo pocl{.platform = "Portable Computing Language", .name = "cpu-haswell-AMD EPYC 9654",
                        .vendor = "AuthenticAMD", .type = CL_DEVICE_TYPE_CPU};
const ClDeviceInfo h200{.platform = "NVIDIA CUDA", .name = "NVIDIA H200", .vendor = "NVIDIA Corporation",
                        .type = CL_DEVICE_TYPE_GPU};
const ClDeviceInfo radeon{.platform = "AMD Accelerated Parallel Processing", .name = "gfx1100",
                          .vendor = "Advanced Micro Devices, Inc.", .type = CL_DEVICE_TYPE_GPU};
const ClDeviceInfo iris{.platform = "Intel(R) OpenCL Graphics", .name = "Intel(R) Iris(R) Xe Graphics",
                        .vendor = "Intel(R) Corporation", .type = CL_DEVICE_TYPE_GPU};
const ClDeviceInfo fpga{.platform = "Intel(R) FPGA Emulation Platform", .name = "Intel(R) FPGA Emulation Device",
                        .vendor = "Intel(R) Corporation", .type = CL_DEVICE_TYPE_ACCELERATOR};
} // namespace devices

TEST(ClDeviceChoice, AGpuIsChosenOverTheCpuWhateverTheOrder) {
    using namespace devices;
    EXPECT_EQ(chooseClDevice({pocl, h200}, "", "").index, 1);
    EXPECT_EQ(chooseClDevice({h200, pocl}, "", "").index, 0);
    EXPECT_EQ(chooseClDevice({pocl, fpga}, "", "").index, 1); // an accelerator before a CPU
    EXPECT_EQ(chooseClDevice({fpga, h200}, "", "").index, 1); // a GPU before an accelerator
    EXPECT_EQ(chooseClDevice({pocl}, "", "").index, 0);       // the CPU when it is all there is
    EXPECT_EQ(chooseClDevice({}, "", "").index, -1);
    EXPECT_NE(chooseClDevice({pocl, h200}, "", "").reason.find("GPU"), std::string::npos);
}

TEST(ClDeviceChoice, TheGlRenderersHardwareBreaksTheTieBetweenGpus) {
    using namespace devices;
    const GlRendererInfo nvidia{"NVIDIA Corporation", "NVIDIA H200/PCIe/SSE2"};
    const GlRendererInfo amd{"AMD", "AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6, DRM 3.49)"};
    const GlRendererInfo intel{"Intel", "Mesa Intel(R) Xe Graphics (TGL GT2)"};
    EXPECT_EQ(chooseClDevice({iris, radeon, h200}, "", "", nvidia).index, 2);
    EXPECT_EQ(chooseClDevice({h200, iris, radeon}, "", "", amd).index, 2);
    EXPECT_EQ(chooseClDevice({h200, radeon, iris}, "", "", intel).index, 2);
    EXPECT_EQ(chooseClDevice({iris, radeon, h200}, "", "").index, 0); // no GL said: the listing's order
    EXPECT_NE(chooseClDevice({iris, h200}, "", "", nvidia).reason.find("GL renderer"), std::string::npos);
    // A software renderer works in host memory, as a CPU device does, but a GPU still computes first.
    const GlRendererInfo llvmpipe{"Mesa", "llvmpipe (LLVM 15.0.6, 256 bits)"};
    EXPECT_TRUE(llvmpipe.software());
    EXPECT_FALSE(nvidia.software());
    EXPECT_EQ(chooseClDevice({pocl, h200}, "", "", llvmpipe).index, 1);
    ClDeviceInfo otherCpu = pocl;
    otherCpu.platform = "Intel(R) CPU Runtime for OpenCL(TM) Applications";
    EXPECT_EQ(chooseClDevice({fpga, otherCpu}, "", "", llvmpipe).index, 0);
    // A CPU device never counts as the GL renderer's hardware by vendor alone.
    ClDeviceInfo intelCpu = otherCpu;
    intelCpu.vendor = "Intel(R) Corporation";
    EXPECT_EQ(chooseClDevice({intelCpu}, "", "", intel).reason.find("GL renderer"), std::string::npos);
}

TEST(ClDeviceChoice, ADeviceSharingTheGlContextComesBeforeOneThatDoesNot) {
    using namespace devices;
    ClDeviceInfo sharing = radeon;
    sharing.sharesGl = true;
    EXPECT_EQ(chooseClDevice({h200, sharing}, "", "", {"NVIDIA Corporation", "NVIDIA H200"}).index, 1);
    EXPECT_NE(chooseClDevice({h200, sharing}, "", "").reason.find("shares"), std::string::npos);
    // ... but a sharing CPU device does not beat a GPU.
    ClDeviceInfo cpuSharing = pocl;
    cpuSharing.sharesGl = true;
    EXPECT_EQ(chooseClDevice({cpuSharing, h200}, "", "").index, 1);
}

TEST(ClDeviceChoice, FiltersSelectByPlatformDeviceNameOrKind) {
    using namespace devices;
    const std::vector<ClDeviceInfo> list{pocl, h200, radeon};
    EXPECT_EQ(chooseClDevice(list, "portable", "").index, 0);
    EXPECT_EQ(chooseClDevice(list, "PORTABLE", "").index, 0); // case-insensitive
    EXPECT_EQ(chooseClDevice(list, "", "cpu").index, 0);
    EXPECT_EQ(chooseClDevice(list, "", "gfx1100").index, 2);
    EXPECT_EQ(chooseClDevice(list, "", "h200").index, 1);
    EXPECT_EQ(chooseClDevice(list, "nvidia", "gpu").index, 1);
    EXPECT_EQ(chooseClDevice(list, "nvidia", "cpu").index, -1);
    EXPECT_EQ(chooseClDevice(list, "no-such-platform", "").index, -1);
    EXPECT_NE(chooseClDevice(list, "", "cpu").reason.find("filters"), std::string::npos);
}

} // namespace
} // namespace hfx::test
