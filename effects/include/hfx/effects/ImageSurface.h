#pragma once
// A surface from maps (SurfaceMaps: read from files by the tools' readSurfaceMaps, or an engine's
// own loaders): a height map, an optional tangent-space normal map and an optional colour map.
// The heights go down the same
// SurfacePipeline as a generated field's (as a StaticField), so a map from files gets the Sobel
// normals, the exact tracer's height bounds, every surface format and both transfer paths; a normal map is
// laid over them by the same pass the decal wall uses (DetailNormals), which with unchanged
// heights gives the map exactly. Derived once: update() only checks dt.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/DetailNormals.h"
#include "hfx/compute/StaticField.h"
#include "hfx/core/SurfaceMaps.h"
#include "hfx/effects/Effect.h"

#include <memory>
#include <string>

namespace hfx {

struct ImageSurfaceConfig {
    /// Required: the heights; the normals (derived from the heights when empty) and the colour
    /// (light grey when empty) optional.
    SurfaceMaps maps;
    SurfaceMaterial material{.depthScale = 0.08f};
    EdgeMode edges = EdgeMode::Wrap; ///< tileable maps wrap; others clamp
    SurfaceOptions surface; ///< mip maps, storage format, path to GL
    void validate() const;  ///< throws hfx::Error naming the bad field and its value
};

class ImageSurface final : public Effect {
public:
    /// Throws hfx::Error naming the field for missing, mismatched or out-of-range maps, before
    /// anything is made on a device.
    ImageSurface(ClContext& cl, const ImageSurfaceConfig& config);

private:
    const SurfacePipeline& surface() const override { return surface_; }
    void advance(double dt) override { heights_.step(dt); }
    /// The first time only: the heights never change.
    void enqueueSurface() override;

    StaticField heights_;
    SurfacePipeline surface_;
    std::unique_ptr<DetailNormals> detail_; ///< with a normal map
    bool derived_ = false;
};

} // namespace hfx
