#include "hfx/effects/GasPlanetEffect.h"

#include "hfx/core/Error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hfx {

std::vector<ColorStop> gasGiantPalette() {
    return {{0.0f, {0.26f, 0.16f, 0.10f}},  {0.3f, {0.48f, 0.30f, 0.18f}}, {0.48f, {0.70f, 0.50f, 0.32f}},
            {0.64f, {0.92f, 0.84f, 0.70f}}, {0.8f, {0.98f, 0.95f, 0.88f}},  {1.0f, {0.78f, 0.38f, 0.22f}}};
}

void GasPlanetConfig::validate() const {
    gas.validate();
    if (gas.edges != EdgeMode::WrapU)
        throw Error(str("GasPlanetConfig.gas.edges must be wrap-u, got ", edgeModeName(gas.edges),
                        ": a planet's poles are walls, not a seam"));
    if (!(stormsPerSecond >= 0.0f && stormsPerSecond <= 100.0f))
        throw Error(str("GasPlanetConfig.stormsPerSecond must be in [0, 100], got ", stormsPerSecond));
    if (!(stormRadius > 0.0f && stormRadius <= 0.25f))
        throw Error(str("GasPlanetConfig.stormRadius must be in (0, 0.25], got ", stormRadius));
    if (!std::isfinite(stormForce) || !std::isfinite(rotationSpeed))
        throw Error("GasPlanetConfig.stormForce and rotationSpeed must be finite");
    if (!(stormShear > 0.0f && stormShear <= 1.0f))
        throw Error(str("GasPlanetConfig.stormShear must be in (0, 1], got ", stormShear));
    if (!(timeScale >= 1.0f && timeScale <= 1e4f))
        throw Error(str("GasPlanetConfig.timeScale must be in [1, 10000], got ", timeScale));
    if (!(maxSubstep > 0.0f && maxSubstep <= 60.0f))
        throw Error(str("GasPlanetConfig.maxSubstep must be in (0, 60] seconds, got ", maxSubstep));
    if (maxSubsteps < 1 || maxSubsteps > 256)
        throw Error(str("GasPlanetConfig.maxSubsteps must be in [1, 256], got ", maxSubsteps));
    if (!(stormWind >= 0.0f && stormWind <= 4.0f))
        throw Error(str("GasPlanetConfig.stormWind must be in [0, 4] (of gas.jetSpeed), got ", stormWind));
    if (!(stormAspect >= 1.0f && stormAspect <= 8.0f))
        throw Error(str("GasPlanetConfig.stormAspect must be in [1, 8], got ", stormAspect));
    if (!(stormHold >= 0.0f && stormHold <= 100.0f) || !(stormFeed >= 0.0f && stormFeed <= 100.0f))
        throw Error(str("GasPlanetConfig.stormHold and stormFeed must be in [0, 100] per second, got ", stormHold,
                        " and ", stormFeed));
    if (!(stormLifeRotations > 0.0f && stormLifeRotations <= 1e4f))
        throw Error(str("GasPlanetConfig.stormLifeRotations must be in (0, 10000], got ", stormLifeRotations));
    if (stormArms < 0 || stormArms > 8)
        throw Error(str("GasPlanetConfig.stormArms must be in [0, 8], got ", stormArms));
    if (!(stormArmContrast >= 0.0f && stormArmContrast <= 1.0f))
        throw Error(str("GasPlanetConfig.stormArmContrast must be in [0, 1], got ", stormArmContrast));
    if (!(stormWinding >= 0.0f && stormWinding <= 30.0f))
        throw Error(str("GasPlanetConfig.stormWinding must be in [0, 30] radians, got ", stormWinding));
    if (maxStorms < 1 || maxStorms > 1024)
        throw Error(str("GasPlanetConfig.maxStorms must be in [1, 1024], got ", maxStorms));
    if (!(gridScale == 0.0f || (gridScale >= 0.0625f && gridScale <= 4.0f)))
        throw Error(str("GasPlanetConfig.gridScale must be 0 (the device's) or in [1/16, 4], got ", gridScale));
    if (gridScale > 0.0f) scaledGas(gas, gridScale).validate();
    if (!(poleCap >= 0.0f && poleCap <= 0.25f))
        throw Error(str("GasPlanetConfig.poleCap must be in [0, 0.25], got ", poleCap));
    if (!(polarSmoothing >= 0.0f && polarSmoothing <= 60.0f))
        throw Error(str("GasPlanetConfig.polarSmoothing must be in [0, 60] degrees, got ", polarSmoothing));
    if (detail.scale != 0) detail.validate(gas); // scale 0 is validated once the device picks one
    if (rings) {
        rings->validate();
        if (rings->radius != 1.0f)
            throw Error(str("GasPlanetConfig.rings.radius must be 1 (the planet's sphere is the unit one), got ",
                            rings->radius));
    }
    material.validate();
}

int autoDetailScale(const ClContext& cl, int gasWidth) {
    const bool gpu = (cl.device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) != 0;
    const int widest = gpu ? 2048 : 1024;
    for (int scale : {4, 2})
        if (gasWidth * scale <= widest) return scale;
    return 1;
}

float autoGridScale(const ClContext& cl) {
    return (cl.device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) != 0 ? 2.0f : 1.0f;
}

GasConfig scaledGas(const GasConfig& gas, float gridScale) {
    if (gridScale == 1.0f) return gas;
    GasConfig g = gas;
    const double s = gridScale;
    g.width = std::max(4, 2 * int(std::lround(gas.width * s / 2.0))); // even: the exact pressure's FFT
    g.height = std::max(4, int(std::lround(gas.height * s)));
    g.jetSpeed = float(gas.jetSpeed * s);
    g.maxSpeed = float(gas.maxSpeed * s);
    g.viscosity = float(gas.viscosity * s * s);
    g.pressureIterations = std::clamp(int(std::lround(gas.pressureIterations * s * s)), 1, 10000);
    return g;
}

namespace {
// Detail or a pole cap to put on the gas's heights: else the surface is the gas's own.
bool hasDetail(const GasPlanetConfig& c) { return c.detail.amount > 0.0f || c.detail.warp > 0.0f || c.poleCap > 0.0f; }

// The configuration with the detail's scale and pole cap settled for this device.
GasPlanetConfig settled(const ClContext& cl, GasPlanetConfig config) {
    if (config.gridScale == 0.0f) config.gridScale = autoGridScale(cl);
    config.gas = scaledGas(config.gas, config.gridScale);
    config.stormForce *= config.gridScale; // cells per second^2
    config.gridScale = 1.0f;               // the scaled gas is the one simulated
    if (config.detail.scale == 0) config.detail.scale = autoDetailScale(cl, config.gas.width);
    if (!hasDetail(config)) config.detail.scale = 1;
    config.detail.capRows = config.poleCap * float(config.gas.height);
    config.detail.seed = config.seed;
    config.detail.validate(config.gas);
    return config;
}

std::unique_ptr<FlowDetail> makeDetail(ClContext& cl, const GasField& gas, const GasPlanetConfig& config) {
    if (!hasDetail(config)) return nullptr;
    return std::make_unique<FlowDetail>(cl, gas, config.detail);
}

// The gas's surface, `detail.scale` texels per cell.
SurfacePipelineConfig surfaceOf(const GasField& gas, const GasPlanetConfig& c) {
    SurfacePipelineConfig s = SurfacePipelineConfig::of(gas, c.material.depthScale, c.surface);
    s.width *= c.detail.scale;
    s.height *= c.detail.scale;
    return s;
}
} // namespace

GasPlanetEffect::GasPlanetEffect(ClContext& cl, const GasPlanetConfig& config)
    : Effect(validated(config).material), cl_(cl), config_(settled(cl, config)), gas_(cl, config_.gas),
      detail_(makeDetail(cl, gas_, config_)),
      colors_(cl, config_.gas.width * config_.detail.scale, config_.gas.height * config_.detail.scale, config_.palette),
      random_(config.seed), surface_(cl, surfaceOf(gas_, config_)) {
    if (config_.polarSmoothing > 0.0f)
        polar_ = std::make_unique<PolarFilter>(cl, surfaceWidth(), surfaceHeight(), config_.polarSmoothing);
    float largest = 0.0f;
    for (int i = 1; i < 4096; ++i) {
        const double v = i / 4096.0, h = 1e-4;
        largest = std::max(largest, float(std::abs(jetProfile(v + h) - jetProfile(v - h)) / (2.0 * h)));
    }
    maxShear_ = largest > 0.0f ? largest : 1.0f;
    if (config_.rings) {
        rings_ = std::make_unique<PlanetRings>(*config_.rings);
        material_.planet = rings_->look();
    }
    refresh();
}

void GasPlanetEffect::addStorm(float u, float v, bool clockwise, float strength) {
    if (!(strength > 0.0f) || !std::isfinite(strength))
        throw Error(str("GasPlanetEffect::addStorm: strength must be positive and finite, got ", strength));
    if (!(u >= 0.0f && u < 1.0f && v >= 0.0f && v <= 1.0f))
        throw Error(str("GasPlanetEffect::addStorm: texcoords must lie in [0, 1), got ", u, ", ", v));
    const float size = std::cbrt(strength);
    const float r = std::min(config_.stormRadius * size, 0.2f), dv = 0.5f * r * float(config_.gas.width) / float(config_.gas.height);
    const float v0 = std::fmin(std::fmax(v, dv + 0.01f), 0.99f - dv);
    // Its colour stands out of its band: white (the pale zones' top) in a dark belt; in a pale
    // zone the palette's rusty top turning clockwise, a dark brown the other way.
    const std::vector<float>& bands = gas_.bands();
    const float band = bands[std::min(size_t(v0 * float(bands.size())), bands.size() - 1)];
    const float colour = band < 0.55f ? 0.8f : (clockwise ? 1.0f : 0.15f);
    const Storm storm{.u = u, .v = v0, .radius = r, .strength = size, .clockwise = clockwise, .born = time_,
                      .colour = colour, .wind = {jetProfile(v0), 0.0f}, .band = band};
    spin(storm, config_.stormForce * size);
    gas_.addSplat({.u = u, .v = v0, .radius = 0.6f * r / config_.stormAspect, .dye = 1.0f, .dyeTarget = colour});
    if (int(storms_.size()) == config_.maxStorms) storms_.erase(storms_.begin());
    storms_.push_back(storm);
}

void GasPlanetEffect::spin(const Storm& storm, float force) {
    // Two opposite pushes a radius apart in latitude: a shear that rolls up into a vortex.
    const float dv = 0.5f * storm.radius * float(config_.gas.width) / float(config_.gas.height);
    const float signed_ = storm.clockwise ? force : -force;
    gas_.addSplat({.u = float(storm.u), .v = float(storm.v) + dv, .radius = storm.radius, .forceX = signed_});
    gas_.addSplat({.u = float(storm.u), .v = float(storm.v) - dv, .radius = storm.radius, .forceX = -signed_});
}

float GasPlanetEffect::jetProfile(double v) const { return float(gasJetAt(config_.gas, v)); }

float GasPlanetEffect::relativeShear(double v) const {
    const double h = 1e-4;
    return float(std::abs(jetProfile(v + h) - jetProfile(v - h)) / (2.0 * h) / maxShear_);
}

void GasPlanetEffect::setTimeScale(float scale) {
    GasPlanetConfig c = config_;
    c.timeScale = scale;
    c.validate();
    config_.timeScale = scale;
}

void GasPlanetEffect::advance(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("GasPlanetEffect::update: dt must be positive and finite, got ", dt));
    const double simulated = dt * config_.timeScale;
    const int substeps = std::clamp(int(std::ceil(simulated / config_.maxSubstep)), 1, config_.maxSubsteps);
    const double step = simulated / substeps;
    // Where the gas carries each storm this frame, and how fast it spins there: its wind at the
    // storm's centre now and a cell either side of it in u and in v (one small read a frame, of
    // a queue the last frame has finished). The curl there, dv/dx - du/dy, is 2 psi0 (1/a^2 +
    // 1/b^2) for GasVortex's oval, whose centre turns at 2 psi0 / (a b): that curl over a/b + b/a.
    // A storm seeded during the frame rides its band's jet, unturning, until the next.
    if (!storms_.empty()) {
        const float du = 1.0f / float(config_.gas.width), dv = 1.0f / float(config_.gas.height);
        stormSamples_.clear();
        for (const Storm& st : storms_) {
            const float u = float(st.u), v = float(st.v);
            for (const glm::vec2 at : {glm::vec2(u, v), {u + du, v}, {u - du, v}, {u, v + dv}, {u, v - dv}})
                stormSamples_.emplace_back(at.x - std::floor(at.x), at.y);
        }
        stormWinds_.resize(stormSamples_.size());
        gas_.velocityAt(stormSamples_, stormWinds_);
        for (size_t i = 0; i < storms_.size(); ++i) {
            const glm::vec2* w = &stormWinds_[5 * i];
            storms_[i].wind = w[0];
            // (dv/dx - d(m u)/dy) / m: on the sphere's map a cell of longitude is m cells wide.
            const float v = float(storms_[i].v), m = gas_.metricAt(v);
            const float across = w[3].x * gas_.metricAt(v + dv) - w[4].x * gas_.metricAt(v - dv);
            const float curl = (0.5f * (w[1].y - w[2].y) - 0.5f * across) / m;
            const float aspect = config_.stormAspect * m; // the oval's on the sphere
            storms_[i].turnRate = curl / (aspect + 1.0f / aspect);
        }
    }
    for (int s = 0; s < substeps; ++s) {
        time_ += step;
        stormClock_ += step * config_.stormsPerSecond;
        for (int storms = 0; stormClock_ >= 1.0 && storms < 8; ++storms) {
            stormClock_ -= 1.0;
            // In a band's middle: latitudes drawn until the shear there is low (or none is found).
            const float u = float(random_.next());
            for (int attempt = 0; attempt < 32; ++attempt) {
                const double v = random_.uniform(0.15, 0.85);
                if (relativeShear(v) > config_.stormShear) continue;
                // Sizes from 0.63x to 1.59x, strengths log-uniform in [1/4, 4].
                const float strength = float(std::exp(random_.uniform(-1.0, 1.0) * std::log(4.0)));
                addStorm(u, float(v), random_.next() < 0.5, strength);
                if (seeded_.size() == 64) seeded_.erase(seeded_.begin());
                seeded_.emplace_back(u, float(v));
                break;
            }
        }
        // The living storms ride the wind at their centres, the gas held to their vortices and
        // their clouds fed their colour, both fading with age.
        const double life = config_.stormLifeRotations * 2.0 * std::numbers::pi / std::max(config_.rotationSpeed, 1e-6f);
        std::erase_if(storms_, [&](const Storm& st) { return time_ - st.born > life; });
        for (Storm& st : storms_) {
            st.u += double(st.wind.x / gas_.metricAt(float(st.v))) * step / double(config_.gas.width);
            st.u -= std::floor(st.u);
            if (st.u >= 1.0) st.u = 0.0;
            const float fade = float(1.0 - (time_ - st.born) / life);
            if (config_.stormHold > 0.0f)
                gas_.addVortex({.u = float(st.u), .v = float(st.v), .radius = st.radius, .aspect = config_.stormAspect,
                                .speed = (st.clockwise ? -1.0f : 1.0f) * config_.stormWind * config_.gas.jetSpeed,
                                .driftX = st.wind.x, .rate = config_.stormHold * fade});
            // Its arms turn as the gas spins at its centre and trail that spin (the storm's own
            // sense until the gas has been read); fed at their angle midway through the step, as
            // their mean over it.
            const double sweep = double(st.turnRate) * step;
            const bool clockwise = st.turnRate != 0.0f ? st.turnRate < 0.0f : st.clockwise;
            const double midway = std::remainder(st.turned + 0.5 * sweep, 2.0 * std::numbers::pi);
            st.turned = std::remainder(st.turned + sweep, 2.0 * std::numbers::pi);
            if (config_.stormFeed > 0.0f)
                gas_.addSplat({.u = float(st.u), .v = float(st.v), .radius = st.radius / config_.stormAspect,
                               .dye = float(1.0 - std::exp(-double(config_.stormFeed * fade) * step)),
                               .dyeTarget = st.colour, .aspect = config_.stormAspect,
                               .arms = {.count = config_.stormArms, .target = st.band,
                                        .contrast = config_.stormArmContrast, .turned = float(midway),
                                        .winding = (clockwise ? -1.0f : 1.0f) * config_.stormWinding,
                                        .sweep = float(sweep)}});
        }
        gas_.step(step);
        if (detail_) detail_->step(step);
    }
}

void GasPlanetEffect::spinUp(double seconds) {
    if (!(seconds >= 0.0 && seconds <= 1e6))
        throw Error(str("GasPlanetEffect::spinUp: seconds must be in [0, 10^6], got ", seconds));
    // In pieces that advance() splits into whole substeps of maxSubstep (its time scale undone).
    const double piece = double(config_.maxSubstep) * config_.maxSubsteps;
    for (double left = seconds; left > 0.0; left -= piece) advance(std::min(left, piece) / config_.timeScale);
    // The textures show the weather spun up: a caller that draws before its next update (an
    // overlapped frame draws what the last update left) would otherwise draw the bands as they
    // started.
    if (seconds > 0.0) refresh();
}

void GasPlanetEffect::enqueueSurface() {
    // The colour follows the heights: the gas's, with the cloud tops' detail.
    if (detail_) detail_->run();
    const cl::Buffer* heights = detail_ ? &detail_->output() : &gas_.buffer();
    if (polar_) {
        polar_->run(*heights);
        heights = &polar_->output();
    }
    surface_.derive(*heights);
    colors_.run(*heights);
    surface_.submit(&colors_.output());
}

std::vector<float> GasPlanetEffect::readHeights() {
    if (!polar_) return detail_ ? detail_->readHeights() : gas_.readHeights();
    std::vector<float> heights(size_t(surfaceWidth()) * surfaceHeight());
    clGuard("reading the planet's heights", [&] {
        cl_.queue().enqueueReadBuffer(polar_->output(), CL_TRUE, 0, heights.size() * sizeof(float), heights.data());
    });
    return heights;
}

glm::mat4 GasPlanetEffect::modelMatrix() const {
    return glm::rotate(glm::mat4(1.0f), float(std::fmod(time_ * config_.rotationSpeed, 6.283185307179586)),
                       glm::vec3(0.0f, 1.0f, 0.0f));
}

} // namespace hfx
