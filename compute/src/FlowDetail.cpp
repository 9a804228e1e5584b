#include "hfx/compute/FlowDetail.h"

#include "hfx/compute/shared/FlowMath.h"
#include "hfx/core/Error.h"

#include <cmath>
#include <numbers>

namespace hfx {

namespace {
constexpr size_t kPlanes = HFX_FLOW_PLANES; // FlowMath.h: the displacements, the strain, the finest octaves
constexpr size_t kSetPlanes = HFX_FLOW_FINEST; // what setPlanes takes: the rest is derived
} // namespace

void FlowDetailConfig::validate(const GasConfig& gas) const {
    if (scale != 1 && scale != 2 && scale != 4 && scale != 8)
        throw Error(str("FlowDetailConfig.scale must be 1, 2, 4 or 8, got ", scale));
    if (gas.width * scale > 16384 || gas.height * scale > 16384)
        throw Error(str("FlowDetailConfig.scale ", scale, " makes the ", gas.width, "x", gas.height,
                        " gas's detail larger than 16384 texels"));
    if (!(amount >= 0.0f && amount <= 1.0f)) throw Error(str("FlowDetailConfig.amount must be in [0, 1], got ", amount));
    if (!(warp >= 0.0f && warp <= 8.0f)) throw Error(str("FlowDetailConfig.warp must be in [0, 8] cells, got ", warp));
    const float lattice = float(gas.width) * frequency;
    if (!(frequency > 0.0f && frequency <= 8.0f) || lattice != std::floor(lattice))
        throw Error(str("FlowDetailConfig.frequency must be in (0, 8] with width * frequency whole (the noise wraps ",
                        "around the longitude), got ", frequency, " for width ", gas.width));
    if (!(aspect >= 1.0f && aspect <= 8.0f)) throw Error(str("FlowDetailConfig.aspect must be in [1, 8], got ", aspect));
    if (!(calm >= 0.0f && calm <= 1.0f)) throw Error(str("FlowDetailConfig.calm must be in [0, 1], got ", calm));
    if (!(strainScale > 0.0f && strainScale <= 1e4f))
        throw Error(str("FlowDetailConfig.strainScale must be in (0, 10000] per second, got ", strainScale));
    if (octaves < 1 || octaves > 8) throw Error(str("FlowDetailConfig.octaves must be in [1, 8], got ", octaves));
    if (!(period > 0.0f && period <= 1e4f))
        throw Error(str("FlowDetailConfig.period must be in (0, 10000] seconds, got ", period));
    if (!(capRows >= 0.0f && capRows <= 0.5f * float(gas.height)))
        throw Error(str("FlowDetailConfig.capRows must be in [0, ", 0.5f * float(gas.height), "], got ", capRows));
    if (gas.edges != EdgeMode::WrapU)
        throw Error(str("FlowDetail needs a gas with wrap-u edges (walls at the poles), got ", edgeModeName(gas.edges)));
}

FlowDetail::FlowDetail(ClContext& cl, const GasField& gas, const FlowDetailConfig& config)
    : cl_(cl), gas_(gas), config_(config) {
    config.validate(gas.config());
    const size_t cells = size_t(gas.width()) * gas.height();
    clGuard("creating the flow detail", [&] {
        for (cl::Buffer& planes : planes_) {
            planes = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, kPlanes * cells * sizeof(float));
            cl.queue().enqueueFillBuffer(planes, 0.0f, 0, kPlanes * cells * sizeof(float));
        }
        output_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, cells * config.scale * config.scale * sizeof(float));
        const cl::Program& program = cl.program("flow.cl");
        advect_ = cl::Kernel(program, "flow_advect");
        finest_ = cl::Kernel(program, "flow_finest");
        detail_ = cl::Kernel(program, "flow_detail");
    });
}

namespace {
// Layer k's place in its life: time / period + k / 2 (whole part: its regenerations).
double phase(double time, double period, int layer) { return time / period + 0.5 * layer; }
} // namespace

float FlowDetail::weight(int layer) const {
    const double a = phase(time_, config_.period, layer);
    return float(std::sin(std::numbers::pi * (a - std::floor(a))));
}

float FlowDetail::generation(int layer) const {
    // A fresh slice of the 3D noise per life, spread over Perlin's 256 z cells (a life's slice
    // never lands on another's within thousands of lives).
    const std::uint64_t h = (config_.seed * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(lives_[layer]) * 0xBF58476D1CE4E5B9ull) ^
                            (std::uint64_t(layer + 1) * 0x94D049BB133111EBull);
    return float((h >> 40) % 65536) * (256.0f / 65536.0f) + 0.5f / 256.0f;
}

void FlowDetail::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt)) throw Error(str("FlowDetail::step: dt must be positive and finite, got ", dt));
    const double next = time_ + dt;
    int reset[2];
    for (int k = 0; k < 2; ++k) {
        const auto before = std::int64_t(std::floor(phase(time_, config_.period, k)));
        const auto after = std::int64_t(std::floor(phase(next, config_.period, k)));
        reset[k] = after != before;
        lives_[k] = after;
    }
    const int W = gas_.width(), H = gas_.height();
    clGuard("FlowDetail::step", [&] {
        advect_.setArg(0, gas_.velocityX());
        advect_.setArg(1, gas_.velocityY());
        advect_.setArg(2, gas_.metric());
        advect_.setArg(3, planes_[front_]);
        advect_.setArg(4, planes_[1 - front_]);
        advect_.setArg(5, W);
        advect_.setArg(6, H);
        advect_.setArg(7, float(dt));
        advect_.setArg(8, reset[0]);
        advect_.setArg(9, reset[1]);
        cl_.enqueue(advect_, cl::NDRange(size_t(W), size_t(H)));
    });
    front_ = 1 - front_;
    time_ = next;
    finestStale_ = true;
}

void FlowDetail::deriveFinest() {
    if (!finestStale_) return;
    finestStale_ = false;
    clGuard("FlowDetail: the finest octaves", [&] {
        finest_.setArg(0, planes_[front_]);
        finest_.setArg(1, gas_.width());
        finest_.setArg(2, gas_.height());
        finest_.setArg(3, params());
        cl_.enqueue(finest_, cl::NDRange(size_t(gas_.width()), size_t(gas_.height())));
    });
}

void FlowDetail::run() {
    deriveFinest();
    const int W = gas_.width(), H = gas_.height();
    clGuard("FlowDetail::run", [&] {
        int a = 0;
        detail_.setArg(a++, gas_.buffer());
        detail_.setArg(a++, planes_[front_]);
        detail_.setArg(a++, output_);
        detail_.setArg(a++, W);
        detail_.setArg(a++, H);
        detail_.setArg(a++, config_.scale);
        detail_.setArg(a++, params());
        detail_.setArg(a++, config_.capRows);
        cl_.enqueue(detail_, cl::NDRange(size_t(width()), size_t(height())));
    });
}

int FlowDetail::octaves() const {
    const FlowDetailConfig& c = config_;
    int shown = 1;
    while (shown < c.octaves && c.frequency * c.aspect * float(1 << shown) <= 0.5f * float(c.scale)) ++shown;
    return shown;
}

HfxFlowParams FlowDetail::params() const {
    const FlowDetailConfig& c = config_;
    return {.amount = c.amount, .frequency = c.frequency, .aspect = c.aspect, .calm = c.calm, .strainScale = c.strainScale,
            .octaves = octaves(), .w0 = weight(0), .w1 = weight(1), .z0 = generation(0), .z1 = generation(1), .warp = c.warp,
            .texels = float(c.scale), .sphere = gas_.config().sphere ? 1 : 0};
}

std::vector<float> FlowDetail::readPlanes() {
    deriveFinest();
    std::vector<float> planes(kPlanes * size_t(gas_.width()) * gas_.height());
    clGuard("reading the flow detail's planes", [&] {
        cl_.queue().enqueueReadBuffer(planes_[front_], CL_TRUE, 0, planes.size() * sizeof(float), planes.data());
    });
    return planes;
}

void FlowDetail::setPlanes(const std::vector<float>& planes) {
    const size_t n = kSetPlanes * size_t(gas_.width()) * gas_.height();
    if (planes.size() != n) throw Error(str("FlowDetail::setPlanes: expected ", n, " values, got ", planes.size()));
    for (float x : planes)
        if (!std::isfinite(x)) throw Error("FlowDetail::setPlanes: the planes hold NaN or infinite values");
    clGuard("setting the flow detail's planes", [&] {
        cl_.queue().enqueueWriteBuffer(planes_[front_], CL_TRUE, 0, n * sizeof(float), planes.data());
    });
    finestStale_ = true;
}

std::vector<float> FlowDetail::readHeights() {
    std::vector<float> heights(size_t(width()) * height());
    clGuard("reading the flow detail's heights", [&] {
        cl_.queue().enqueueReadBuffer(output_, CL_TRUE, 0, heights.size() * sizeof(float), heights.data());
    });
    return heights;
}

} // namespace hfx
