// Both of HFX's VkFFT plans, InverseRealFft (the ocean) and RealFft (the gas's pressure), in one
// file: VkFFT's header is 33,000 lines of code generator, compiled here only.
#include "hfx/compute/InverseRealFft.h"
#include "hfx/compute/RealFft.h"

#include "hfx/core/Error.h"

#include <CL/cl.h>
#include <locale.h> // newlocale, uselocale (POSIX)
#include <string>

// VkFFT's code generator writes its kernels' constants with sprintf, and sets the process's
// locale to "C" around that with setlocale: a call that races with every other thread of the
// host (setlocale is not thread-safe), and that does not reach a thread which has its own locale
// (uselocale), whose sprintf kept writing "8,66...e-01" into the kernels, which C reads as its
// comma operator: the transform came out wrong with no error. Its setlocale calls are made no-ops
// here (compiled into this file only); the plan runs with this thread alone in the C locale
// (inTheCLocale).
//
// It builds its kernels with no options and no hook for them, and PoCL's clang printed "N
// warnings generated" for them on a cold build; its clBuildProgram calls get "-w" here (a
// standard OpenCL option: PoCL then prints nothing, checked with a #warning), where HFX once set
// POCL_EXTRA_BUILD_FLAGS in the process's environment for the plan, which no other thread may
// touch meanwhile. HFX's own kernels are held to -Werror by ClContextTest.EveryKernelBuildsWithoutWarnings.
namespace hfx::detail {
inline const char* vkfftSetlocale(const char*) { return "C"; }
inline cl_int vkfftBuildProgram(cl_program program, cl_uint count, const cl_device_id* devices,
                                void(CL_CALLBACK* notify)(cl_program, void*), void* data) {
    return clBuildProgram(program, count, devices, "-w", notify, data);
}
} // namespace hfx::detail
#define setlocale(category, name) ::hfx::detail::vkfftSetlocale(name)
#define clBuildProgram(program, count, devices, options, notify, data)                             \
    ::hfx::detail::vkfftBuildProgram(program, count, devices, notify, data)
#define VKFFT_BACKEND 3
#include <vkFFT.h>
#undef clBuildProgram
#undef setlocale

namespace hfx {
namespace {

std::string vkfftResultName(VkFFTResult r) {
    switch (r) {
#define HFX_CASE(c) case c: return str(#c, " (", int(c), ")")
        HFX_CASE(VKFFT_ERROR_MALLOC_FAILED);
        HFX_CASE(VKFFT_ERROR_INSUFFICIENT_CODE_BUFFER);
        HFX_CASE(VKFFT_ERROR_INVALID_DEVICE);
        HFX_CASE(VKFFT_ERROR_INVALID_CONTEXT);
        HFX_CASE(VKFFT_ERROR_INVALID_PLATFORM);
        HFX_CASE(VKFFT_ERROR_UNSUPPORTED_RADIX);
        HFX_CASE(VKFFT_ERROR_UNSUPPORTED_FFT_LENGTH);
        HFX_CASE(VKFFT_ERROR_UNSUPPORTED_FFT_LENGTH_R2C);
        HFX_CASE(VKFFT_ERROR_FAILED_TO_ALLOCATE);
        HFX_CASE(VKFFT_ERROR_FAILED_TO_CREATE_PROGRAM);
        HFX_CASE(VKFFT_ERROR_FAILED_TO_COMPILE_PROGRAM);
        HFX_CASE(VKFFT_ERROR_FAILED_TO_SET_KERNEL_ARG);
        HFX_CASE(VKFFT_ERROR_FAILED_TO_LAUNCH_KERNEL);
#undef HFX_CASE
    default: return str("VkFFT error ", int(r));
    }
}

/// Runs `plan` with this thread in the C locale (uselocale), and puts back the thread's own
/// locale, or the process's where it had none: the process's locale is never touched. (VkFFT's
/// own setlocale, made a no-op above, also restored through a pointer its "C" call had freed
/// where the locale was a composite one: AddressSanitizer found the read in a window run, GLFW's
/// X11 start setting LC_CTYPE alone.)
template <typename F>
auto inTheCLocale(F&& plan) {
    static const locale_t c = newlocale(LC_ALL_MASK, "C", locale_t(0));
    if (!c) throw Error("VkFFT: newlocale could not make the C locale to plan in");
    const locale_t before = uselocale(c);
    struct Restore {
        locale_t before;
        ~Restore() { uselocale(before); }
    } restore{before};
    return plan();
}

/// A VkFFT application and the handles it reads through pointers: VkFFT keeps pointers to these
/// (device, context, buffers, sizes) for the plan's lifetime, and reads the buffers' handles
/// through them at every launch, so a launch only writes its own handles into the same slots.
/// `spectrum` is VkFFT's `buffer` (rows of W/2 + 1 complex values), `field` its formatted
/// `inputBuffer` (rows of W floats, no padding), which an inverse plan writes when told to
/// return to the input buffer.
struct VkFftPlan {
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
    cl_context context = nullptr;
    cl_command_queue queue = nullptr;
    cl_mem spectrum = nullptr;
    cl_mem field = nullptr;
    uint64_t spectrumBytes = 0;
    uint64_t fieldBytes = 0;
    VkFFTApplication app = {};
    bool initialised = false;

    VkFftPlan(ClContext& cl, size_t spectrumSize, size_t fieldSize) {
        platform = cl.device().getInfo<CL_DEVICE_PLATFORM>();
        device = cl.device()();
        context = cl.context()();
        queue = cl.queue()();
        spectrumBytes = spectrumSize;
        fieldBytes = fieldSize;
    }
    ~VkFftPlan() {
        if (initialised) deleteVkFFT(&app);
    }
    VkFftPlan(const VkFftPlan&) = delete;
    VkFftPlan& operator=(const VkFftPlan&) = delete;

    /// The configuration's device, buffers and their strides for W-wide rows, W x H a field.
    VkFFTConfiguration configuration(int width, int height) {
        VkFFTConfiguration c = {};
        c.platform = &platform;
        c.device = &device;
        c.context = &context;
        c.commandQueue = &queue;
        c.performR2C = 1;
        c.isInputFormatted = 1;
        c.inverseReturnToInputBuffer = 1;
        c.buffer = &spectrum;
        c.bufferSize = &spectrumBytes;
        c.bufferStride[0] = uint64_t(width / 2 + 1);
        c.bufferStride[1] = uint64_t(width / 2 + 1) * uint64_t(height);
        c.inputBuffer = &field;
        c.inputBufferSize = &fieldBytes;
        c.inputBufferStride[0] = uint64_t(width);
        c.inputBufferStride[1] = uint64_t(width) * uint64_t(height);
        return c;
    }

    /// Makes the plan; `what` names it in the error (VkFFT has then freed what it made, and
    /// printed the build log of a kernel that failed).
    void initialise(const VkFFTConfiguration& c, ClContext& cl, const std::string& what) {
        const VkFFTResult result = inTheCLocale([&] { return initializeVkFFT(&app, c); });
        if (result != VKFFT_SUCCESS)
            throw Error(
                str("VkFFT could not plan the ", what, " on ", cl.description(), ": ", vkfftResultName(result)));
        initialised = true;
    }

    /// Enqueues the transform (VkFFT's direction: -1 forward, 1 inverse) of `spectrumBuffer` and
    /// `fieldBuffer` on the context's queue; its kernels do not go through ClContext::enqueue, so
    /// two markers time them when asked. `what()` names the transform, called only for an error
    /// (a gas step or an ocean frame runs several).
    template <typename What>
    void append(ClContext& cl, const cl::Buffer& spectrumBuffer, const cl::Buffer& fieldBuffer, int direction,
                What&& what) {
        spectrum = spectrumBuffer();
        field = fieldBuffer();
        queue = cl.queue()();
        VkFFTLaunchParams launch = {};
        launch.commandQueue = &queue;
        launch.buffer = &spectrum;
        launch.inputBuffer = &field;
        cl::Event before, after;
        if (cl.recordingKernelTimes()) cl.queue().enqueueMarkerWithWaitList(nullptr, &before);
        const VkFFTResult result = VkFFTAppend(&app, direction, &launch);
        if (result != VKFFT_SUCCESS)
            throw Error(str("VkFFT: the ", what(), " failed to enqueue on ", cl.description(), ": ",
                            vkfftResultName(result)));
        if (cl.recordingKernelTimes()) {
            cl.queue().enqueueMarkerWithWaitList(nullptr, &after);
            cl.recordSpan("vkfft", before, after);
        }
    }
};

} // namespace

struct InverseRealFft::Plan : VkFftPlan {
    using VkFftPlan::VkFftPlan;
};

InverseRealFft::InverseRealFft(ClContext& cl, int n, int batch) : cl_(cl), n_(n), batch_(batch) {
    if (n < 2 || n > 8192 || (n & (n - 1)) != 0)
        throw Error(str("InverseRealFft: the size must be a power of two in [2, 8192], got ", n));
    if (batch < 1 || batch > 64) throw Error(str("InverseRealFft: the batch must be in [1, 64], got ", batch));
    plan_ = std::make_unique<Plan>(cl, spectrumBytes(), fieldBytes());
    VkFFTConfiguration c = plan_->configuration(n, n);
    c.FFTdim = 2;
    c.size[0] = uint64_t(n);
    c.size[1] = uint64_t(n);
    c.numberBatches = uint64_t(batch);
    c.makeInversePlanOnly = 1;
    plan_->initialise(c, cl, str(n, "x", n, " inverse real FFT (batch ", batch, ")"));
}

InverseRealFft::~InverseRealFft() = default;

void InverseRealFft::enqueue(const cl::Buffer& spectrum, const cl::Buffer& fields) {
    const auto batch = [&] { return str("a batch of ", batch_, " ", n_, "x", n_, " transforms"); };
    requireBufferBytes(spectrum, spectrumBytes(), "InverseRealFft::enqueue: the spectrum", batch);
    requireBufferBytes(fields, fieldBytes(), "InverseRealFft::enqueue: the fields", batch);
    plan_->append(cl_, spectrum, fields, 1, [&] { return str(n_, "x", n_, " inverse real FFT"); });
}

std::string InverseRealFft::libraryVersion() {
    const int v = VkFFTGetVersion();
    return str("VkFFT ", v / 10000, ".", (v / 100) % 100, ".", v % 100);
}

struct RealFft::Plan : VkFftPlan {
    using VkFftPlan::VkFftPlan;
};

RealFft::RealFft(ClContext& cl, int width, int height, Axes axes)
    : cl_(cl), width_(width), height_(height), axes_(axes) {
    if (width < 2 || width > 8192 || width % 2 != 0 || height < 2 || height > 8192)
        throw Error(str("RealFft: the size must be an even width and a height in [2, 8192], got ", width, "x",
                        height));
    plan_ = std::make_unique<Plan>(cl, spectrumBytes(), fieldBytes());
    VkFFTConfiguration c = plan_->configuration(width, height);
    c.FFTdim = 2;
    c.size[0] = uint64_t(width);
    c.size[1] = uint64_t(height);
    c.omitDimension[1] = axes == Axes::Rows ? 1 : 0; // the rows alone: H transforms of W
    plan_->initialise(c, cl,
                      str(width, "x", height, " real FFT", axes == Axes::Rows ? " along the rows" : ""));
}

RealFft::~RealFft() = default;

void RealFft::forward(const cl::Buffer& field, const cl::Buffer& spectrum) { enqueue(spectrum, field, -1); }

void RealFft::inverse(const cl::Buffer& spectrum, const cl::Buffer& field) { enqueue(spectrum, field, 1); }

void RealFft::enqueue(const cl::Buffer& spectrum, const cl::Buffer& field, int direction) {
    const auto transform = [&] { return str("a ", width_, "x", height_, " transform"); };
    requireBufferBytes(spectrum, spectrumBytes(), "RealFft: the spectrum", transform);
    requireBufferBytes(field, fieldBytes(), "RealFft: the field", transform);
    plan_->append(cl_, spectrum, field, direction,
                  [&] { return str(width_, "x", height_, direction < 0 ? " forward" : " inverse", " real FFT"); });
}

} // namespace hfx
