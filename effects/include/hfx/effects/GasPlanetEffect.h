#pragma once
// The gaseous-planet user: the Navier-Stokes gas on a longitude-latitude grid (periodic in u,
// walls at the poles) drives a sphere's relief (the dye) and its colour (the dye through a
// ColorRamp, on the device). Zonal jets make the bands; storms, seeded, are oval vortices the gas
// is held towards, carried by its wind, their clouds fed a colour that stands out of their band.
// Detail finer than the gas's grid rides on its flow (FlowDetail): the surface is `detail.scale`
// texels per gas cell. Draw it on makeSphere() with modelMatrix(), which turns the planet slowly
// about +Y.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/ColorRamp.h"
#include "hfx/compute/GasField.h"
#include "hfx/compute/FlowDetail.h"
#include "hfx/compute/PolarFilter.h"
#include "hfx/core/Random.h"
#include "hfx/effects/Effect.h"
#include "hfx/effects/PlanetRings.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <memory>
#include <optional>
#include <vector>

namespace hfx {

/// Banded gas giant colours: dark belts, pale zones, rusty storm cores.
std::vector<ColorStop> gasGiantPalette();

struct GasPlanetConfig {
    /// MacCormack's advection keeps the bands' edges and the storms' curls sharp: semi-Lagrangian
    /// advection blurs an edge twice as wide (Gas.MacCormackKeepsAnAdvectedEdgeSharper), for 1.37x
    /// the gas step's time on PoCL on 2 cores of an Intel Xeon, Skylake-AVX512 (BM_PlanetGas in
    /// hfx-bench-kernels). On the sphere's metric (GasConfig::sphere), so its polar eddies are
    /// round on the planet, not on the map: 1.25x the flat map's step on the same device.
    /// Its pressure is solved exactly (GasPressure::Exact) and it spins (GasConfig::rotation, 8
    /// rad/s): its jets have inflection points and, on a still sphere, break into eddies within a
    /// minute or two (Jacobi's sweeps, which leave the large scales' divergence, only delay it);
    /// the spin's beta effect, above the jets' curvature (Rayleigh-Kuo: 6.9 at the equator),
    /// holds them (PlanetWeather.ThePlanetsSpinHoldsItsBandsWhichWithoutItBreakUp).
    GasConfig gas{.width = 512, .height = 256, .sphere = true, .vorticity = 0.35f,
                  .maccormack = true, .jetSpeed = 14.0f, .jetBands = 4.5f, .jetRate = 0.2f, .jetPolar = 1.0f,
                  .maxSpeed = 56.0f, .rotation = 8.0f, .initialBands = 9.0f, .bandVariety = 1.0f, .dyeRate = 0.15f};
    std::vector<ColorStop> palette = gasGiantPalette();
    float stormsPerSecond = 0.6f;  ///< new storms, their sizes drawn from 0.63x to 1.59x
    float stormRadius = 0.025f;    ///< a storm's half-length along the bands, in map widths
    float stormForce = 900.0f;     ///< its birth's push (cells per second^2 over a step)
    /// A storm lives on as an oval vortex that the gas's wind at its centre carries along its
    /// band (GasField::velocityAt, once a frame). The gas is held towards the vortex
    /// (GasField::addVortex): its fastest wind stormWind times gas.jetSpeed, stormAspect times
    /// longer along the bands than across, held at stormHold per second; its clouds are fed
    /// towards the storm's colour at stormFeed per second (a share of the way each second),
    /// which contrasts with its band: white in a dark belt, in a pale zone the palette's rusty
    /// top (turning clockwise) or a dark brown. The hold and the feed fade with the storm's age
    /// over stormLifeRotations turns of the planet; at most maxStorms at once (the oldest goes).
    float stormWind = 1.0f;
    float stormAspect = 2.0f;
    float stormHold = 1.0f;
    float stormFeed = 2.0f;
    float stormLifeRotations = 40.0f;
    int maxStorms = 32;
    /// The storm's clouds are fed over its oval (stormAspect), wound into stormArms spiral arms
    /// of its band's colour (GasArms): stormArmContrast of the way to the band's at each arm's
    /// crest on the oval's rim, none at its centre. The arms turn at the gas's spin at the
    /// storm's centre (Storm::turnRate) and their outer parts trail by stormWinding (1 -
    /// exp(-rho^2)) radians, as the vortex's slower rim leaves them. 0 arms: one colour.
    int stormArms = 3;
    float stormArmContrast = 0.8f;
    float stormWinding = 4.0f;
    /// Storms are seeded only where the jets' shear |dU/dy| is at most this fraction of its
    /// largest: in the middle of a band, where a vortex is not torn apart at once.
    float stormShear = 0.35f;
    /// Simulated seconds per second, 1 to 10^4; a frame's time is split into substeps of at most
    /// maxSubstep seconds, at most maxSubsteps of them (beyond, the substeps lengthen: the
    /// advection, whose MacCormack estimate is clamped to the values it came from, and the
    /// speed limit, gas.maxSpeed, keep them stable).
    float timeScale = 1.0f;
    float maxSubstep = 0.5f;
    int maxSubsteps = 8;
    /// The last fraction of rows at each pole fades to a flat 0.5, so the poles, where all the
    /// columns meet in one point, show no pinched seam. 0: none.
    float poleCap = 0.04f;
    /// The drawn heights' polar filter (PolarFilter): each row averaged along the longitude over
    /// this many degrees at 60 degrees of latitude, more towards the poles, in [0, 60]; 0: none.
    /// For a flat gas (gas.sphere false), whose eddies, round on the map, the sphere squeezes
    /// into wedges that meet in a starburst at a pole: 0.75 draws its caps with no starburst, as
    /// the sphere's metric does (PlanetWeather's ThePolesDrawNoStarburst... test).
    float polarSmoothing = 0.0f;
    float rotationSpeed = 0.08f;   ///< radians per second about +Y
    /// The cloud tops' detail finer than the gas's grid, advected by its flow (FlowDetail; its
    /// capRows come from poleCap, its seed from seed). scale 0 picks one for the compute
    /// device: the largest of 4, 2 and 1 that keeps the surface at most 2048 texels wide on a
    /// GPU, 1024 on a CPU device (autoDetailScale). A warp alone (band edges fray into
    /// filaments, the bands' middles stay smooth; added noise read as fur); amount and warp 0
    /// draw the gas's own heights alone.
    FlowDetailConfig detail{.scale = 0, .amount = 0.0f, .warp = 2.0f};
    /// The gas's grid per device: `gas` is the planet at its reference grid, and the simulation
    /// runs on gridScale times its cells on each axis with the same weather in planet units:
    /// the rates in cells (gas.jetSpeed, gas.maxSpeed, stormForce) scale by gridScale, the
    /// viscosity (cells^2 per second) by its square, and the pressure projection's iterations by
    /// its square too (Jacobi spreads a correction over the square root of its iterations in
    /// cells). The vorticity confinement (epsilon h |curl|, h a cell) weakens with the cell, as
    /// the numerical dissipation it makes up for does. 0: the device's (autoGridScale: 2 on a
    /// GPU, 1024x512 from the default, 1 on a CPU device); else in [1/16, 4].
    float gridScale = 1.0f;
    std::uint64_t seed = 1;
    SurfaceMaterial material{.depthScale = 0.006f, .minSamples = 8, .maxSamples = 32,
                             .shadowSharpness = 1.5f, .specularStrength = 0.05f, .specularPower = 16.0f,
                             .shading = Shading::Planet, .silhouetteFade = 0.25f};
    SurfaceOptions surface; ///< mip maps, storage format, path to GL
    /// Rings (PlanetRings) in the planet's equatorial plane, their radii in planet radii (the
    /// config's radius must be 1: the sphere's); none by default. Their shadow falls on the cloud
    /// tops (material().planet); draw them with rings()->draw after the planet.
    std::optional<PlanetRingsConfig> rings;
    void validate() const;  ///< throws hfx::Error naming the bad field and its value
};

/// The detail scale `scale` 0 stands for on `cl`'s device for a gas `gasWidth` cells wide.
int autoDetailScale(const ClContext& cl, int gasWidth);
/// The grid scale GasPlanetConfig::gridScale 0 stands for on `cl`'s device: 2 on a GPU, else 1.
float autoGridScale(const ClContext& cl);
/// `gas` on gridScale times its cells, its rates scaled to keep the weather (GasPlanetConfig::gridScale).
GasConfig scaledGas(const GasConfig& gas, float gridScale);

class GasPlanetEffect final : public Effect {
public:
    explicit GasPlanetEffect(ClContext& cl, const GasPlanetConfig& config = {});

    /// A storm now: a vortex of the configured size (times the cube root of `strength`, > 0)
    /// at texcoords (u in [0,1), v in [0,1]), pushed into spin and coloured at once.
    void addStorm(float u, float v, bool clockwise, float strength = 1.0f);
    /// Runs the weather `seconds` simulated seconds ([0, 10^6]) at once, in substeps of
    /// maxSubstep, storms and all: a planet that starts with its bands already worked by storms
    /// and shear (the demo spins up a minute). It ends by refreshing the textures, so what is
    /// drawn next, before any update, is the weather spun up. Waits for the device.
    void spinUp(double seconds);
    GasField& gas() { return gas_; }
    /// The heights drawn (the gas's, with the cloud tops' detail, polar filtered, surfaceWidth() x
    /// surfaceHeight()), row 0 at v = 0; waits.
    std::vector<float> readHeights();
    /// The cloud tops' detail: none when its amount, warp and poleCap are 0 (the surface is the gas's).
    const FlowDetail* detail() const { return detail_.get(); }
    /// The configuration as it runs on this device: the gas at its grid (gridScale applied,
    /// then 1), the detail's scale chosen.
    const GasPlanetConfig& config() const { return config_; }
    int surfaceWidth() const { return surface_.config().width; }
    int surfaceHeight() const { return surface_.config().height; }
    const ColorRamp& colors() const { return colors_; }
    double time() const { return time_; }
    /// Live time scale (validated as the config's); throws and keeps the old one on a bad value.
    void setTimeScale(float scale);
    float timeScale() const { return config_.timeScale; }
    /// The jets' zonal speed (cells per second) at texcoord v: what the gas relaxes towards.
    float jetProfile(double v) const;
    /// |dU/dv| of jetProfile relative to its largest over the planet (0 in a band's middle).
    float relativeShear(double v) const;
    /// A living storm: where it is now (texcoords), its size (half-length along u, widths) and
    /// spin, when it was born, its colour (the dye its clouds are fed towards) and the wind that
    /// carries it (cells per second: the gas's at its centre at the last frame's start).
    struct Storm {
        double u, v;
        float radius, strength;
        bool clockwise;
        double born;
        float colour;
        glm::vec2 wind;
        float band = 0.0f;     ///< its band's colour when it was born: its arms'
        float turnRate = 0.0f; ///< radians a second its centre turns (counter-clockwise), read with wind
        double turned = 0.0;   ///< radians its arms have turned at that rate (counter-clockwise)
    };
    const std::vector<Storm>& storms() const { return storms_; }
    /// Where the last seeded storms (not impacts) went, oldest first, at most 64.
    const std::vector<glm::vec2>& seededStorms() const { return seeded_; }
    /// Rotation about +Y after time() seconds: the planet's model matrix (scale not included).
    glm::mat4 modelMatrix() const;
    /// The planet's rings (GasPlanetConfig::rings), nullptr without.
    PlanetRings* rings() { return rings_.get(); }

private:
    const SurfacePipeline& surface() const override { return surface_; }
    /// New storms at their rate, then the gas's step.
    void advance(double dt) override;
    /// The relief from the dye, and the albedo: the dye through the colour ramp.
    void enqueueSurface() override;

    ClContext& cl_;
    GasPlanetConfig config_;
    GasField gas_;
    std::unique_ptr<FlowDetail> detail_; ///< none when config.detail.amount, warp and poleCap are 0
    std::unique_ptr<PolarFilter> polar_; ///< none when config.polarSmoothing is 0
    ColorRamp colors_;
    SplitMix64 random_;
    double time_ = 0.0, stormClock_ = 0.0;
    float maxShear_ = 1.0f;
    std::vector<Storm> storms_;
    std::vector<glm::vec2> stormSamples_, stormWinds_; ///< advance()'s, kept between frames
    /// Queues the two opposite zonal pushes that spin `storm` (force in cells per second^2).
    void spin(const Storm& storm, float force);
    std::vector<glm::vec2> seeded_;
    SurfacePipeline surface_;
    std::unique_ptr<PlanetRings> rings_; ///< none without GasPlanetConfig::rings
};

} // namespace hfx
