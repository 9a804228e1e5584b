#include "hfx/compute/ClContext.h"

#include <CL/cl_gl.h>

#include "hfx/core/Error.h"
#include "hfx/core/Source.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <vector>

namespace hfx {
namespace detail {
std::string_view embeddedKernel(std::string_view name);

void rethrowCl(const char* what, const cl::Error& e) {
    throw Error(str(what, ": ", e.what(), " failed with ", clErrorName(e.err())));
}
} // namespace detail

namespace detail {
void throwBufferTooSmall(const char* what, std::size_t bytes, const std::string& content, std::size_t needed) {
    throw Error(str(what, " holds ", bytes, " bytes, ", content, " need ", needed));
}
} // namespace detail

std::string clErrorName(cl_int code) {
    switch (code) {
#define HFX_CASE(c) case c: return str(#c, " (", code, ")")
        HFX_CASE(CL_DEVICE_NOT_FOUND);
        HFX_CASE(CL_DEVICE_NOT_AVAILABLE);
        HFX_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE);
        HFX_CASE(CL_OUT_OF_RESOURCES);
        HFX_CASE(CL_OUT_OF_HOST_MEMORY);
        HFX_CASE(CL_BUILD_PROGRAM_FAILURE);
        HFX_CASE(CL_INVALID_VALUE);
        HFX_CASE(CL_INVALID_BUFFER_SIZE);
        HFX_CASE(CL_INVALID_KERNEL_NAME);
        HFX_CASE(CL_INVALID_KERNEL_ARGS);
        HFX_CASE(CL_INVALID_ARG_SIZE);
        HFX_CASE(CL_INVALID_WORK_GROUP_SIZE);
        HFX_CASE(CL_INVALID_GLOBAL_WORK_SIZE);
        HFX_CASE(CL_INVALID_MEM_OBJECT);
        HFX_CASE(CL_INVALID_BUILD_OPTIONS);
#undef HFX_CASE
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR (-1001)";
    default: return str("OpenCL error ", code);
    }
}

namespace {

std::string fromEnv(const std::string& value, const char* variable) {
    if (!value.empty()) return value;
    const char* env = std::getenv(variable);
    return env ? env : "";
}

/// Replaces `#include "X.h"` lines by the embedded header X.h (each header once).
std::string resolveIncludes(const std::string& source, std::vector<std::string>& seen) {
    static const std::regex include(R"re(^[ \t]*#[ \t]*include[ \t]*"([^"]+)")re");
    std::string out;
    std::istringstream in(source);
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, include)) {
            const std::string file = m[1].str();
            const std::string base = file.substr(file.find_last_of('/') + 1);
            if (std::find(seen.begin(), seen.end(), base) == seen.end()) {
                seen.push_back(base);
                out += resolveIncludes(
                    loadSource(base, detail::embeddedKernel(base), "HFX_KERNEL_DIR").text, seen);
            }
            out += '\n';
            continue;
        }
        out += line + '\n';
    }
    return out;
}

std::string numbered(const std::string& source) {
    std::istringstream in(source);
    std::string line, out;
    for (int n = 1; std::getline(in, line); ++n) out += str(n < 10 ? "   " : n < 100 ? "  " : " ", n, "| ", line, '\n');
    return out;
}

} // namespace

namespace {

/// One device the process can see, with what the choice needs to know of it.
struct Present {
    cl::Platform platform;
    cl::Device device;
    ClDeviceInfo info;
    std::vector<cl_context_properties> sharing; ///< the context properties that share GL, or none
};

/// The context properties that tie a context on `platform` to the caller's GL context.
std::vector<cl_context_properties> sharingProperties(const cl::Platform& platform, const GlShareHandles& gl) {
    const cl_context_properties displayKey = gl.api == GlShareHandles::Api::Glx ? CL_GLX_DISPLAY_KHR : CL_EGL_DISPLAY_KHR;
    return {CL_GL_CONTEXT_KHR, reinterpret_cast<cl_context_properties>(gl.context), displayKey,
            reinterpret_cast<cl_context_properties>(gl.display), CL_CONTEXT_PLATFORM,
            reinterpret_cast<cl_context_properties>(platform()), 0};
}

/// The devices of `platform` that can share objects with the caller's GL context: what the
/// platform's cl_khr_gl_sharing says for it (none without the extension or without a context).
std::vector<cl_device_id> devicesSharingGl(const cl::Platform& platform, const GlShareHandles& gl) {
    if (gl.api == GlShareHandles::Api::None || !gl.context) return {};
    if (platform.getInfo<CL_PLATFORM_EXTENSIONS>().find("cl_khr_gl_sharing") == std::string::npos) return {};
    using Query = cl_int (*)(const cl_context_properties*, cl_gl_context_info, size_t, void*, size_t*);
    const auto query = reinterpret_cast<Query>(
        clGetExtensionFunctionAddressForPlatform(platform(), "clGetGLContextInfoKHR"));
    if (!query) return {};
    const std::vector<cl_context_properties> properties = sharingProperties(platform, gl);
    size_t bytes = 0;
    if (query(properties.data(), CL_DEVICES_FOR_GL_CONTEXT_KHR, 0, nullptr, &bytes) != CL_SUCCESS || bytes == 0)
        return {}; // NVIDIA refuses an EGL display (CL_INVALID_OPERATION): no sharing there
    std::vector<cl_device_id> ids(bytes / sizeof(cl_device_id));
    if (query(properties.data(), CL_DEVICES_FOR_GL_CONTEXT_KHR, bytes, ids.data(), nullptr) != CL_SUCCESS) return {};
    return ids;
}

std::vector<Present> presentDevices(const GlShareHandles& gl) {
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error&) {
        platforms.clear();
    }
    std::vector<Present> present;
    for (const cl::Platform& p : platforms) {
        std::vector<cl::Device> devices;
        try {
            p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue; // a platform with no device (CL_DEVICE_NOT_FOUND)
        }
        const std::vector<cl_device_id> sharing = devicesSharingGl(p, gl);
        for (const cl::Device& d : devices) {
            const bool shares = std::find(sharing.begin(), sharing.end(), d()) != sharing.end();
            present.push_back({p, d,
                               {.platform = p.getInfo<CL_PLATFORM_NAME>(),
                                .name = d.getInfo<CL_DEVICE_NAME>(),
                                .vendor = d.getInfo<CL_DEVICE_VENDOR>(),
                                .type = d.getInfo<CL_DEVICE_TYPE>(),
                                .sharesGl = shares},
                               shares ? sharingProperties(p, gl) : std::vector<cl_context_properties>{}});
        }
    }
    return present;
}

} // namespace

ClContext::ClContext(const ClContextConfig& config) {
    const std::string platformFilter = fromEnv(config.platform, "HFX_CL_PLATFORM");
    const std::string deviceFilter = fromEnv(config.device, "HFX_CL_DEVICE");
    const std::vector<Present> present = presentDevices(config.glShare);
    if (present.empty())
        throw Error("no OpenCL platform with a device found: install an OpenCL driver (on Debian without GPU: "
                    "apt-get install pocl-opencl-icd ocl-icd-libopencl1)");
    std::vector<ClDeviceInfo> infos;
    for (const Present& p : present) infos.push_back(p.info);
    const ClDeviceChoice choice = chooseClDevice(infos, platformFilter, deviceFilter, config.gl);
    if (choice.index < 0) {
        std::string seen;
        for (const ClDeviceInfo& info : infos) seen += "\n  " + info.label();
        throw Error(str("no OpenCL device matches HFX_CL_PLATFORM='", platformFilter, "' HFX_CL_DEVICE='",
                        deviceFilter, "'; devices present:", seen));
    }
    const Present& chosen = present[size_t(choice.index)];
    platform_ = chosen.platform;
    device_ = chosen.device;
    reason_ = choice.reason;
    sharesGl_ = !chosen.sharing.empty();
    if (sharesGl_) glShare_ = config.glShare;
    clGuard("creating the OpenCL context", [&] {
        context_ = sharesGl_ ? cl::Context(device_, chosen.sharing.data()) : cl::Context(device_);
        queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
    });
    cache_ = ProgramCache(config.kernelCache == "off" ? std::filesystem::path()
                          : config.kernelCache.empty() ? ProgramCache::defaultFolder()
                                                       : std::filesystem::path(config.kernelCache));
    // A binary is only valid for the driver that made it: its identity leads every key.
    cacheKeyPrefix_ = str("hfx program binary\nplatform ", platform_.getInfo<CL_PLATFORM_NAME>(), " ",
                          platform_.getInfo<CL_PLATFORM_VERSION>(), "\ndevice ", device_.getInfo<CL_DEVICE_NAME>(),
                          " ", device_.getInfo<CL_DEVICE_VERSION>(), "\ndriver ",
                          device_.getInfo<CL_DRIVER_VERSION>(), "\n");
    if (config.log) {
        std::string others;
        for (const ClDeviceInfo& info : infos)
            if (&info != &infos[size_t(choice.index)]) others += (others.empty() ? "" : ", ") + info.label();
        std::fprintf(stderr, "hfx: OpenCL device %s: %s%s; kernel cache %s\n", description().c_str(),
                     reason_.c_str(), others.empty() ? "" : str("; also present: ", others).c_str(),
                     cache_.enabled() ? cache_.folder().c_str() : "off");
    }
}

ClContext::~ClContext() {
    try {
        if (queue_()) queue_.finish();
    } catch (...) {
        // Destructors never throw; a failed finish leaves nothing to wait for.
    }
}

std::string ClContext::description() const {
    return str("'", device_.getInfo<CL_DEVICE_NAME>(), "' (", platform_.getInfo<CL_PLATFORM_NAME>(),
               ", ", device_.getInfo<CL_DEVICE_VERSION>(), ")");
}

const cl::Program& ClContext::program(std::string_view file, const std::string& options) {
    const auto key = std::make_pair(std::string(file), options);
    if (auto it = programs_.find(key); it != programs_.end()) return it->second;
    const SourceFile source = loadSource(file, detail::embeddedKernel(file), "HFX_KERNEL_DIR");
    return programFromSource(source.name, source.text, options);
}

const cl::Program& ClContext::programFromSource(const std::string& name, const std::string& source,
                                                const std::string& options) {
    const auto key = std::make_pair(name, options);
    if (auto it = programs_.find(key); it != programs_.end()) return it->second;
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::string> seen;
    const std::string text = resolveIncludes(source, seen);
    const std::string cacheKey = str(cacheKeyPrefix_, "options ", options, "\nsource\n", text);
    cl::Program program = buildFromCache(cacheKey, options);
    if (!program()) {
        program = buildFromSource(name, text, options);
        ++stats_.built;
        if (cache_.enabled()) {
            bool saved = false;
            try {
                const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
                saved = binaries.size() == 1 && cache_.store(cacheKey, binaries[0]);
            } catch (const cl::Error&) {
                saved = false; // a driver without binaries still has its program
            }
            if (!saved) ++stats_.unsaved;
        }
    }
    stats_.milliseconds += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return programs_.emplace(key, std::move(program)).first->second;
}

cl::Program ClContext::buildFromCache(const std::string& key, const std::string& options) {
    bool damaged = false;
    const std::optional<ProgramCache::Binary> binary = cache_.load(key, &damaged);
    if (damaged) ++stats_.rejected;
    if (!binary) return {};
    try {
        cl::Program program(context_, {device_}, cl::Program::Binaries{*binary});
        program.build({device_}, options.c_str());
        ++stats_.loaded;
        return program;
    } catch (const cl::Error&) {
        // A binary the driver refuses (an update it could not detect from its version) is
        // rebuilt from source, and the fresh binary replaces it.
        ++stats_.rejected;
        return {};
    }
}

cl::Program ClContext::buildFromSource(const std::string& name, const std::string& text, const std::string& options) {
    cl::Program program = clGuard("creating an OpenCL program", [&] { return cl::Program(context_, text); });
    try {
        program.build({device_}, options.c_str());
    } catch (const cl::Error& e) {
        std::string log;
        try {
            log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
        } catch (const cl::Error&) {
            log = "(no build log)";
        }
        throw Error(str("OpenCL kernel ", name, " failed to build (", clErrorName(e.err()),
                        ") with options '", options, "' on ", description(), ":\n", log,
                        "\nsource after includes:\n", numbered(text)));
    }
    return program;
}

std::string ClContext::programReport() const {
    const ClProgramStats& s = stats_;
    std::string report = str(s.built + s.loaded, " programs in ", int(s.milliseconds + 0.5), " ms: ");
    if (!cache_.enabled()) return report + str(s.built, " compiled, no kernel cache");
    report += str(s.loaded, " from the cache ", cache_.folder().string(), ", ", s.built, " compiled");
    if (s.rejected) report += str(", ", s.rejected, " cache entries rebuilt");
    if (s.unsaved) report += str(", ", s.unsaved, " not saved");
    return report;
}

cl::Kernel ClContext::kernel(std::string_view file, const char* name, const std::string& options) {
    const cl::Program& p = program(file, options);
    return clGuard("creating an OpenCL kernel", [&] { return cl::Kernel(p, name); });
}

void ClContext::enqueue(const cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local) {
    cl::Event event;
    queue_.enqueueNDRangeKernel(kernel, cl::NullRange, global, local, nullptr, recording_ ? &event : nullptr);
    ++launches_;
    Launches& entry = launchesByKernel_[kernel()];
    if (!entry.kernel()) entry.kernel = kernel;
    ++entry.count;
    if (recording_) recorded_.push_back({entry.kernel.getInfo<CL_KERNEL_FUNCTION_NAME>(), {}, event});
}

void ClContext::recordSpan(const std::string& name, const cl::Event& before, const cl::Event& after) {
    if (recording_) recorded_.push_back({name, before, after});
}

std::map<std::string, double> ClContext::takeKernelTimes() {
    std::map<std::string, double> times;
    clGuard("reading the kernels' device times", [&] {
        for (const Recorded& r : recorded_) {
            r.end.wait();
            const cl_ulong end = r.end.getProfilingInfo<CL_PROFILING_COMMAND_END>();
            const cl_ulong start = r.begin() ? r.begin.getProfilingInfo<CL_PROFILING_COMMAND_END>()
                                             : r.end.getProfilingInfo<CL_PROFILING_COMMAND_START>();
            times[r.name] += double(end > start ? end - start : 0) * 1e-6;
        }
    });
    recorded_.clear();
    return times;
}

std::uint64_t ClContext::launches(std::string_view kernelName) const {
    std::uint64_t n = 0;
    for (const auto& [handle, entry] : launchesByKernel_)
        if (entry.kernel.getInfo<CL_KERNEL_FUNCTION_NAME>() == kernelName) n += entry.count;
    return n;
}

std::string edgeOptions(EdgeMode edges) {
    return str("-DHFX_WRAP_U=", wrapsU(edges) ? 1 : 0, " -DHFX_WRAP_V=", wrapsV(edges) ? 1 : 0);
}

} // namespace hfx
