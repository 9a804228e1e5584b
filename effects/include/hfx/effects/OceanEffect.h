#pragma once
// The procedural-water user: the FFT ocean (Tessendorf), shaded as water (Fresnel-weighted sky
// reflection, sun glint, body colour by depth). The relief depth follows the sea state: a patch
// of patchMeters carries 8 sigma metres between h = 0 and h = 1, so the material's depth scale
// is 8 sigma / patchMeters texture units (times `reliefExaggeration`), and a stronger wind
// deepens the waves on screen, not only their shape.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/OceanField.h"
#include "hfx/effects/Effect.h"

namespace hfx {

struct OceanEffectConfig {
    OceanConfig ocean{.size = 512, .spectrum = OceanSpectrum::Jonswap};
    /// The look; its depthScale is replaced by the sea state's (physicalDepthScale()).
    SurfaceMaterial material{.minSamples = 8, .maxSamples = 40, .shadowSharpness = 1.0f,
                             .specularStrength = 0.0f, .shading = Shading::Water};
    float reliefExaggeration = 1.0f; ///< multiplies the physical depth scale
    SurfaceOptions surface; ///< mip maps, height pyramid, storage format, path to GL
    void validate() const;  ///< throws hfx::Error naming the bad field and its value
};

class OceanEffect final : public Effect {
public:
    explicit OceanEffect(ClContext& cl, const OceanEffectConfig& config = {});

    /// Live wind change (m/s, radians from +u): a new spectrum and with it a new depth scale in
    /// material(); throws and changes nothing on bad values.
    void setWind(float speed, float direction);
    /// Jumps to an absolute time (seconds) and refreshes the textures.
    void setTime(double seconds);
    double time() const { return ocean_.time(); }
    const OceanField& ocean() const { return ocean_; }
    /// 8 sigma / patchMeters * exaggeration: the depth scale of the sea as it is now.
    float physicalDepthScale() const;

private:
    const SurfacePipeline& surface() const override { return surface_; }
    void advance(double dt) override { ocean_.step(dt); }
    void enqueueSurface() override;

    OceanField ocean_;
    float exaggeration_;
    SurfacePipeline surface_;
};

} // namespace hfx
