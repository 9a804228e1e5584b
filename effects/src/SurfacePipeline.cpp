#include "hfx/effects/SurfacePipeline.h"

#include "StreamTransfer.h"

#include "hfx/core/Error.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/core/GpuTimer.h"

#include <chrono>
#include <cmath>
#include <optional>

namespace hfx {

void SurfacePipelineConfig::validate() const {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("SurfacePipelineConfig size must be in 1..16384, got ", width, "x", height));
    if (!(normalDepth > 0.0f) || !std::isfinite(normalDepth))
        throw Error(str("SurfacePipelineConfig.normalDepth must be positive and finite, got ", normalDepth));
}

SurfacePipelineConfig SurfacePipelineConfig::of(const HeightSource& source, float normalDepth,
                                                const SurfaceOptions& options) {
    return {.width = source.width(),
            .height = source.height(),
            .edges = source.edges(),
            .normalDepth = normalDepth > 0.0f ? normalDepth : 0.05f,
            .options = options};
}

SurfaceFormat chooseSurfaceFormat(SurfaceFormat requested, const GlWorkarounds& device) {
    if (requested != SurfaceFormat::Auto) return requested;
    return device.float32Surfaces ? SurfaceFormat::Float32 : SurfaceFormat::Float16;
}

SurfaceFormat chooseSurfaceFormat(SurfaceFormat requested) {
    return requested != SurfaceFormat::Auto ? requested
                                            : chooseSurfaceFormat(requested, glWorkarounds(currentGlRenderer()));
}

namespace {

/// `config` validated, its format chosen for the GL context's device (`device`).
SurfacePipelineConfig chosen(const SurfacePipelineConfig& config, const GlWorkarounds& device) {
    SurfacePipelineConfig c = validated(config);
    c.options.format = chooseSurfaceFormat(c.options.format, device);
    return c;
}

SurfaceTexturesConfig texturesConfig(const SurfacePipelineConfig& c) {
    return {.width = c.width,
            .height = c.height,
            .mipmaps = c.options.mipmaps,
            .edges = c.edges,
            .format = c.options.format,
            .normalDepth = c.normalDepth};
}

std::unique_ptr<PixelBuffer> makePixels(TransferPath path, const SurfacePipelineConfig& c) {
    if (path != TransferPath::PixelBuffer) return nullptr;
    return std::make_unique<PixelBuffer>(texelBytes(c.options.format) * size_t(c.width) * c.height);
}

/// Maps the first `bytes` of `buffer` for reading (waiting for the queue's work on it), hands
/// the mapping to `upload`, and unmaps whatever happens.
template <typename Upload>
void mapAndUpload(ClContext& cl, const cl::Buffer& buffer, size_t bytes, const char* what, Upload&& upload) {
    cl::CommandQueue& q = cl.queue();
    void* mapped = clGuard(what, [&] { return q.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes); });
    try {
        upload(mapped);
    } catch (...) {
        q.enqueueUnmapMemObject(buffer, mapped);
        throw;
    }
    clGuard(what, [&] { q.enqueueUnmapMemObject(buffer, mapped); });
}

} // namespace

double SurfacePipeline::nowMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SurfacePipeline::SurfacePipeline(ClContext& cl, const SurfacePipelineConfig& config)
    : SurfacePipeline(cl, config, glWorkarounds(currentGlRenderer())) {}

SurfacePipeline::SurfacePipeline(ClContext& cl, const SurfacePipelineConfig& config, const GlWorkarounds& device)
    : cl_(cl), config_(chosen(config, device)), transfer_(chooseTransferPath(cl, config_.options.transfer)),
      pixels_(makePixels(transfer_, config_)),
      // A float32 surface's texels are the normals themselves: with a pixel buffer, they lie in it.
      sobel_(cl, config_.sobel(),
             pixels_ && config_.options.format == SurfaceFormat::Float32 ? pixels_->memory() : nullptr),
      textures_{std::make_unique<SurfaceTextures>(texturesConfig(config_)),
                std::make_unique<SurfaceTextures>(texturesConfig(config_))} {
    // A float32 surface's stored heights are the device's: where GL builds the bounds slower than
    // the device and the copy (GlWorkarounds::pyramidFromCompute), they come from the device.
    boundsFromDevice_ = config_.options.format == SurfaceFormat::Float32 &&
                        device.pyramidFromCompute &&
                        carriesBounds(textures_[0]->config());
    if (boundsFromDevice_)
        for (auto& b : bounds_) b = std::make_unique<HeightBounds>(textures_[0]->config()); // storage on first upload
    if (config_.options.format != SurfaceFormat::Float32)
        packer_ = std::make_unique<SurfacePacker>(cl, config_.width, config_.height, config_.options.format,
                                                  pixels_ ? pixels_->memory() : nullptr);
    if (transfer_ == TransferPath::Staged || transfer_ == TransferPath::GlSharing ||
        transfer_ == TransferPath::ExternalMemory)
        streams_ = std::make_unique<StreamTransfer>(cl, transfer_);
}

SurfacePipeline::~SurfacePipeline() {
    // The streams' own destructor waits for their copies; a pixel buffer's memory is GL's, which
    // the device's kernels may still be writing.
    if (!pixels_) return; // device buffers of their own outlive their kernels by reference counts
    try {
        cl_.queue().finish();
    } catch (...) {
        // Destructors never throw; a failed finish leaves nothing running to wait for.
    }
}

std::string SurfacePipeline::transferDescription() const {
    const std::string memory = streams_ ? streams_->description() : "";
    return str(surfaceFormatName(config_.options.format), " texels", packer_ ? " packed on the device" : "", ", ",
               transferPathName(transfer_), " path", memory.empty() ? "" : str(" (", memory, ")"));
}

void SurfacePipeline::setAlbedo(const Image& albedo) {
    for (auto& t : textures_) t->setAlbedo(albedo);
}

void SurfacePipeline::wait() {
    clGuard("SurfacePipeline: waiting for the device", [&] { cl_.queue().finish(); });
}

void SurfacePipeline::begin(StageTiming timing) {
    if (state_ == State::Submitted) finish(); // never two frames in flight
    // A frame abandoned before submit() (its source refused a bad dt, say) is simply dropped:
    // whatever it enqueued wrote nothing GL reads.
    state_ = State::Begun;
    timing_ = timing;
    boundsThisFrame_ = false;
    albedo_ = cl::Buffer();
    channels_ = cl::Buffer();
    times_ = {};
    start_ = nowMs();
}

void SurfacePipeline::derive(const cl::Buffer& heights) {
    HFX_CHECK(state_ == State::Begun);
    if (timing_ == StageTiming::Staged) wait();
    derived_ = nowMs();
    if (pixels_) pixels_->waitUntilRead(); // the normals or the packing write the pixel buffer
    sobel_.run(heights);
    if (timing_ == StageTiming::Staged) wait();
    normalsDone_ = nowMs();
    // Either pair's bounds read since the last frame: the device goes on building them (both
    // pairs' wishes are taken, each once).
    boundsThisFrame_ = false;
    if (boundsFromDevice_)
        for (auto& b : bounds_) boundsThisFrame_ = b->takeWanted() || boundsThisFrame_;
    if (boundsThisFrame_) {
        if (!pyramid_) pyramid_ = std::make_unique<BoundsPyramid>(cl_, config_.width, config_.height, config_.edges);
        pyramid_->build(heights);
    }
    state_ = State::Derived;
}

void SurfacePipeline::submit(const cl::Buffer* albedo, const cl::Buffer* channels) {
    HFX_CHECK(state_ == State::Derived);
    const size_t needed = 4 * size_t(config_.width) * config_.height;
    for (auto [buffer, name] : {std::pair{albedo, "albedo"}, std::pair{channels, "shading channels"}})
        if (buffer && buffer->getInfo<CL_MEM_SIZE>() < needed)
            throw Error(str("SurfacePipeline::submit: the ", name, " buffer holds ", buffer->getInfo<CL_MEM_SIZE>(),
                            " bytes, a ", config_.width, "x", config_.height, " RGBA8 map needs ", needed));
    if (packer_) packer_->run(sobel_.output());
    if (albedo) albedo_ = *albedo;
    if (channels) channels_ = *channels;
    if (streams_) {
        // The copies towards GL go behind the frame's kernels now, and run while the host draws.
        const size_t texels = size_t(config_.width) * config_.height;
        const cl::Buffer& source = packer_ ? packer_->output() : sobel_.output();
        streams_->enqueue(StreamTransfer::Texels, source, texelBytes(config_.options.format) * texels);
        if (boundsThisFrame_)
            streams_->enqueue(StreamTransfer::Pyramid, pyramid_->buffer(), pyramid_->totalTexels() * 2 * sizeof(float));
        if (albedo_()) streams_->enqueue(StreamTransfer::Albedo, albedo_, 4 * texels);
        if (channels_()) streams_->enqueue(StreamTransfer::Channels, channels_, 4 * texels);
    }
    clGuard("SurfacePipeline::submit", [&] {
        cl_.queue().enqueueMarkerWithWaitList(nullptr, &submitted_);
        cl_.queue().flush(); // start now, not at the wait
    });
    state_ = State::Submitted;
    if (timing_ == StageTiming::Staged) {
        wait();
        const double done = nowMs();
        times_ = {.compute = done - start_,
                  .upload = 0.0,
                  .field = derived_ - start_,
                  .normals = normalsDone_ - derived_,
                  .extra = done - normalsDone_};
    }
}

void SurfacePipeline::finish() {
    if (state_ != State::Submitted) {
        state_ = State::Idle;
        return;
    }
    state_ = State::Idle; // a failed upload leaves no frame in flight
    const double waitStart = nowMs();
    clGuard("SurfacePipeline::finish", [&] { submitted_.wait(); });
    const double computed = nowMs();
    if (timing_ == StageTiming::Overlapped) times_ = {.compute = computed - waitStart, .staged = false};

    SurfaceTextures& back = *textures_[1 - front_];
    const size_t texels = size_t(config_.width) * config_.height;
    // The texels in the surface's own layout: packed, or for float32 the normals themselves.
    const cl::Buffer& source = packer_ ? packer_->output() : sobel_.output();
    const size_t bytes = texelBytes(config_.options.format) * texels;
    const GpuScope upload("upload");
    if (streams_) streams_->arrive();
    // Each stream from where its path left it: the staged or shared pixel buffer, or a mapping.
    auto uploadStream = [&](StreamTransfer::Stream stream, const cl::Buffer& buffer, size_t size, const char* what,
                            auto&& glUpload) {
        if (streams_) {
            glUpload(streams_->source(stream));
            streams_->unbind();
        } else {
            mapAndUpload(cl_, buffer, size, what, glUpload);
        }
    };
    if (pixels_) {
        // Mapping a buffer over host memory waits for its writers and makes that memory current
        // (on a device sharing host memory it copies nothing); GL then reads it where it lies.
        mapAndUpload(cl_, source, bytes, "uploading the surface from the pixel buffer", [&](const void* mapped) {
            // A buffer made over host memory maps to that memory (CL_MEM_USE_HOST_PTR).
            HFX_CHECK_EQ(mapped, static_cast<const void*>(pixels_->memory()));
            pixels_->uploadTexels(back);
        });
    } else {
        uploadStream(StreamTransfer::Texels, source, bytes, "uploading the surface",
                     [&](const void* from) { back.uploadTexels(from); });
    }
    if (boundsThisFrame_)
        uploadStream(StreamTransfer::Pyramid, pyramid_->buffer(), pyramid_->totalTexels() * 2 * sizeof(float),
                     "uploading the height bounds",
                     [&](const void* levels) { bounds_[1 - front_]->upload(levels, back); });
    if (albedo_())
        uploadStream(StreamTransfer::Albedo, albedo_, 4 * texels, "uploading the albedo",
                     [&](const void* rgba) { back.uploadAlbedo(static_cast<const unsigned char*>(rgba)); });
    if (channels_())
        uploadStream(StreamTransfer::Channels, channels_, 4 * texels, "uploading the shading channels",
                     [&](const void* rgba) { back.uploadChannels(static_cast<const unsigned char*>(rgba)); });
    if (streams_) streams_->uploaded();
    front_ = 1 - front_;
    times_.upload = nowMs() - computed;
}

void SurfacePipeline::run(const cl::Buffer& heights, const cl::Buffer* albedo) {
    begin(StageTiming::Staged);
    derive(heights);
    submit(albedo);
    finish();
}

} // namespace hfx
