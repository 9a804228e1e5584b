#include "hfx/compute/ClDeviceChoice.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace hfx {
namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

bool contains(std::string_view text, std::string_view filter) {
    return filter.empty() || lower(text).find(lower(filter)) != std::string::npos;
}

/// The hardware maker a vendor string names ("NVIDIA Corporation", "Advanced Micro Devices,
/// Inc.", "ATI Technologies Inc.", "Intel(R) Corporation"), or "" when none is known.
std::string maker(std::string_view vendor) {
    const std::string v = lower(vendor);
    constexpr std::array<std::pair<const char*, const char*>, 9> kMakers = {{{"nvidia", "nvidia"},
                                                                             {"advanced micro devices", "amd"},
                                                                             {"amd", "amd"},
                                                                             {"ati technologies", "amd"},
                                                                             {"intel", "intel"},
                                                                             {"apple", "apple"},
                                                                             {"arm", "arm"},
                                                                             {"qualcomm", "qualcomm"},
                                                                             {"imagination", "imagination"}}};
    for (const auto& [word, key] : kMakers)
        if (v.find(word) != std::string::npos) return key;
    return {};
}

/// 0 for a GPU, 1 an accelerator, 2 anything else, 3 a CPU: smaller is preferred.
int kindRank(cl_device_type type) {
    if (type & CL_DEVICE_TYPE_GPU) return 0;
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return 1;
    if (type & CL_DEVICE_TYPE_CPU) return 3;
    return 2;
}

/// The device runs on the hardware that runs the GL renderer.
bool besideRenderer(const ClDeviceInfo& d, const GlRendererInfo& gl) {
    if (gl.empty()) return false;
    if (gl.software()) return (d.type & CL_DEVICE_TYPE_CPU) != 0;
    const std::string glMaker = maker(gl.vendor + " " + gl.renderer);
    return !glMaker.empty() && glMaker == maker(d.vendor + " " + d.platform) && !(d.type & CL_DEVICE_TYPE_CPU);
}

} // namespace

const char* clDeviceTypeName(cl_device_type type) {
    if (type & CL_DEVICE_TYPE_GPU) return "GPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
    if (type & CL_DEVICE_TYPE_CPU) return "CPU";
    return "custom device";
}

std::string ClDeviceInfo::label() const { return str("'", name, "' (", clDeviceTypeName(type), ") on '", platform, "'"); }

ClDeviceChoice chooseClDevice(const std::vector<ClDeviceInfo>& devices, std::string_view platformFilter,
                              std::string_view deviceFilter, const GlRendererInfo& gl) {
    // Smaller keys are preferred; the index keeps the listing's order among equals.
    auto key = [&](int i) {
        const ClDeviceInfo& d = devices[size_t(i)];
        return std::array<int, 4>{kindRank(d.type), d.sharesGl ? 0 : 1, besideRenderer(d, gl) ? 0 : 1, i};
    };
    ClDeviceChoice choice;
    for (int i = 0; i < int(devices.size()); ++i) {
        const ClDeviceInfo& d = devices[size_t(i)];
        if (!contains(d.platform, platformFilter) || !contains(d.label(), deviceFilter)) continue;
        if (choice.index < 0 || key(i) < key(choice.index)) choice.index = i;
    }
    if (choice.index < 0) return choice;
    const ClDeviceInfo& d = devices[size_t(choice.index)];
    choice.reason = str("a ", clDeviceTypeName(d.type));
    if (d.sharesGl) choice.reason += ", shares objects with the GL context";
    else if (besideRenderer(d, gl)) choice.reason += ", on the GL renderer's hardware";
    if (!platformFilter.empty() || !deviceFilter.empty())
        choice.reason += str(" (filters: platform '", platformFilter, "', device '", deviceFilter, "')");
    return choice;
}

} // namespace hfx
