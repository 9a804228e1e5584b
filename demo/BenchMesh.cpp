// hfx-demo bench-mesh: a POM quad against a displaced, tessellated mesh carrying the same 1024²
// height samples (one vertex per sample, two triangles per cell), drawn in the same run at the
// same view: median draw times and the memory each side needs (textures with their mips for
// POM; vertex and index buffers for the mesh, with only what it needs: position and normal).
// With shadows, each side the way it gets them: the quad traces its own shadow rays; the mesh
// has no relief to trace, so it draws itself into a shadow map first (hfx::ShadowMap, 2048²)
// and reads it as the module's receivers do (3x3 taps of 2x2 comparison, bias and normal offset
// of 1.5 map texels).


#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "Devices.h"
#include "hfx/platform/GlContext.h"
#include "hfx/core/GlObject.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/core/ShaderProgram.h"
#include "hfx/effects/OceanEffect.h"
#include "hfx/effects/ShadowMap.h"
#include "hfx/effects/SurfaceUniforms.h"
#include "hfx/tools/Timing.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace hfx::demo {
namespace {

const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_meshViewProj;
out vec3 v_normal;
out vec3 v_world;
void main() {
    v_normal = a_normal;
    v_world = a_position;
    gl_Position = u_meshViewProj * vec4(a_position, 1.0);
}
)";

/// Composed after the module's surface/uniforms.glsl and surface/shadowmap.glsl: the light comes
/// in the surface block (u_lightDir) and the shadow map in the shadows' block (HfxShadows),
/// received by hfx_shadow_map as every surface and flat mesh receives it.
const char* kFragment = R"(#version 450 core
in vec3 v_normal;
in vec3 v_world;
uniform vec3 u_albedo;
out vec4 o_color;
void main() {
    const vec3 n = normalize(v_normal);
    const float diffuse = max(dot(n, u_lightDir), 0.0) * hfx_shadow_map(v_world, n);
    o_color = vec4(pow(u_albedo * (0.25 + diffuse), vec3(1.0 / 2.2)), 1.0);
}
)";
const char* kDepthFragment = R"(#version 450 core
void main() {}
)";

struct MeshVertex {
    glm::vec3 position, normal;
};

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

} // namespace

int runBenchMesh(const DeviceOptions& deviceOptions, int width, int height, int frames) {
    const Devices devices = openDevices(deviceOptions, {.width = width, .height = height}, false);
    ClContext& cl = *devices.cl;
    constexpr int N = 1024;
    constexpr float kSize = 8.0f;
    // One ocean per surface format, all from the same seed: the same heights, stored three ways.
    std::vector<std::unique_ptr<OceanEffect>> oceans;
    for (SurfaceFormat format : kSurfaceFormats)
        oceans.push_back(std::make_unique<OceanEffect>(cl, OceanEffectConfig{.ocean = {.size = N, .cascades = 1}, .surface = {.format = format}}));
    const SurfaceTextures& textures = oceans.front()->textures();
    const float depthScale = oceans.front()->material().depthScale;

    // The same samples as vertices: texel (i, j) at its centre, pushed down by (1 - h) depth units
    // (the plane's texture unit is kSize world units), normal turned from tangent to world space.
    std::vector<float> texels(size_t(N) * N * 4);
    glGetTextureImage(textures.surface(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
    std::vector<MeshVertex> vertices(size_t(N) * N);
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            const float* t = &texels[(size_t(j) * N + i) * 4];
            const float u = (i + 0.5f) / N, v = (j + 0.5f) / N;
            vertices[size_t(j) * N + i] = {{(u - 0.5f) * kSize, -(1.0f - t[3]) * depthScale * kSize, (0.5f - v) * kSize},
                                           {t[0], t[2], -t[1]}};
        }
    std::vector<uint32_t> indices;
    indices.reserve(size_t(N - 1) * (N - 1) * 6);
    for (int j = 0; j + 1 < N; ++j)
        for (int i = 0; i + 1 < N; ++i) {
            const uint32_t a = j * N + i, b = a + 1, c = a + N, d = c + 1;
            indices.insert(indices.end(), {a, b, d, a, d, c});
        }
    GlBuffer vbo = GlBuffer::create(), ibo = GlBuffer::create();
    GlVertexArray vao = GlVertexArray::create();
    glNamedBufferStorage(vbo.id(), GLsizeiptr(vertices.size() * sizeof(MeshVertex)), vertices.data(), 0);
    glNamedBufferStorage(ibo.id(), GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), 0);
    glVertexArrayVertexBuffer(vao.id(), 0, vbo.id(), 0, sizeof(MeshVertex));
    glVertexArrayElementBuffer(vao.id(), ibo.id());
    for (GLuint a = 0; a < 2; ++a) {
        glEnableVertexArrayAttrib(vao.id(), a);
        glVertexArrayAttribFormat(vao.id(), a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
        glVertexArrayAttribBinding(vao.id(), a, 0);
    }
    // The mesh's programs, unshadowed and receiving the map (HFX_SHADOW_MAP, as the renderer's variants).
    ShaderProgram meshPrograms[2];
    for (int shadowed = 0; shadowed < 2; ++shadowed)
        meshPrograms[shadowed] = ShaderProgram({{"bench-mesh.vert", kVertex, "embedded"}},
                                               {surfaceShader("bindings.glsl"), surfaceShader("surface/uniforms.glsl"), surfaceShader("surface/shadowmap.glsl"),
                                                {"bench-mesh.frag", kFragment, "embedded"}},
                                               {{"HFX_SHADOW_MAP", shadowed ? "1" : "0"}});
    ShaderProgram depthProgram({"bench-mesh.vert", kVertex, "embedded"}, {"bench-mesh-depth.frag", kDepthFragment, "embedded"});

    const Mesh quad(makePlane({.size = kSize}));
    Camera camera = Camera::orbit({0, 0, 0}, 7.0f, 0.5f, 0.52f); // 60 degrees from the normal
    camera.aspect = float(width) / float(height);
    DirectionalLight light;
    light.direction = {-0.35f, 0.5f, -0.8f};
    ShadowMap map;
    // The sphere that holds the mesh: the plane and its depth below it.
    map.fit(glm::normalize(light.direction), {0.0f, -0.5f * depthScale * kSize, 0.0f},
            std::sqrt(0.5f * kSize * kSize + 0.25f * depthScale * depthScale * kSize * kSize));
    SurfaceRenderer renderer;
    SurfaceMaterial pom = oceans.front()->material();
    SurfaceMaterial unshadowed = pom;
    unshadowed.shadows = false;
    RenderTarget target(width, height);
    target.bind();
    // Per format: POM with and without shadows; then the mesh. Interleaved frame by frame, so a
    // noisy neighbour hits every side alike.
    std::vector<std::vector<GlTime>> pomMs(oceans.size()), plainMs(oceans.size());
    std::vector<GlTime> meshMs, meshShadowedMs;
    GpuTimer timer;
    // The mesh's surface and shadow blocks, made once: the light and the receiver's lookup as
    // the renderer's own draws get them.
    const GlBuffer meshBlock = GlBuffer::create(), shadowBlock = GlBuffer::create();
    const SurfaceUniforms u{.lightDir = glm::normalize(light.direction)};
    glNamedBufferStorage(meshBlock.id(), sizeof u, &u, 0);
    bool arrayTexture = false;
    const ShadowUniforms shadows = shadowUniforms(map.receiver(), arrayTexture);
    glNamedBufferStorage(shadowBlock.id(), sizeof shadows, &shadows, 0);
    const auto drawMesh = [&](bool shadowed) {
        glEnable(GL_DEPTH_TEST);
        glBindVertexArray(vao.id());
        if (shadowed) {
            map.begin();
            depthProgram.set("u_meshViewProj", map.viewProj());
            depthProgram.use();
            glDrawElements(GL_TRIANGLES, GLsizei(indices.size()), GL_UNSIGNED_INT, nullptr);
            map.end();
            glBindTextureUnit(HFX_UNIT_SHADOW_MAP, map.texture());
        }
        target.clear();
        glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SURFACE, meshBlock.id());
        glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SHADOWS, shadowBlock.id());
        const ShaderProgram& meshProgram = meshPrograms[shadowed ? 1 : 0];
        meshProgram.set("u_meshViewProj", camera.viewProjection());
        meshProgram.set("u_albedo", glm::vec3(0.05f, 0.22f, 0.30f));
        meshProgram.use();
        glDrawElements(GL_TRIANGLES, GLsizei(indices.size()), GL_UNSIGNED_INT, nullptr);
        glBindVertexArray(0);
        glBindTextureUnit(HFX_UNIT_SHADOW_MAP, 0);
    };
    for (int frame = -kWarmupFrames; frame < frames; ++frame) {
        for (size_t f = 0; f < oceans.size(); ++f) {
            const GlTime p = timeGl(timer, "pom", [&] {
                target.clear();
                renderer.draw(quad, glm::mat4(1.0f), oceans[f]->textures(), pom, camera, light);
            });
            const GlTime q = timeGl(timer, "pom", [&] {
                target.clear();
                renderer.draw(quad, glm::mat4(1.0f), oceans[f]->textures(), unshadowed, camera, light);
            });
            if (frame >= 0) {
                pomMs[f].push_back(p);
                plainMs[f].push_back(q);
            }
        }
        const GlTime m = timeGl(timer, "mesh", [&] { drawMesh(false); });
        const GlTime ms = timeGl(timer, "mesh", [&] { drawMesh(true); });
        if (frame >= 0) {
            meshMs.push_back(m);
            meshShadowedMs.push_back(ms);
        }
    }
    // Memory each side needs on the GPU: the surface texture and the albedo (RGBA8) with their
    // mip chains and the quad for POM; positions, normals and indices for the mesh.
    const double mipFactor = 4.0 / 3.0;
    auto pomBytes = [&](SurfaceFormat f) {
        return double(N) * N * double(texelBytes(f) + 4) * mipFactor + 4 * sizeof(Vertex) + 6 * sizeof(uint32_t);
    };
    const double meshBytes = double(vertices.size()) * sizeof(MeshVertex) + double(indices.size()) * sizeof(uint32_t);
    const GlTime mt = median(meshMs), mst = median(meshShadowedMs);
    std::printf("hfx-demo bench-mesh: %dx%d, medians of %d frames after %d warm-up frames, interleaved\n%s\n\n"
                "GPU time (timer queries) of each draw, the CPU wall clock around glFinish in brackets:\n\n",
                width, height, frames, kWarmupFrames, devices.summary().c_str());
    std::printf("| side | GPU ms: soft shadows / none (wall) | memory MiB | mesh / side, GPU: shadows / none (wall) | "
                "mesh / side: memory |\n|---|---|---|---|---|\n");
    for (size_t f = 0; f < oceans.size(); ++f) {
        const SurfaceFormat format = kSurfaceFormats[f];
        const GlTime pt = median(pomMs[f]), qt = median(plainMs[f]);
        std::printf("| POM quad, %s surface | %.2f / %.2f (%.1f / %.1f) | %.1f | %.2fx / %.2fx (%.2fx / %.2fx) | %.2fx |\n",
                    surfaceFormatName(format), pt.gpu, qt.gpu, pt.wall, qt.wall, mib(pomBytes(format)), mst.gpu / pt.gpu,
                    mt.gpu / qt.gpu, mst.wall / pt.wall, mt.wall / qt.wall, meshBytes / pomBytes(format));
    }
    std::printf("| mesh, %zu triangles (shadow map %d² + draw / draw alone) | %.2f / %.2f (%.1f / %.1f) | %.1f | | |\n",
                indices.size() / 3, map.size(), mst.gpu, mt.gpu, mst.wall, mt.wall, mib(meshBytes));
    return 0;
}

} // namespace hfx::demo
