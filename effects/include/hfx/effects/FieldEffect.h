#pragma once
// The frame of any generated field: source.step(dt) -> Sobel normals -> GL upload, every update.
// Draw it with SurfaceRenderer using textures() and material(). The textures are double
// buffered: endUpdate() uploads into the pair the last draw did not read, then swaps, so a GPU
// never waits for an in-flight draw to release the texture being refreshed.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/HeightSource.h"
#include "hfx/compute/MaxPyramid.h"
#include "hfx/compute/SobelNormals.h"
#include "hfx/compute/SurfacePacker.h"
#include "hfx/effects/Effect.h"
#include "hfx/effects/FieldUpload.h"

#include <memory>

namespace hfx {

/// How a field effect stores and moves its surface; each effect's configuration holds one as `surface`.
struct FieldOptions {
    bool mipmaps = true;
    /// Also build the maximum-height pyramid each update (for Technique::Hierarchical; the
    /// field's sizes must be powers of two).
    bool pyramid = false;
    /// The surface textures' storage; other than Float32, a SurfacePacker packs the texels on
    /// the device before the transfer.
    SurfaceFormat format = SurfaceFormat::Float32;
    TransferPath transfer = TransferPath::Auto; ///< resolved by chooseTransferPath
};

class FieldEffect : public Effect {
public:
    FieldEffect(ClContext& cl, std::unique_ptr<HeightSource> source, const SurfaceMaterial& material,
                const FieldOptions& options = {});
    /// Waits for device work still writing the pixel buffer (an overlapped update in flight)
    /// before the buffer's memory goes.
    ~FieldEffect() override;

    void update(double dt) override;
    void beginUpdate(double dt) override;
    void endUpdate() override;
    /// The textures to draw now (they change after each update: ask every frame).
    const SurfaceTextures& textures() const override { return *textures_[front_]; }
    const SurfaceMaterial& material() const override { return material_; }
    StageTimes lastTimes() const override { return times_; }
    std::string transferDescription() const override;

    HeightSource& source() { return *source_; }
    const SobelNormals& normals() const { return normals_; }
    /// Changes the relief depth; the normals follow from the next update.
    void setDepthScale(float depthScale);
    /// The path the surface takes to GL (never Auto: what Auto chose).
    TransferPath transferPath() const { return transfer_; }

protected:
    /// Runs the normals and the upload for whatever the source holds now.
    void refresh(double computeStartMs);
    /// Hooks for derived effects: advance the source (default: source().step(dt)), enqueue more
    /// device work after the normals (timed as compute), and upload more after the field (into
    /// uploadTarget(), timed as upload).
    virtual void stepSource(double dt);
    virtual void enqueueExtra() {}
    virtual void uploadExtra() {}
    ClContext& cl() { return cl_; }
    static double nowMs();
    /// The textures the running update uploads into (the back pair until it swaps).
    SurfaceTextures& uploadTarget() { return *textures_[1 - front_]; }
    /// A fixed albedo for both pairs.
    void setAlbedo(const Image& albedo);

private:
    ClContext& cl_;
    std::unique_ptr<HeightSource> source_;
    SurfaceMaterial material_;
    TransferPath transfer_;
    std::unique_ptr<PixelBuffer> pixels_; ///< the PixelBuffer path's staging, else null
    SobelNormals normals_;
    std::unique_ptr<SurfaceTextures> textures_[2];
    int front_ = 0;
    std::unique_ptr<MaxPyramid> pyramid_;
    std::unique_ptr<SurfacePacker> packer_; ///< null for Float32
    StageTimes times_;
    // The overlapped update in flight: when it started, and the marker its wait is for.
    bool pending_ = false;
    double pendingStart_ = 0.0;
    cl::Event pendingDone_;
    void upload();
};

} // namespace hfx
