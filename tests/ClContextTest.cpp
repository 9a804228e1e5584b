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
    const cl::Program& a = cl().program("sobel.cl");
    const cl::Program& b = cl().program("sobel.cl");
    const cl::Program& c = cl().program("sobel.cl", "-DCLAMP_EDGES");
    EXPECT_EQ(a(), b());
    EXPECT_NE(a(), c());
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
