// GPU-honest timing: the GL timer queries (GpuTimer, GpuScope) and the kernels' device times (CL
// event profiling) report passes of known cost in proportion to that cost. Ratios of one run,
// never a time: this machine is shared and noisy. (On llvmpipe GpuTimer times each pass by the CPU
// clock between two glFinish, its one software-rasteriser switch: its queries time a tile, not a
// pass. On a GPU the same tests hold the queries.)

#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/core/ShaderProgram.h"
#include "hfx/tools/Timing.h"

#include <memory>

namespace hfx::test {
namespace {

/// A full-screen triangle whose fragments each run `u_iterations` rounds of dependent math.
ShaderProgram loopProgram() {
    const SourceFile vertex{"loop.vert", R"(#version 450 core
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})",
                            "test"};
    const SourceFile fragment{"loop.frag", R"(#version 450 core
uniform int u_iterations;
out vec4 color;
void main() {
    vec2 x = gl_FragCoord.xy * 0.001;
    for (int i = 0; i < u_iterations; ++i) x = fract(x * 1.7 + vec2(x.y, x.x) * 0.3 + 0.1);
    color = vec4(x, 0.0, 1.0);
})",
                              "test"};
    return ShaderProgram(vertex, fragment);
}

class GpuTiming : public GlTest {
protected:
    /// The loop program bound with an empty vertex array, drawing into a size x size target
    /// (made here: the fixture's constructor runs before SetUp makes the context current).
    void bindLoop(int size) {
        program_ = loopProgram();
        empty_ = GlVertexArray::create();
        target_ = std::make_unique<RenderTarget>(size, size);
        target_->bind();
        program_.use();
        glBindVertexArray(empty_.id());
    }
    ShaderProgram program_;
    GlVertexArray empty_;
    std::unique_ptr<RenderTarget> target_;
};

TEST_F(GpuTiming, APassOfKnownCostIsReportedInProportion) {
    GpuTimer timer;
    if (!timer.available()) GTEST_SKIP() << "no GL_TIMESTAMP counter on this driver";
    bindLoop(256);
    GpuTimer::Activation on(timer);
    const int costs[] = {100, 200, 400};
    // Interleaved, after warm-up frames: each frame draws every cost once, under its own name.
    for (int frame = -3; frame < 15; ++frame) {
        if (frame == 0) {
            timer.finish();
            timer.clearSamples();
        }
        timer.beginFrame();
        for (int cost : costs) {
            program_.set("u_iterations", cost);
            const GpuScope scope(str("loop ", cost));
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        timer.endFrame();
    }
    timer.finish();
    std::map<int, double> ms;
    for (int cost : costs) {
        const auto& samples = timer.samples().at(str("loop ", cost));
        ASSERT_EQ(samples.size(), 15u) << "one sample per frame";
        ms[cost] = median(samples);
    }
    std::printf("GPU time of the loop pass: 100: %.3f ms, 200: %.3f ms, 400: %.3f ms\n", ms[100], ms[200], ms[400]);
    EXPECT_GT(ms[100], 0.0);
    // Twice the work, about twice the time (a fixed cost per pass lowers the ratio a little).
    EXPECT_GT(ms[200] / ms[100], 1.5);
    EXPECT_LT(ms[200] / ms[100], 2.6);
    EXPECT_GT(ms[400] / ms[100], 2.8);
    EXPECT_LT(ms[400] / ms[100], 5.0);
}

TEST_F(GpuTiming, ScopesRecordOnlyOnTheActiveTimerAndNestedPassesAddUp) {
    GpuTimer timer;
    if (!timer.available()) GTEST_SKIP() << "no GL_TIMESTAMP counter on this driver";
    bindLoop(128);
    program_.set("u_iterations", 200);
    {
        const GpuScope ignored("nobody listens"); // no active timer: nothing recorded
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    GpuTimer::Activation on(timer);
    for (int frame = 0; frame < 6; ++frame) {
        timer.beginFrame();
        const GpuScope outer("outer");
        for (int i = 0; i < 2; ++i) {
            const GpuScope inner("inner"); // twice a frame: one sample, the sum
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        timer.endFrame();
    }
    timer.finish();
    EXPECT_EQ(timer.samples().count("nobody listens"), 0u);
    ASSERT_EQ(timer.samples().at("inner").size(), 6u);
    ASSERT_EQ(timer.samples().at("outer").size(), 6u);
    for (size_t i = 0; i < 6; ++i) EXPECT_GE(timer.samples().at("outer")[i], 0.9 * timer.samples().at("inner")[i]);
}

class KernelTiming : public ClTest {};

TEST_F(KernelTiming, KernelsOfKnownCostAreReportedInProportion) {
    const cl::Program& p = cl().programFromSource("loop.cl", R"(
__kernel void loop(__global float* out, int iterations) {
    float x = (float)get_global_id(0) * 0.001f;
    for (int i = 0; i < iterations; ++i) {
        x = x * 1.7f + 0.1f;
        x = x - floor(x);
    }
    out[get_global_id(0)] = x;
})");
    cl::Kernel kernel(p, "loop");
    cl::Buffer out(cl().context(), CL_MEM_READ_WRITE, 1 << 18);
    kernel.setArg(0, out);
    std::map<int, std::vector<double>> ms;
    for (int round = -2; round < 9; ++round)
        for (int cost : {2000, 4000}) {
            kernel.setArg(1, cost);
            cl().recordKernelTimes(true);
            cl().enqueue(kernel, cl::NDRange(1 << 12));
            cl().recordKernelTimes(false);
            const std::map<std::string, double> times = cl().takeKernelTimes();
            ASSERT_EQ(times.size(), 1u);
            if (round >= 0) ms[cost].push_back(times.at("loop"));
        }
    cl().enqueue(kernel, cl::NDRange(1 << 12)); // not recording: nothing kept
    EXPECT_TRUE(cl().takeKernelTimes().empty());
    const double ratio = median(ms[4000]) / median(ms[2000]);
    std::printf("device time of the loop kernel: 2000: %.3f ms, 4000: %.3f ms\n", median(ms[2000]), median(ms[4000]));
    EXPECT_GT(ratio, 1.5);
    EXPECT_LT(ratio, 2.6);
}

} // namespace
} // namespace hfx::test
