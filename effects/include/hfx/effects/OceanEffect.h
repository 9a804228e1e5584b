#pragma once
// The procedural-water user: a FieldEffect over the FFT ocean (Tessendorf), shaded as water
// (Fresnel-weighted sky reflection, sun glint, body colour by depth). The relief depth follows
// the sea state: a patch of patchMeters carries 8 sigma metres between h = 0 and h = 1, so the
// depth scale is 8 sigma / patchMeters texture units (times `reliefExaggeration`), and a
// stronger wind deepens the waves on screen, not only their shape.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/OceanField.h"
#include "hfx/effects/FieldEffect.h"

namespace hfx {

struct OceanEffectConfig {
    OceanConfig ocean{.size = 512, .spectrum = OceanSpectrum::Jonswap};
    SurfaceMaterial material{.minSamples = 8, .maxSamples = 40, .shadowSharpness = 1.0f,
                             .specularStrength = 0.0f, .shading = Shading::Water};
    float reliefExaggeration = 1.0f; ///< multiplies the physical depth scale
    FieldOptions surface; ///< mip maps, height pyramid, storage format, path to GL
    void validate() const;
};

class OceanEffect final : public FieldEffect {
public:
    explicit OceanEffect(ClContext& cl, const OceanEffectConfig& config = {});

    /// Live wind change (m/s, radians from +u); throws and changes nothing on bad values.
    void setWind(float speed, float direction);
    /// Jumps to an absolute time (seconds) and refreshes the textures.
    void setTime(double seconds);
    double time() const { return ocean_.time(); }
    const OceanField& ocean() const { return ocean_; }
    /// 8 sigma / patchMeters * exaggeration: what the material's depth scale is set to.
    float physicalDepthScale() const;

private:
    OceanField& ocean_;
    float exaggeration_;
};

} // namespace hfx
