#include "hfx/core/GlRenderer.h"

#include "hfx/core/Gl.h"

#include <algorithm>
#include <cctype>

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

} // namespace hfx
