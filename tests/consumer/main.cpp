// The API example of docs/API.md: a wave field stepped on the OpenCL device and drawn with POM
// into the caller's own context and framebuffer. The context is this program's, as an engine's
// would be (OSMesa here, created without HFX); HFX only loads the GL entry points from it.
// Exits 0 when the frame shows the relief.
#include "EngineContext.h"

#include <hfx/compute/ClContext.h>
#include <hfx/core/Gl.h>
#include <hfx/effects/SineWavesEffect.h>
#include <hfx/effects/SurfaceRenderer.h>

#include <cmath>
#include <cstdio>
#include <vector>

int main() try {
    if (!createEngineContext(320, 180)) { // the engine's context, current on this thread
        std::fprintf(stderr, "hfx-consumer: no OSMesa 4.5 core context\n");
        return 1;
    }
    hfx::loadGl(&engineProcAddress);                   // HFX resolves GL through the engine's loader

    hfx::ClContext cl;                                 // PoCL by default; HFX_CL_DEVICE picks another
    hfx::SineWavesEffect waves(cl, {.waves = {.size = 256}});
    hfx::SurfaceRenderer renderer;
    const hfx::Mesh plane(hfx::makePlane({.size = 8.0f, .texcoordScale = 2.0f}));
    hfx::Camera camera = hfx::Camera::orbit({0, 0, 0}, 5.0f, 0.4f, 0.45f);
    camera.aspect = 320.0f / 180.0f;
    for (int frame = 0; frame < 3; ++frame) {
        waves.update(1.0 / 60.0);                      // waves -> Sobel -> upload, on this thread
        glBindFramebuffer(GL_FRAMEBUFFER, 0);          // the caller's framebuffer
        glViewport(0, 0, 320, 180);
        glClearColor(0.5f, 0.6f, 0.7f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        renderer.draw(plane, glm::mat4(1.0f), waves.textures(), waves.material(), camera, {});
    }
    std::vector<unsigned char> rgba(320 * 180 * 4);
    glReadPixels(0, 0, 320, 180, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < rgba.size(); i += 4) {
        sum += rgba[i + 2];
        sum2 += double(rgba[i + 2]) * rgba[i + 2];
    }
    const double n = rgba.size() / 4.0, deviation = std::sqrt(sum2 / n - (sum / n) * (sum / n));
    std::printf("hfx-consumer: blue channel deviation %.1f\n", deviation);
    destroyEngineContext();
    return deviation > 3.0 ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "hfx-consumer: %s\n", e.what());
    return 1;
}
