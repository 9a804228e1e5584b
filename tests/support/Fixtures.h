#pragma once
// Shared device fixtures: one OpenCL context and one headless GL context per test program.
// Where a device is missing the tests skip, saying why.

#include "hfx/compute/ClContext.h"
#include "hfx/core/GlContext.h"
#include "hfx/core/Image.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace hfx::test {

class ClTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override; ///< drains the queue: no test leaves work behind at exit
    ClContext& cl();
};

class GlTest : public ::testing::Test {
protected:
    void SetUp() override;
};

/// GL and CL both (scenes); skips if either is missing.
class DeviceTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    ClContext& cl();
};

/// Folder for images a failing test leaves behind (actual, expected, diff).
std::string outputPath(const std::string& fileName);

} // namespace hfx::test
