#include "hfx/compute/InverseRealFft.h"

#include "hfx/core/Error.h"

#include <clocale>
#include <cstdlib>
#include <string>

// VkFFT's OpenCL back end, in this file only: the header is 33,000 lines of code generator.
#define VKFFT_BACKEND 3
#include <vkFFT.h>

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

/// VkFFT builds its generated kernels with no hook for build options, and PoCL's clang prints
/// "N warnings generated" for them on a cold build. PoCL reads POCL_EXTRA_BUILD_FLAGS at each
/// build, so "-w" is set for the plan alone, unless the user set the variable. HFX's own kernels
/// are held to -Werror by ClContextTest.EveryKernelBuildsWithoutWarnings.
template <typename F>
auto withoutPoclWarnings(F&& plan) {
    const bool ours = std::getenv("POCL_EXTRA_BUILD_FLAGS") == nullptr;
    if (ours) setenv("POCL_EXTRA_BUILD_FLAGS", "-w", 0);
    const auto result = plan();
    if (ours) unsetenv("POCL_EXTRA_BUILD_FLAGS");
    return result;
}

/// VkFFT's code generator keeps the pointer setlocale(LC_ALL, NULL) returns, sets "C", and
/// restores the locale through that pointer, which the "C" call has freed where the locale was a
/// composite one (GLFW's X11 start sets LC_CTYPE alone: AddressSanitizer found the read in a
/// window run). The plan is made under "C" here, so its save and restore both name the C
/// locale's own string, and the caller's locale is put back from a copy.
template <typename F>
auto inTheCLocale(F&& plan) {
    const char* current = std::setlocale(LC_ALL, nullptr);
    const std::string saved = current ? current : "C";
    std::setlocale(LC_ALL, "C");
    const auto result = plan();
    std::setlocale(LC_ALL, saved.c_str());
    return result;
}

} // namespace

struct InverseRealFft::Plan {
    // VkFFT keeps pointers to these (device, context, buffers, sizes) for the plan's lifetime,
    // and reads the buffers' handles through them at every launch: enqueue() only writes the
    // handles of the call into the same slots.
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
    cl_context context = nullptr;
    cl_command_queue queue = nullptr;
    cl_mem spectrum = nullptr;
    cl_mem fields = nullptr;
    uint64_t spectrumBytes = 0;
    uint64_t fieldBytes = 0;
    VkFFTApplication app = {};
    bool initialised = false;
    ~Plan() {
        if (initialised) deleteVkFFT(&app);
    }
};

InverseRealFft::InverseRealFft(ClContext& cl, int n, int batch)
    : cl_(cl), n_(n), batch_(batch), plan_(std::make_unique<Plan>()) {
    if (n < 2 || n > 8192 || (n & (n - 1)) != 0)
        throw Error(str("InverseRealFft: the size must be a power of two in [2, 8192], got ", n));
    if (batch < 1 || batch > 64) throw Error(str("InverseRealFft: the batch must be in [1, 64], got ", batch));
    Plan& p = *plan_;
    p.platform = cl.device().getInfo<CL_DEVICE_PLATFORM>();
    p.device = cl.device()();
    p.context = cl.context()();
    p.queue = cl.queue()();
    p.spectrumBytes = spectrumBytes();
    p.fieldBytes = fieldBytes();
    // Out of place: the complex half spectra are VkFFT's `buffer` (rows of N/2 + 1), the real
    // fields its formatted `inputBuffer` (rows of N, no padding), which an inverse R2C plan
    // writes when told to return to the input buffer.
    VkFFTConfiguration c = {};
    c.FFTdim = 2;
    c.size[0] = uint64_t(n);
    c.size[1] = uint64_t(n);
    c.numberBatches = uint64_t(batch);
    c.platform = &p.platform;
    c.device = &p.device;
    c.context = &p.context;
    c.commandQueue = &p.queue;
    c.performR2C = 1;
    c.makeInversePlanOnly = 1;
    c.isInputFormatted = 1;
    c.inverseReturnToInputBuffer = 1;
    c.buffer = &p.spectrum;
    c.bufferSize = &p.spectrumBytes;
    c.bufferStride[0] = uint64_t(n / 2 + 1);
    c.bufferStride[1] = uint64_t(n / 2 + 1) * uint64_t(n);
    c.inputBuffer = &p.fields;
    c.inputBufferSize = &p.fieldBytes;
    c.inputBufferStride[0] = uint64_t(n);
    c.inputBufferStride[1] = uint64_t(n) * uint64_t(n);
    // On failure VkFFT has freed what it made (and printed the build log of a kernel that failed).
    const VkFFTResult result =
        withoutPoclWarnings([&] { return inTheCLocale([&] { return initializeVkFFT(&p.app, c); }); });
    if (result != VKFFT_SUCCESS)
        throw Error(str("VkFFT could not plan the ", n, "x", n, " inverse real FFT (batch ", batch, ") on ",
                        cl.description(), ": ", vkfftResultName(result)));
    p.initialised = true;
}

InverseRealFft::~InverseRealFft() = default;

void InverseRealFft::enqueue(const cl::Buffer& spectrum, const cl::Buffer& fields) {
    const size_t haveSpectrum = spectrum.getInfo<CL_MEM_SIZE>(), haveFields = fields.getInfo<CL_MEM_SIZE>();
    if (haveSpectrum < spectrumBytes() || haveFields < fieldBytes())
        throw Error(str("InverseRealFft::enqueue: a ", n_, "x", n_, " batch of ", batch_, " needs ", spectrumBytes(),
                        " bytes of spectrum and ", fieldBytes(), " of fields, got ", haveSpectrum, " and ",
                        haveFields));
    Plan& p = *plan_;
    p.spectrum = spectrum();
    p.fields = fields();
    p.queue = cl_.queue()();
    VkFFTLaunchParams launch = {};
    launch.commandQueue = &p.queue;
    launch.buffer = &p.spectrum;
    launch.inputBuffer = &p.fields;
    // Its kernels do not go through ClContext::enqueue: two markers time them when asked.
    cl::Event before, after;
    if (cl_.recordingKernelTimes()) cl_.queue().enqueueMarkerWithWaitList(nullptr, &before);
    const VkFFTResult result = VkFFTAppend(&p.app, 1, &launch);
    if (result != VKFFT_SUCCESS)
        throw Error(str("VkFFT: the ", n_, "x", n_, " inverse real FFT failed to enqueue on ", cl_.description(), ": ",
                        vkfftResultName(result)));
    if (cl_.recordingKernelTimes()) {
        cl_.queue().enqueueMarkerWithWaitList(nullptr, &after);
        cl_.recordSpan("vkfft", before, after);
    }
}

std::string InverseRealFft::libraryVersion() {
    const int v = VkFFTGetVersion();
    return str("VkFFT ", v / 10000, ".", (v / 100) % 100, ".", v % 100);
}

} // namespace hfx
