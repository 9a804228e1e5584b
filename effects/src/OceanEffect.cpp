#include "hfx/effects/OceanEffect.h"

#include "hfx/compute/OceanSpectrum.h"
#include "hfx/compute/shared/DecalMath.h"
#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <algorithm>
#include <cmath>

namespace hfx {

void OceanEffectConfig::validate() const {
    ocean.validate();
    material.validate();
    if (!(reliefExaggeration > 0.0f && reliefExaggeration <= 20.0f))
        throw Error(str("OceanEffectConfig.reliefExaggeration must be in (0, 20], got ", reliefExaggeration));
    if (!(windBlendSeconds >= 0.0) || !std::isfinite(windBlendSeconds))
        throw Error(str("OceanEffectConfig.windBlendSeconds must be >= 0 and finite, got ", windBlendSeconds));
    if (!(untracedShare >= 0.0f && untracedShare < 1.0f))
        throw Error(str("OceanEffectConfig.untracedShare must be in [0, 1), got ", untracedShare));
    if (!(foamCellMeters >= 0.0f && foamCellMeters <= 100.0f))
        throw Error(
            str("OceanEffectConfig.foamCellMeters must be in [0, 100] (0: no bubbles), got ",
                foamCellMeters));
}

OceanEffect::OceanEffect(ClContext& cl, const OceanEffectConfig& config)
    : Effect(validated(config).material), ocean_(cl, config.ocean),
      exaggeration_(config.reliefExaggeration), windBlendSeconds_(config.windBlendSeconds),
      untracedShare_(config.untracedShare), foamCellMeters_(config.foamCellMeters) {
    for (int i = 0; i < ocean_.cascadeCount(); ++i) {
        // Each cascade's normals for its own relief: 8 sigma_i metres over its patch, in its own
        // texcoords, so the renderer adds physical slopes (SurfaceUniforms::layerSlope).
        const OceanCascade& c = ocean_.cascade(i);
        const float depth = std::max(8.0f * c.sigma / c.patchMeters, 1e-6f);
        surfaces_.push_back(std::make_unique<SurfacePipeline>(
            cl, SurfacePipelineConfig{.width = ocean_.config().size,
                                      .height = ocean_.config().size,
                                      .edges = EdgeMode::Wrap,
                                      .normalDepth = depth,
                                      .options = config.surface}));
    }
    material_.depthScale = physicalDepthScale();
    updateFoamLook(0.0);
    refresh();
}

std::vector<const SurfacePipeline*> OceanEffect::surfaces() const {
    std::vector<const SurfacePipeline*> all;
    for (const auto& s : surfaces_) all.push_back(s.get());
    return all;
}

float OceanEffect::physicalDepthScale() const {
    float sum = 0.0f;
    for (int i = 0; i < ocean_.cascadeCount(); ++i) sum += ocean_.cascade(i).sigma;
    return std::clamp(8.0f * sum / ocean_.config().patchMeters * exaggeration_, 1e-5f, 1.0f);
}

std::vector<float> OceanEffect::cascadeWeights() const {
    float sum = 0.0f;
    for (int i = 0; i < ocean_.cascadeCount(); ++i) sum += ocean_.cascade(i).sigma;
    std::vector<float> weights;
    for (int i = 0; i < ocean_.cascadeCount(); ++i)
        weights.push_back(sum > 0.0f ? ocean_.cascade(i).sigma / sum : 1.0f / float(ocean_.cascadeCount()));
    return weights;
}

std::vector<bool> OceanEffect::tracedCascades(const std::vector<float>& weights) const {
    // From the finest up, while the untraced weights stay within the share.
    std::vector<bool> traced(weights.size(), true);
    float untraced = 0.0f;
    for (size_t i = weights.size() - 1; i > 0; --i) {
        untraced += weights[i];
        if (untraced > untracedShare_) break;
        traced[i] = false;
    }
    return traced;
}

std::vector<SurfaceLayer> OceanEffect::layers() const {
    const std::vector<float> weights = cascadeWeights();
    const std::vector<bool> traced = tracedCascades(weights);
    std::vector<SurfaceLayer> layers;
    for (int i = 0; i < ocean_.cascadeCount(); ++i) {
        const OceanCascade& c = ocean_.cascade(i);
        // Untraced, a cascade stands at its stored rest height (0.5: OceanCascade::scale).
        layers.push_back({.textures = &surfaces_[size_t(i)]->textures(),
                          .texcoordScale = ocean_.config().patchMeters / c.patchMeters,
                          .weight = weights[size_t(i)],
                          .traced = traced[size_t(i)],
                          .restHeight = 0.5f,
                          .bounds = surfaces_[size_t(i)]->bounds()});
    }
    return layers;
}

void OceanEffect::enqueueSurface() {
    for (int i = 0; i < ocean_.cascadeCount(); ++i) {
        SurfacePipeline& s = *surfaces_[size_t(i)];
        s.derive(ocean_.cascade(i).height);
        s.submit(&ocean_.cascade(i).foamColor);
    }
}

void OceanEffect::advance(double dt) {
    ocean_.step(dt);
    foamSeconds_ += dt;
    material_.depthScale = physicalDepthScale(); // moves while a wind change blends in
    updateRings();
    updateFoamLook(dt);
}

namespace {
// The wind streaks' lattice across the wind, metres (the noise crosses its middle in about half
// its cells: a band of foam every 3 m or so).
constexpr double kStreakMeters = 3.0;
} // namespace

void OceanEffect::updateFoamLook(double dt) {
    const OceanConfig& c = ocean_.config();
    const WaveSpectrum& wind = c.sea.wind;
    const glm::dvec2 downwind(std::cos(double(wind.direction)), std::sin(double(wind.direction)));
    // The foam drifts at its share of the wind (FoamConfig::drift), as the field's foam does.
    foamDrift_ +=
        downwind * (double(c.foam.drift) * double(wind.windSpeed) * dt / double(c.patchMeters));
    WaterLook& w = material_.water;
    w.foamDrift = glm::vec2(foamDrift_);
    w.windDirection = glm::vec2(downwind);
    w.streakCells = float(double(c.patchMeters) / kStreakMeters);
    w.foamCells = foamCellMeters_ > 0.0f ? c.patchMeters / foamCellMeters_ : 0.0f;
    // Streaks from the middle of Beaufort 7 (a near gale, where spray starts to blow off the
    // crests) to full at that of 10, built as the whitecaps' foam they are drawn from builds: none
    // at a clear start, where a gale's lines crossed a sea without foam as scratches.
    const double built = 1.0 - std::exp2(-foamSeconds_ / double(c.foam.halfLife));
    const float strength = float(built) *
        hfx_decal_smoothstep(beaufortWindSpeed(7), beaufortWindSpeed(10), wind.windSpeed);
    // The new wind's streaks fade in as the last wind's fade out where they lie.
    const double blend = ocean_.windBlend().at(ocean_.time());
    w.spindrift = float(strength * blend);
    w.spindriftFrom = float(spindriftFrom_ * (1.0 - blend));
    w.windDirectionFrom = streaksFrom_;
}

namespace {
constexpr double kRingDecaySeconds = 10.0, kRingFoamSeconds = 3.0, kRingLifeSeconds = 40.0;
} // namespace

void OceanEffect::disturb(glm::dvec2 uv, float energy, ImpactKind kind) {
    if (!isFinite(uv)) throw Error(str("OceanEffect::disturb: texcoords must be finite, got ", text(uv)));
    if (!(energy > 0.0f) || !std::isfinite(energy))
        throw Error(str("OceanEffect::disturb: energy must be positive and finite, got ", energy));
    const bool blast = kind == ImpactKind::Explosion;
    const float size = std::cbrt(energy);
    const Ring ring{.uv = uv,
                    .start = ocean_.time(),
                    .wavelength = blast ? 5.0f : 0.8f,
                    .amplitude = (blast ? 0.5f : 0.06f) * size,
                    .foam = std::min(1.0f, (blast ? 1.0f : 0.4f) * size)};
    if (rings_.size() == size_t(kMaxWaterRings)) rings_.erase(rings_.begin()); // the oldest goes
    rings_.push_back(ring);
    updateRings();
}

void OceanEffect::updateRings() {
    const double now = ocean_.time();
    std::erase_if(rings_, [&](const Ring& r) { return now - r.start > kRingLifeSeconds || now < r.start; });
    const double patch = ocean_.config().patchMeters, depth = double(material_.depthScale) * patch;
    WaterLook& w = material_.water;
    w.ringCount = int(rings_.size());
    for (size_t i = 0; i < rings_.size(); ++i) {
        const Ring& r = rings_[i];
        const double t = now - r.start, lambda = r.wavelength;
        // Deep water: a packet of wavelength lambda travels at half its phase speed; its height
        // falls as energy spreads over the growing circle and as it decays.
        const double groupSpeed = 0.5 * std::sqrt(kGravity * lambda / (2.0 * 3.14159265358979));
        const double r0 = 0.5 * lambda, radius = r0 + groupSpeed * t;
        const double amplitude = r.amplitude * std::exp(-t / kRingDecaySeconds) * std::sqrt(r0 / radius);
        w.rings[i] = {.centre = glm::vec2(r.uv),
                      .radius = float(radius / patch),
                      .width = float(0.8 * lambda / patch),
                      .wavenumber = float(2.0 * 3.14159265358979 / lambda * patch),
                      .amplitude = float(amplitude / depth),
                      .foam = float(r.foam * std::exp(-t / kRingFoamSeconds))};
    }
}

void OceanEffect::setWind(float speed, float direction) { setWind(speed, direction, windBlendSeconds_); }

void OceanEffect::setWind(float speed, float direction, double blendSeconds) {
    // The streaks as they are fade out: of a change still blending in, the stronger of its two
    // (the weaker goes at once).
    const WaterLook& w = material_.water;
    const bool newer = w.spindrift >= w.spindriftFrom;
    const float from = newer ? w.spindrift : w.spindriftFrom;
    const glm::vec2 fromDirection = newer ? w.windDirection : w.windDirectionFrom;
    ocean_.setWind(speed, direction, blendSeconds);
    spindriftFrom_ = from;
    streaksFrom_ = fromDirection;
    material_.depthScale = physicalDepthScale();
    updateFoamLook(0.0);
    refresh();
}

void OceanEffect::settleFoam(double seconds) {
    ocean_.settleFoam(seconds); // the foam cleared, then `seconds` of it
    foamSeconds_ = seconds;
    updateFoamLook(0.0);
    refresh();
}

void OceanEffect::setTime(double seconds) {
    ocean_.setTime(seconds); // the foam cleared
    foamSeconds_ = 0.0;
    rings_.clear();
    material_.water.ringCount = 0;
    material_.depthScale = physicalDepthScale();
    updateFoamLook(0.0);
    refresh();
}

} // namespace hfx
