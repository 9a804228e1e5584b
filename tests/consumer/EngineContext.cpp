// The consumer's own platform layer, as an engine has one: an OSMesa 4.5 core context made
// without HFX. A file of its own because OSMesa's header brings the system GL/gl.h, which must
// not meet the GL loader HFX's headers include.
#include "EngineContext.h"

#include <GL/osmesa.h>

#include <cstddef>
#include <vector>

namespace {
OSMesaContext context = nullptr;
std::vector<unsigned> pixels;
} // namespace

bool createEngineContext(int width, int height) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    context = OSMesaCreateContextAttribs(attribs, nullptr);
    pixels.resize(static_cast<std::size_t>(width) * height);
    return context && OSMesaMakeCurrent(context, pixels.data(), GL_UNSIGNED_BYTE, width, height);
}

void (*engineProcAddress(const char* name))() { return reinterpret_cast<void (*)()>(OSMesaGetProcAddress(name)); }

void destroyEngineContext() {
    if (context) OSMesaDestroyContext(context);
    context = nullptr;
}
