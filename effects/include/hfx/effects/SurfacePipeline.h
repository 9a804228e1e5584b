#pragma once
// The one path from a height buffer on the compute device to the textures a renderer draws:
//
//   heights --Sobel--> normals (float4: normal.xyz, h) --[passes]--> pack --transfer--> textures
//   (the exact tracer builds its height bounds on the GL side from the textures' heights,
//   BoundsPass; on a CPU rasteriser a float32 surface's are built here and transferred while a
//   draw reads them, GlWorkarounds::pyramidFromCompute, bounds())
//
// Every user goes down it: the generated fields (ocean, waves, gas, decals), a static map from
// files (ImageSurface, via StaticField) and the accuracy probe. A frame is five calls, in order:
//
//   surface.begin(timing);          // the frame's clock starts; the source steps after this
//   surface.derive(heights);        // Sobel (+ bounds) of the source's buffer, enqueued
//   ... passes on surface.normals() // effect-specific work, e.g. DetailNormals::apply
//   surface.submit(&albedo);        // packing into the storage format; the device work is flushed
//   surface.finish();               // waits, moves texels (+ bounds, albedo) to GL, swaps
//
// With StageTiming::Staged each stage is waited for and timed (lastTimes() reads the budget
// stage by stage); with Overlapped nothing waits until finish(), so a draw issued between
// submit() and finish() hides the compute. The textures are double buffered: finish() uploads
// into the pair the last draw did not read, then swaps.
//
// Owns its compute buffers, the GL textures and the pixel buffer. Thread: the thread that owns
// both the ClContext and the current GL context.

#include "hfx/compute/HeightSource.h"
#include "hfx/compute/BoundsPyramid.h"
#include "hfx/compute/SobelNormals.h"
#include "hfx/compute/SurfacePacker.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/core/Image.h"
#include "hfx/core/PixelBuffer.h"
#include "hfx/core/SurfaceTextures.h"
#include "hfx/effects/TransferPath.h"
#include "hfx/effects/tracer/HeightBounds.h"

#include <memory>
#include <string>

namespace hfx {

class StreamTransfer;

/// How a surface is stored and moved; each effect's configuration holds one as `surface`.
struct SurfaceOptions {
    bool mipmaps = true;
    /// The surface textures' storage; other than Float32, a SurfacePacker packs the texels on
    /// the device before the transfer. Auto: the device's (chooseSurfaceFormat).
    SurfaceFormat format = SurfaceFormat::Auto;
    TransferPath transfer = TransferPath::Auto; ///< resolved by chooseTransferPath
};

/// The format `requested` resolves to: Auto takes Float16 (half the bytes to move and to sample,
/// heights to 2^-11 near 1: docs/ACCURACY.md) where `device` is a GPU, Float32 where it asks for
/// it (GlWorkarounds::float32Surfaces, a CPU rasteriser); any other format is itself.
SurfaceFormat chooseSurfaceFormat(SurfaceFormat requested, const GlWorkarounds& device);
/// The same for the current GL context's device.
SurfaceFormat chooseSurfaceFormat(SurfaceFormat requested);

struct SurfacePipelineConfig {
    int width = 512;
    int height = 512;
    EdgeMode edges = EdgeMode::Wrap;
    /// The relief depth the normals are derived for (SobelConfig::normalDepth); the renderer
    /// rescales them to the material's depth, so any positive value draws right.
    float normalDepth = 0.05f;
    SurfaceOptions options;
    void validate() const; ///< throws hfx::Error naming the bad field and its value
    /// The Sobel filter this surface runs: for passes that derive normals alike (DetailNormals).
    SobelConfig sobel() const { return {.width = width, .height = height, .edges = edges, .normalDepth = normalDepth}; }
    /// The size and edges of `source`; normalDepth is usually the material's depth at the start
    /// (a flat material's 0 becomes 0.05: any positive depth draws right).
    static SurfacePipelineConfig of(const HeightSource& source, float normalDepth, const SurfaceOptions& options);
};

/// Wall-clock milliseconds of the last frame, by stage (measured on the host around waits).
struct StageTimes {
    double compute = 0.0; ///< field step + normals + bounds and passes + packing
    double upload = 0.0;  ///< map, GL upload, mip generation
    // The parts of compute, each waited for on its own (so they add up to compute):
    double field = 0.0;   ///< the source's step
    double normals = 0.0; ///< Sobel
    double extra = 0.0;   ///< the effect's passes, packing (and llvmpipe's bounds)
    // With StageTiming::Overlapped the parts are not waited for one by one: compute is then the
    // time finish() still had to wait, the part the draw did not hide.
    bool staged = true; ///< the parts above were waited for one by one
};

enum class StageTiming {
    Staged,     ///< every stage waited for and timed: lastTimes() has each part
    Overlapped, ///< nothing waits before finish(): the compute runs beside whatever GL does
};

class SurfacePipeline {
public:
    SurfacePipeline(ClContext& cl, const SurfacePipelineConfig& config);
    /// Waits for device work still writing the pixel buffer (a frame submitted, not finished)
    /// before the buffer's memory goes.
    ~SurfacePipeline();
    SurfacePipeline(const SurfacePipeline&) = delete;
    SurfacePipeline& operator=(const SurfacePipeline&) = delete;

    /// Starts a frame (finishing one still in flight first: never two at once). The time until
    /// derive() is the source's step.
    void begin(StageTiming timing);
    /// Enqueues the Sobel normals of `heights`, width*height floats, and where the device builds
    /// the height bounds and a draw read them since the last derive(), the bounds.
    void derive(const cl::Buffer& heights);
    /// The float4 normals derive() writes: passes between derive() and submit() may edit them.
    const cl::Buffer& normals() const { return sobel_.output(); }
    /// Enqueues the packing and ends the frame's device work. `albedo`, when given, is
    /// width*height RGBA8 on the device (a ColorRamp's output) that finish() uploads too;
    /// `channels` likewise, the shading channels (SurfaceTextures::uploadChannels).
    void submit(const cl::Buffer* albedo = nullptr, const cl::Buffer* channels = nullptr);
    /// Waits for the submitted frame, uploads it into the back textures and swaps. Without a
    /// submitted frame (begin() with nothing after it), does nothing.
    void finish();
    /// A frame submitted and not yet finished.
    bool pending() const { return state_ == State::Submitted; }

    /// begin(Staged), derive, submit, finish: a whole frame of `heights` now.
    void run(const cl::Buffer& heights, const cl::Buffer* albedo = nullptr);

    /// The textures to draw now (they change at each finish(): ask every frame).
    const SurfaceTextures& textures() const { return *textures_[front_]; }
    /// Their height bounds where the compute device builds them (float32 texels on a CPU
    /// rasteriser, GlWorkarounds::pyramidFromCompute: the device and the copy beat GL's build
    /// there), for SurfaceLayer::bounds; null elsewhere. Built while draws read them (noteWanted):
    /// the frame after the first such draw on, that draw's tracer builds its own.
    HeightBounds* bounds() const { return boundsFromDevice_ ? bounds_[front_].get() : nullptr; }
    /// A fixed albedo for both texture pairs (an image of the surface's size, or 1x1).
    void setAlbedo(const Image& albedo);
    StageTimes lastTimes() const { return times_; }
    /// The path the surface takes to GL (never Auto: what Auto chose).
    TransferPath transferPath() const { return transfer_; }
    /// "float16 texels packed on the device, pixel-buffer path", for start-up reports.
    std::string transferDescription() const;
    /// The configuration, its format chosen (never Auto: chooseSurfaceFormat's).
    const SurfacePipelineConfig& config() const { return config_; }

private:
    enum class State { Idle, Begun, Derived, Submitted };
    /// The constructor, with the GL context's workarounds asked for once.
    SurfacePipeline(ClContext& cl, const SurfacePipelineConfig& config, const GlWorkarounds& device);
    void wait(); ///< Staged: the queue's work so far
    static double nowMs();

    ClContext& cl_;
    SurfacePipelineConfig config_;
    TransferPath transfer_;
    std::unique_ptr<PixelBuffer> pixels_; ///< the PixelBuffer path's staging, else null
    std::unique_ptr<StreamTransfer> streams_; ///< the Staged and GlSharing paths' memory, else null
    SobelNormals sobel_;
    /// Where the device builds the bounds (GlWorkarounds::pyramidFromCompute): its pyramid,
    /// made when first read, and each texture pair's bounds on the GL side.
    bool boundsFromDevice_ = false;
    bool boundsThisFrame_ = false; ///< derive() enqueued them
    std::unique_ptr<BoundsPyramid> pyramid_;
    std::unique_ptr<HeightBounds> bounds_[2];
    std::unique_ptr<SurfacePacker> packer_; ///< null for Float32: the normals are the texels
    std::unique_ptr<SurfaceTextures> textures_[2];
    int front_ = 0;
    State state_ = State::Idle;
    StageTiming timing_ = StageTiming::Staged;
    cl::Buffer albedo_;    ///< this frame's device albedo, or none
    cl::Buffer channels_;  ///< this frame's device shading channels, or none
    cl::Event submitted_;  ///< a marker behind the frame's device work
    double start_ = 0.0, derived_ = 0.0, normalsDone_ = 0.0;
    StageTimes times_;
};

} // namespace hfx
