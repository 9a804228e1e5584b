#include "hfx/effects/FieldEffect.h"

#include "hfx/core/Error.h"
#include "hfx/effects/FieldUpload.h"

#include <chrono>

namespace hfx {
namespace {
const HeightSource& checked(const std::unique_ptr<HeightSource>& source) {
    if (!source) throw Error("FieldEffect needs a height source, got none");
    return *source;
}
SurfaceTexturesConfig texturesConfig(const HeightSource& source, const FieldOptions& o) {
    return {.width = source.width(),
            .height = source.height(),
            .mipmaps = o.mipmaps,
            .edges = source.edges(),
            .pyramid = o.pyramid,
            .format = o.format};
}

std::unique_ptr<PixelBuffer> makePixels(TransferPath path, const HeightSource& source, SurfaceFormat format) {
    if (path != TransferPath::PixelBuffer) return nullptr;
    return std::make_unique<PixelBuffer>(texelBytes(format) * size_t(source.width()) * source.height());
}

} // namespace

double FieldEffect::nowMs() {
    return std::chrono::duration<double, std::milli>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

FieldEffect::FieldEffect(ClContext& cl, std::unique_ptr<HeightSource> source,
                         const SurfaceMaterial& material, const FieldOptions& options)
    : cl_(cl), material_((material.validate(), material)), transfer_(chooseTransferPath(cl, options.transfer)),
      pixels_(makePixels(transfer_, checked(source), options.format)),
      // A float32 surface's texels are the normals themselves: with a pixel buffer, they lie in it.
      normals_(cl,
               SobelConfig{.width = source->width(),
                           .height = source->height(),
                           .depthScale = material.depthScale,
                           .edges = source->edges()},
               pixels_ && options.format == SurfaceFormat::Float32 ? pixels_->memory() : nullptr),
      textures_{std::make_unique<SurfaceTextures>(texturesConfig(*source, options)),
                std::make_unique<SurfaceTextures>(texturesConfig(*source, options))} {
    source_ = std::move(source);
    if (options.pyramid)
        pyramid_ = std::make_unique<MaxPyramid>(cl, source_->width(), source_->height(), source_->edges());
    if (options.format != SurfaceFormat::Float32)
        packer_ = std::make_unique<SurfacePacker>(cl, source_->width(), source_->height(), options.format,
                                                  pixels_ ? pixels_->memory() : nullptr);
    refresh(nowMs());
}

FieldEffect::~FieldEffect() {
    if (!pixels_) return; // device buffers of their own outlive their kernels by reference counts
    try {
        cl_.queue().finish();
    } catch (...) {
        // Destructors never throw; a failed finish leaves nothing running to wait for.
    }
}

std::string FieldEffect::transferDescription() const {
    return str(surfaceFormatName(textures_[0]->config().format), " texels", packer_ ? " packed on the device" : "",
               ", ", transferPathName(transfer_), " path");
}

void FieldEffect::stepSource(double dt) { source_->step(dt); }

void FieldEffect::setAlbedo(const Image& albedo) {
    for (auto& t : textures_) t->setAlbedo(albedo);
}

void FieldEffect::update(double dt) {
    if (pending_) endUpdate();
    const double start = nowMs();
    stepSource(dt);
    refresh(start);
}

void FieldEffect::beginUpdate(double dt) {
    if (pending_) endUpdate(); // never two in flight
    const double start = nowMs();
    stepSource(dt);
    if (pixels_) pixels_->waitUntilRead(); // the normals or the packing write the pixel buffer
    normals_.run(source_->buffer());
    if (pyramid_) pyramid_->build(source_->buffer());
    enqueueExtra();
    if (packer_) packer_->run(normals_.output());
    clGuard("FieldEffect::beginUpdate", [&] {
        cl_.queue().enqueueMarkerWithWaitList(nullptr, &pendingDone_);
        cl_.queue().flush(); // start now, not at the wait
    });
    pending_ = true;
    pendingStart_ = start;
}

void FieldEffect::endUpdate() {
    if (!pending_) return;
    pending_ = false;
    const double waitStart = nowMs();
    clGuard("FieldEffect::endUpdate", [&] { pendingDone_.wait(); });
    const double computed = nowMs();
    upload();
    times_ = {.compute = computed - waitStart, .upload = nowMs() - computed, .field = 0, .normals = 0, .extra = 0};
}

void FieldEffect::upload() {
    SurfaceTextures& back = uploadTarget();
    // The texels in the surface's own layout: packed, or for float32 the normals themselves.
    const cl::Buffer& texels = packer_ ? packer_->output() : normals_.output();
    if (pixels_)
        uploadFromPixelBuffer(cl_, texels, *pixels_, back);
    else
        uploadTexels(cl_, texels, back);
    if (pyramid_) uploadPyramid(cl_, *pyramid_, back);
    uploadExtra();
    front_ = 1 - front_;
}

namespace {
double finishedMs(ClContext& cl) {
    clGuard("FieldEffect::update", [&] { cl.queue().finish(); });
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace

void FieldEffect::setDepthScale(float depthScale) {
    SurfaceMaterial next = material_;
    next.depthScale = depthScale;
    next.validate();
    normals_.setDepthScale(depthScale);
    material_ = next;
}

void FieldEffect::refresh(double computeStartMs) {
    pending_ = false; // an overlapped update in flight is part of what this waits for
    // Each stage is waited for, so the frame's budget can be read stage by stage; the queue is
    // in order and the CPU device runs one kernel at a time, so the waits cost no overlap.
    const double stepped = finishedMs(cl_);
    if (pixels_) pixels_->waitUntilRead();
    normals_.run(source_->buffer());
    const double normalised = finishedMs(cl_);
    if (pyramid_) pyramid_->build(source_->buffer());
    enqueueExtra();
    if (packer_) packer_->run(normals_.output());
    const double computed = finishedMs(cl_);
    upload();
    times_ = {.compute = computed - computeStartMs,
              .upload = nowMs() - computed,
              .field = stepped - computeStartMs,
              .normals = normalised - stepped,
              .extra = computed - normalised};
}

} // namespace hfx
