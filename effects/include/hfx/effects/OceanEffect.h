#pragma once
// The procedural-water user: the FFT ocean (OceanField: physical spectra, cascades, choppy
// waves, foam) shaded as water, drawn as one layer per cascade (SurfaceRenderer's layered
// surfaces). Texcoords: one unit is the largest cascade's patch (OceanField::config().patchMeters
// metres); the others repeat at their own lengths. The material's depth scale follows the sea
// state: the cascades carry 8 sigma_i metres each between h = 0 and 1, so the relief is
// 8 sum(sigma_i) / patch texture units (times `reliefExaggeration`), and each cascade's normals
// are made for its own physical depth, so their slopes add as the sea's do.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/DamageLog.h"
#include "hfx/compute/OceanField.h"
#include "hfx/effects/Effect.h"

#include <glm/vec2.hpp>

#include <memory>
#include <vector>

namespace hfx {

struct OceanEffectConfig {
    OceanConfig ocean;
    /// The look; its depthScale is replaced by the sea state's (physicalDepthScale()). With
    /// boundedSearch (on by default) the renderer's exact tracer builds each traced cascade's
    /// height bounds every frame: the searches (POM and the other sampled techniques) then step
    /// only through the depths the waves reach on each ray's path, and shadow rays only below the
    /// waves' top there (hfx_segment_bounds). It costs a bounds build per traced cascade (unorm8
    /// takes none: its rounding exceeds the bounds' margin, and the searches go unbounded).
    SurfaceMaterial material{.minSamples = 8, .maxSamples = 40, .shadowSharpness = 1.0f,
                             .specularStrength = 0.0f, .shading = Shading::Water, .water = {.foam = true},
                             .boundedSearch = true};
    float reliefExaggeration = 1.0f; ///< multiplies the physical depth scale
    /// How long a wind change (setWind) takes to blend in, seconds of the sea's time: a gust
    /// that takes the sea over at once reads as a cut.
    double windBlendSeconds = 4.0;
    /// The finest cascades whose weights together are at most this share of the relief depth
    /// are left out of the trace (SurfaceLayer::traced): flat there, they still shade. Each saves
    /// a fetch per search and shadow step; their height moves the hit by at most half their share
    /// of the depth. 0 traces every cascade.
    float untracedShare = 0.05f;
    /// The foam's bubbles, metres across (WaterLook::foamCells, which the effect sets every step:
    /// aged foam opens into their lace, every foam's edge frays through them); 0 draws none.
    float foamCellMeters = 0.5f;
    /// Storage and path to GL, for every cascade. hier traces one grid: it needs one cascade.
    SurfaceOptions surface;
    void validate() const; ///< throws hfx::Error naming the bad field and its value
};

class OceanEffect final : public Effect {
public:
    explicit OceanEffect(ClContext& cl, const OceanEffectConfig& config = {});

    /// Live wind change (m/s, radians from +u): the new sea blends in over the config's
    /// windBlendSeconds, and the depth scale in material() follows it frame by frame; throws and
    /// changes nothing on bad values.
    void setWind(float speed, float direction);
    /// The same over `blendSeconds` (0: at once).
    void setWind(float speed, float direction, double blendSeconds);
    /// The foam as `seconds` of this wind would have left it (OceanField::settleFoam), and the
    /// textures refreshed: a first frame of a sea that has blown a while. The wind's streaks grow
    /// with it (foamSeconds()).
    void settleFoam(double seconds);
    /// Seconds of wind the foam has seen: 0 when the effect is made and after setTime (a clear
    /// start), settleFoam's seconds after it, and every step's added. A gale's streaks are drawn
    /// from the whitecaps' foam, so they build as it does: their strength is the wind's times
    /// 1 - 2^(-foamSeconds / FoamConfig::halfLife) (half after one half-life, 97% after five).
    double foamSeconds() const { return foamSeconds_; }
    /// Jumps to an absolute time (seconds) and refreshes the textures; rings are dropped, the foam
    /// starts clear (OceanField::setTime) and the streaks with it.
    void setTime(double seconds);
    /// An impact on the water at `uv` (the mesh's texcoords, in patches: metres over the
    /// largest patch): a ring of waves spreads from it at the group speed of its wavelength,
    /// with foam on its crest, and decays (a bullet: 0.8 m waves, an explosion: 5 m; amplitudes
    /// grow with the cube root of `energy`, 1 being the kind's usual). At most kMaxWaterRings at
    /// once, the oldest replaced; rings live in material().water and are not tiled with the
    /// patches. Throws hfx::Error and adds nothing on a non-finite uv or energy <= 0.
    void disturb(glm::dvec2 uv, float energy, ImpactKind kind);
    int ringCount() const { return material_.water.ringCount; }
    double time() const { return ocean_.time(); }
    const OceanField& ocean() const { return ocean_; }
    /// 8 sum(sigma_i) / patch * exaggeration: the depth scale of the sea as it is now.
    float physicalDepthScale() const;
    /// The cascades, largest first: texcoord scales patch / L_i, weights sigma_i / sum(sigma);
    /// the finest untraced as the config's untracedShare says.
    std::vector<SurfaceLayer> layers() const override;

private:
    const SurfacePipeline& surface() const override { return *surfaces_.front(); }
    std::vector<const SurfacePipeline*> surfaces() const override;
    void advance(double dt) override;
    void enqueueSurface() override;

    /// Each cascade's share of the relief depth, sigma_i / sum(sigma).
    std::vector<float> cascadeWeights() const;
    /// Which cascades the searches trace, given their weights (untracedShare).
    std::vector<bool> tracedCascades(const std::vector<float>& weights) const;
    /// Writes the live rings into material_.water for the sea's time now.
    void updateRings();
    /// Writes the foam's look into material_.water for the present wind: its bubbles' lattice, and
    /// the wind streaks (the last wind's fading out as the new wind's fade in, as the waves
    /// blend), drifted by dt seconds of the foam's drift.
    void updateFoamLook(double dt);

    struct Ring {
        glm::dvec2 uv;
        double start;
        float wavelength, amplitude, foam; ///< metres, metres, coverage
    };
    std::vector<Ring> rings_;
    glm::dvec2 foamDrift_{0.0}; ///< texcoords the foam has drifted downwind
    double foamSeconds_ = 0.0;   ///< seconds of wind the foam has seen (foamSeconds())
    float spindriftFrom_ = 0.0f; ///< the streaks' strength a wind change blends from
    glm::vec2 streaksFrom_{1.0f, 0.0f}; ///< ... and their direction
    OceanField ocean_;
    float exaggeration_;
    double windBlendSeconds_;
    float untracedShare_;
    float foamCellMeters_;
    std::vector<std::unique_ptr<SurfacePipeline>> surfaces_; ///< one per cascade
};

} // namespace hfx
