#include "hfx/core/GlRenderer.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

namespace hfx {

bool GlRendererInfo::software() const {
    std::string r = renderer;
    std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (const char* word : {"llvmpipe", "softpipe", "swrast", "swiftshader", "microsoft basic render"})
        if (r.find(word) != std::string::npos) return true;
    return false;
}

GlRendererInfo currentGlRenderer() {
    auto text = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "");
    };
    return {text(GL_VENDOR), text(GL_RENDERER)};
}

GlWorkarounds glWorkarounds(const GlRendererInfo& renderer) {
    const bool software = renderer.software();
    GlWorkarounds w{.cpuClockTimer = software,
                    .float32Surfaces = software,
                    .pyramidAtlas = software,
                    .pyramidFromCompute = software,
                    .traceInDraw = software};
    const char* env = std::getenv("HFX_GL_WORKAROUNDS");
    if (!env || !*env) return w;
    std::stringstream list(env);
    std::string entry;
    while (std::getline(list, entry, ',')) {
        const size_t eq = entry.find('=');
        const std::string name = entry.substr(0, eq), value = eq == std::string::npos ? "" : entry.substr(eq + 1);
        bool* flag = name == "cpu-clock-timer"        ? &w.cpuClockTimer
                     : name == "float32-surfaces"     ? &w.float32Surfaces
                     : name == "pyramid-atlas"        ? &w.pyramidAtlas
                     : name == "pyramid-from-compute" ? &w.pyramidFromCompute
                     : name == "trace-in-draw"        ? &w.traceInDraw
                                                      : nullptr;
        if (!flag || (value != "0" && value != "1"))
            throw Error(str("HFX_GL_WORKAROUNDS: '", entry, "' is not name=0 or name=1 with a name of "
                            "cpu-clock-timer, float32-surfaces, pyramid-atlas, pyramid-from-compute, trace-in-draw "
                            "(in '", env, "')"));
        *flag = value == "1";
    }
    return w;
}

} // namespace hfx
