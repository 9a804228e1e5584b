#pragma once
// The frame of any generated field: source.step(dt) -> Sobel normals -> GL upload, every update.
// Draw it with SurfaceRenderer using textures() and material().
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/HeightSource.h"
#include "hfx/compute/MaxPyramid.h"
#include "hfx/compute/SobelNormals.h"
#include "hfx/effects/Effect.h"

#include <memory>

namespace hfx {

class FieldEffect : public Effect {
public:
    /// pyramid: also build the maximum-height pyramid each update (for Technique::Hierarchical;
    /// the field's sizes must be powers of two).
    FieldEffect(ClContext& cl, std::unique_ptr<HeightSource> source, const SurfaceMaterial& material,
                bool mipmaps = true, bool pyramid = false);

    void update(double dt) override;
    const SurfaceTextures& textures() const override { return textures_; }
    const SurfaceMaterial& material() const override { return material_; }
    StageTimes lastTimes() const override { return times_; }

    HeightSource& source() { return *source_; }
    const SobelNormals& normals() const { return normals_; }
    /// Changes the relief depth; the normals follow from the next update.
    void setDepthScale(float depthScale);

protected:
    /// Runs the normals and the upload for whatever the source holds now.
    void refresh(double computeStartMs);
    /// Hooks for derived effects: enqueue more device work after the normals (timed as
    /// compute), and upload more after the field (timed as upload).
    virtual void enqueueExtra() {}
    virtual void uploadExtra() {}
    ClContext& cl() { return cl_; }
    static double nowMs();
    SurfaceTextures& mutableTextures() { return textures_; }

private:
    ClContext& cl_;
    std::unique_ptr<HeightSource> source_;
    SurfaceMaterial material_;
    SobelNormals normals_;
    SurfaceTextures textures_;
    std::unique_ptr<MaxPyramid> pyramid_;
    StageTimes times_;
};

} // namespace hfx
