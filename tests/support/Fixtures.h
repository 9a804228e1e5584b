#pragma once
// Shared device fixtures: one OpenCL context and one headless GL context per test program.
// Where a device is missing the tests skip, saying why.

#include "hfx/compute/ClContext.h"
#include "hfx/compute/HeightSource.h"
#include "hfx/platform/GlContext.h"
#include "hfx/tools/ImageFiles.h"
#include "hfx/core/SurfaceTextures.h"
#include "hfx/effects/tracer/HeightBounds.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

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
    void TearDown() override; ///< fails the test where it left a GL error unchecked
};

/// Sets HFX_GL_WORKAROUNDS for its lifetime, after what the run set (a later entry wins: a run
/// under HFX_GL_WORKAROUNDS=float32-surfaces=0 keeps that inside), and puts back what was there.
class WorkaroundsSet {
public:
    explicit WorkaroundsSet(const char* value) {
        if (const char* old = std::getenv("HFX_GL_WORKAROUNDS")) old_ = old;
        const std::string set = old_ && !old_->empty() ? *old_ + "," + value : std::string(value);
        setenv("HFX_GL_WORKAROUNDS", set.c_str(), 1);
    }
    ~WorkaroundsSet() {
        if (old_) setenv("HFX_GL_WORKAROUNDS", old_->c_str(), 1);
        else unsetenv("HFX_GL_WORKAROUNDS");
    }
    WorkaroundsSet(const WorkaroundsSet&) = delete;
    WorkaroundsSet& operator=(const WorkaroundsSet&) = delete;

private:
    std::optional<std::string> old_;
};

/// GL and CL both (scenes); skips if either is missing.
class DeviceTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override; ///< drains the queue; fails the test where it left a GL error unchecked
    ClContext& cl();
};

/// Level 0 of a surface texture as GL holds it: width*height float4 (normal.xyz, height), row 0
/// at v = 0. Needs the texture's context current.
std::vector<float> readSurface(const SurfaceTextures& textures);
/// Level `level` of `bounds` as they hold it, (max, min) pairs row by row, in either layout.
std::vector<float> readBoundsLevel(const HeightBounds& bounds, int level);
/// The same of bounds in `layout` as a draw reads them, built by BoundsPass from the textures'
/// current texels.
std::vector<float> readPyramidLevel(const SurfaceTextures& textures, int level,
                                    PyramidLayout layout = PyramidLayout::Auto);

/// The first `count` floats of a device buffer (waits for the queue).
std::vector<float> readFloats(ClContext& cl, const cl::Buffer& buffer, size_t count);
/// All of a height source's heights, row 0 at v = 0.
std::vector<float> readHeights(ClContext& cl, const HeightSource& source);

/// How far a draw's hit may lie from the CPU's exact one, texels, where the test's rays cross the
/// view at a slant: a GPU's rasteriser interpolates the fragments' inputs to its own rounding, and
/// an exact walk carries it to the hit (an H200 put the triplanar box's hits up to 0.081 texels
/// off, an orthographic plane's 0.006; llvmpipe, whose interpolation is the CPU's own arithmetic,
/// 0.002). A hit from another pixel's ray or another projection lies a texel or more away.
constexpr double kDrawHitTexels = 0.1;

/// The message of the hfx::Error that `f` throws, or "(no error)".
std::string messageOf(const std::function<void()>& f);

/// Folder for images a failing test leaves behind (actual, expected, diff): HFX_TEST_OUTPUT_DIR
/// when set (a bundle's tests run outside the tree), else build/tests/output.
std::string outputPath(const std::string& fileName);

/// The shader sources (shaders/): HFX_SHADER_SOURCE_DIR when set (a bundle carries its copy),
/// else the tree the tests were built from.
std::string shaderSourceDir();

/// While it lives, the renderers made read a copy of the shaders (outputPath(name)) whose `file`
/// has its one `from` made `to` (the live-editing override, HFX_SHADER_DIR): a mutation, or a
/// device's rounding played on this one. Throws hfx::Error where the file holds no `from`. The
/// caller's own override comes back after.
class PatchedShaders {
public:
    PatchedShaders(const std::string& name, const std::string& from, const std::string& to,
                   const std::string& file = "surface.frag");
    ~PatchedShaders();
    PatchedShaders(const PatchedShaders&) = delete;
    PatchedShaders& operator=(const PatchedShaders&) = delete;

private:
    std::optional<std::string> callers_;
};

} // namespace hfx::test
