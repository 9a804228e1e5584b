#include "support/Fixtures.h"

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
// generated": those came from clFFT's generated kernels, see OceanField.cpp.)
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
    for (const auto& [file, options] : builds) {
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

} // namespace
} // namespace hfx::test
