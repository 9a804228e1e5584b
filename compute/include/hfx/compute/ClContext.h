#pragma once
// The OpenCL device, its context and in-order queue, and a cache of built programs: in memory
// for the process, and on disk as program binaries (ProgramCache) for the next start.
//
// Device choice (ClDeviceChoice.h): among the devices that match HFX_CL_PLATFORM and HFX_CL_DEVICE
// (case-insensitive substrings: "nvidia", "portable", "gpu", "cpu"), a GPU before a CPU, then one
// that shares objects with the caller's GL context, then one on the GL renderer's hardware. The
// choice and the reason are logged once to stderr.
//
// Thread: one ClContext per thread that enqueues; programs and kernels it hands out are not
// shared across threads.

#include "hfx/compute/ClDeviceChoice.h"
#include "hfx/compute/OpenCl.h"
#include "hfx/compute/ProgramCache.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/core/EdgeMode.h"

#include <cstdint>
#include <map>
#include <unordered_map>
#include <string>
#include <string_view>
#include <utility>

namespace hfx {

struct ClContextConfig {
    std::string platform; ///< substring of the platform name; empty: HFX_CL_PLATFORM
    std::string device;   ///< substring of the device's label(); empty: HFX_CL_DEVICE
    bool log = true;      ///< print the chosen device to stderr
    /// The GL renderer the kernels' results go to (currentGlRenderer()): the choice prefers a
    /// device on its hardware. Empty: not considered.
    GlRendererInfo gl;
    /// The caller's GL context: a device that offers cl_khr_gl_sharing for it is preferred, and
    /// its context is made sharing (sharesGl()). None: no sharing.
    GlShareHandles glShare;
    /// Folder of program binaries; empty: ProgramCache::defaultFolder() (HFX_KERNEL_CACHE,
    /// else $XDG_CACHE_HOME/hfx/kernels); "off": build every program from source.
    std::string kernelCache;
};

/// How the programs of a context came to be, for start-up reports.
struct ClProgramStats {
    int built = 0;      ///< compiled from OpenCL C
    int loaded = 0;     ///< created from a cached binary
    int rejected = 0;   ///< cache entries damaged, stale or refused by the driver (rebuilt instead)
    int unsaved = 0;    ///< binaries the cache could not store
    double milliseconds = 0; ///< wall time spent creating and building programs
};

class ClContext {
public:
    explicit ClContext(const ClContextConfig& config = {});
    /// Waits for the queue's work first: a process must not exit while the driver still
    /// compiles or runs what was enqueued.
    ~ClContext();
    ClContext(const ClContext&) = delete;
    ClContext& operator=(const ClContext&) = delete;

    const cl::Context& context() const { return context_; }
    const cl::Device& device() const { return device_; }
    cl::CommandQueue& queue() { return queue_; }
    std::string description() const; ///< "device name (platform name, OpenCL x.y)"
    /// The context was made with the caller's GL context (glShare): GL textures and buffers can
    /// be used by the kernels through cl_khr_gl_sharing.
    bool sharesGl() const { return sharesGl_; }
    const GlShareHandles& glShare() const { return glShare_; }
    /// Why this device: "a GPU, on the GL renderer's hardware".
    const std::string& choiceReason() const { return reason_; }

    /// Builds an embedded kernel file (kernels/*.cl, with its #include "X.h" of the shared
    /// headers resolved) once per set of options; later calls return the cached program.
    /// Throws hfx::Error with the build log when it does not build.
    const cl::Program& program(std::string_view file, const std::string& options = {});
    /// Builds OpenCL C source text under a name used in errors; cached by name and options.
    const cl::Program& programFromSource(const std::string& name, const std::string& source,
                                         const std::string& options = {});
    cl::Kernel kernel(std::string_view file, const char* name, const std::string& options = {});

    /// Enqueues `kernel` over `global` work-items (and `local`, when given) on the queue, and
    /// counts the launch: every HFX kernel goes through here (VkFFT's own do not).
    void enqueue(const cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local = cl::NullRange);
    /// Device time of the kernels launched while recording (CL event profiling; the queue is made
    /// with CL_QUEUE_PROFILING_ENABLE): enqueue() keeps each launch's event, and work enqueued
    /// otherwise (VkFFT's) can add its own span with recordSpan().
    void recordKernelTimes(bool on) { recording_ = on; }
    bool recordingKernelTimes() const { return recording_; }
    /// Adds `name`'s device time as the span from the end of `before` to the end of `after`
    /// (two markers around work of the caller's), when recording.
    void recordSpan(const std::string& name, const cl::Event& before, const cl::Event& after);
    /// Waits for the recorded launches and returns their device milliseconds summed per kernel
    /// function name (and recorded span), forgetting them.
    std::map<std::string, double> takeKernelTimes();

    /// Launches so far through enqueue(), all kernels or those of one function name ("sobel4").
    std::uint64_t launches() const { return launches_; }
    std::uint64_t launches(std::string_view kernelName) const;

    const ProgramCache& programCache() const { return cache_; }
    const ClProgramStats& programStats() const { return stats_; }
    /// "9 programs in 41 ms: 9 from the cache /home/u/.cache/hfx/kernels, 0 compiled"
    std::string programReport() const;

private:
    cl::Program buildFromSource(const std::string& name, const std::string& text, const std::string& options);
    cl::Program buildFromCache(const std::string& key, const std::string& options);

    cl::Platform platform_;
    cl::Device device_;
    cl::Context context_;
    cl::CommandQueue queue_;
    bool sharesGl_ = false;
    GlShareHandles glShare_;
    std::string reason_;
    std::map<std::pair<std::string, std::string>, cl::Program> programs_;
    ProgramCache cache_;
    std::string cacheKeyPrefix_; ///< platform, device and driver identity
    ClProgramStats stats_;
    std::uint64_t launches_ = 0;
    bool recording_ = false;
    struct Recorded {
        std::string name;
        cl::Event begin, end; ///< a launch: begin is empty and end its own event; a span: two markers
    };
    std::vector<Recorded> recorded_;
    /// Per kernel object (held, so its handle is never reused by another), named on demand.
    struct Launches {
        cl::Kernel kernel;
        std::uint64_t count = 0;
    };
    std::unordered_map<cl_kernel, Launches> launchesByKernel_;
};

/// The kernel build options of an edge mode, "-DHFX_WRAP_U=1 -DHFX_WRAP_V=0": the one place an
/// EdgeMode becomes kernel text (read through hfx_edge_index, compute/shared/EdgeMath.h).
std::string edgeOptions(EdgeMode edges);

namespace detail {
[[noreturn]] void throwBufferTooSmall(const char* what, std::size_t bytes, const std::string& content,
                                      std::size_t needed);
}

/// Throws hfx::Error "<what> holds N bytes, <content> need M" where `buffer`, an input a kernel
/// will read, is smaller than `needed` bytes. `content()` says what fills them ("512x512 floats")
/// and is called only then: a kernel's every run checks its input, and words nothing unless it
/// fails.
template <typename Content>
void requireBufferBytes(const cl::Buffer& buffer, std::size_t needed, const char* what, Content&& content) {
    const std::size_t bytes = buffer.getInfo<CL_MEM_SIZE>();
    if (bytes < needed) detail::throwBufferTooSmall(what, bytes, content(), needed);
}

/// Sets `kernel`'s arguments 0, 1, ... to `args` in order (buffers, scalars, structs by value).
template <typename... Args>
void setArgs(cl::Kernel& kernel, const Args&... args) {
    cl_uint index = 0;
    (kernel.setArg(index++, args), ...);
}

/// Runs f, turning an OpenCL exception into hfx::Error that says what was being done.
template <typename F>
decltype(auto) clGuard(const char* what, F&& f);

namespace detail {
[[noreturn]] void rethrowCl(const char* what, const cl::Error& e);
}

template <typename F>
decltype(auto) clGuard(const char* what, F&& f) {
    try {
        return f();
    } catch (const cl::Error& e) {
        detail::rethrowCl(what, e);
    }
}

} // namespace hfx
