// The noise user: any NoiseField configuration as a lit, animated POM surface on a plane that
// repeats it twice each way (so a tiling noise shows its seams, or that it has none), for an
// artist to tune in the panel and export with --export-maps. With --triplanar, the relief covers a
// rounded box instead, its texcoords projected along the box's axes (SurfaceMaterial::triplanar):
// a mesh with no texcoords fit for it, as a rock or a prop.

#include "Scene.h"

#include "hfx/core/Error.h"
#include "hfx/effects/NoiseSurfaceEffect.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace hfx::demo {
namespace {

/// The plane the surface repeats on, twice each way.
constexpr PlaneConfig kPlane{.size = 4.0f, .texcoordScale = 2.0f, .subdivisions = 1};

/// A box with rounded edges, 2.4 across: a 1.6 box grown by 0.4 every way (its faces flat, its
/// edges quarter cylinders, its corners eighths of a sphere), each vertex where the grown box's
/// normal is a sphere grid's direction. Each quarter turn of longitude and each hemisphere has
/// its own corner, so a grid line where they meet is there twice, once on either side, and the
/// quads between the copies are the flat faces and the edges; two triangles cap the top and the
/// bottom. So it is convex (Mesh::convex) and closed, which the mapping's walks in a compute pass
/// ask for. Its texcoords and tangents are the sphere's (a triplanar mapping reads neither).
MeshData roundedBox() {
    constexpr double half = 0.8, radius = 0.4, pi = 3.14159265358979323846;
    constexpr int quarter = 24, hemisphere = 16; // a corner's grid: its steps in longitude, in latitude
    constexpr int columns = 4 * (quarter + 1), rows = 2 * (hemisphere + 1);
    MeshData mesh;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const int q = i / (quarter + 1), h = j / (hemisphere + 1);
            const double lon = 0.5 * pi * (q + double(i % (quarter + 1)) / quarter);
            const double lat = 0.5 * pi * (h - 1 + double(j % (hemisphere + 1)) / hemisphere);
            const double cl = std::cos(lat), sl = std::sin(lat), co = std::cos(lon), so = std::sin(lon);
            const glm::dvec3 d(cl * co, sl, -cl * so);
            // The quarter's corner: x's sign is cos(lon)'s over the quarter, z's -sin(lon)'s.
            const glm::dvec3 corner(q == 0 || q == 3 ? half : -half, h == 1 ? half : -half, q < 2 ? -half : half);
            Vertex v;
            v.position = glm::vec3(corner + radius * d);
            v.normal = glm::vec3(d);
            v.tangent = glm::vec3(glm::dvec3(-cl * so, 0.0, -cl * co) * (2.0 * pi));
            v.bitangent = glm::vec3(glm::dvec3(-sl * co, cl, sl * so) * pi);
            v.texcoord = {float(double(i) / (columns - 1)), float(double(j) / (rows - 1))};
            mesh.vertices.push_back(v);
        }
    // Counter-clockwise seen from outside, as makeSphere's (longitude grows along a row, latitude
    // up the rows); the last column meets the first.
    for (int j = 0; j + 1 < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const uint32_t a = uint32_t(j * columns + i), b = uint32_t(j * columns + (i + 1) % columns);
            const uint32_t c = a + columns, d = b + columns;
            mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
        }
    // The caps: each pole's row holds the four corners of a flat face, a quarter's first column.
    for (const int j : {0, rows - 1}) {
        const auto corner = [&](int q) { return uint32_t(j * columns + q * (quarter + 1)); };
        if (j == 0)
            mesh.indices.insert(mesh.indices.end(), {corner(0), corner(2), corner(1), corner(0), corner(3), corner(2)});
        else
            mesh.indices.insert(mesh.indices.end(), {corner(0), corner(1), corner(2), corner(0), corner(2), corner(3)});
    }
    mesh.convex = true;
    mesh.closed = true;
    return mesh;
}

class NoiseScene final : public Scene {
public:
    NoiseScene(ClContext& cl, const SceneOptions& o)
        : surface_(cl, config(o)), mesh_(o.triplanar > 0.0f ? roundedBox() : makePlane(kPlane)), triplanar_(o.triplanar > 0.0f) {
        if (triplanar_) {
            SurfaceMaterial m = surface_.material();
            m.triplanar = {.scale = o.triplanar};
            m.silhouetteFade = 0.3f; // the box's rim keeps its outline
            surface_.setMaterial(m);
        }
        applyOptions(o);
        camera_ = Camera::orbit({0.0f, 0.0f, 0.0f}, 4.0f, 0.6f, 0.6f);
        camera_.aspect = o.aspect();
        // Grazing across the plane; over the box's shoulder, so that two of its sides are lit.
        light_.direction = triplanar_ ? glm::vec3(0.8f, 0.55f, 0.25f) : glm::vec3(-0.9f, 0.5f, -0.35f);
    }

    void draw() override { drawSurface(renderer_, light_); }
    Effect& effect() override { return surface_; }
    const char* name() const override { return "noise"; }
    const Mesh& mesh() const override { return mesh_; }

    void panel() override {
        NoiseConfig n = surface_.noise().config();
        static constexpr const char* kKinds[] = {"perlin", "simplex", "psrd"};
        static constexpr const char* kFractals[] = {"fbm", "ridged", "turbulence"};
        static constexpr const char* kTilings[] = {"tiles (wrap)", "tiles in u", "does not tile"};
        int kind = int(n.kind), fractal = int(n.fractal);
        int tiling = n.edges == EdgeMode::Wrap ? 0 : n.edges == EdgeMode::WrapU ? 1 : 2;
        bool changed = ImGui::Combo("kind", &kind, kKinds, IM_ARRAYSIZE(kKinds));
        changed |= ImGui::Combo("fractal", &fractal, kFractals, IM_ARRAYSIZE(kFractals));
        changed |= ImGui::Combo("tiling", &tiling, kTilings, IM_ARRAYSIZE(kTilings));
        changed |= ImGui::SliderInt("octaves", &n.octaves, 1, 10);
        changed |= ImGui::SliderFloat("frequency (cells)", &n.frequency, 1.0f, 32.0f, "%.0f");
        changed |= ImGui::SliderFloat("gain", &n.gain, 0.1f, 0.9f);
        changed |= ImGui::SliderFloat("warp (cells)", &n.warp, 0.0f, 2.0f);
        changed |= ImGui::SliderFloat("speed", &n.speed, 0.0f, 2.0f);
        if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
        if (!changed) return;
        n.kind = NoiseKind(kind);
        n.fractal = Fractal(fractal);
        n.edges = tiling == 0 ? EdgeMode::Wrap : tiling == 1 ? EdgeMode::WrapU : EdgeMode::Clamp;
        n.frequency = std::round(n.frequency); // a tiling noise needs whole cells
        if (triplanar_ && n.edges != EdgeMode::Wrap) {
            message_ = "the box's triplanar mapping tiles the noise: it must wrap both ways";
            return; // the surface stays as it was
        }
        try {
            surface_.setNoise(n);
            message_.clear();
        } catch (const Error& e) {
            message_ = e.what(); // simplex does not tile, say: the surface stays as it was
        }
    }

private:
    static NoiseSurfaceConfig config(const SceneOptions& o) {
        NoiseSurfaceConfig c;
        NoiseConfig& n = c.noise;
        if (o.fieldSize > 0) n.width = n.height = o.fieldSize;
        n.kind = parseNoiseKind(o.noiseKind);
        n.fractal = parseFractal(o.fractal);
        n.octaves = o.octaves;
        n.frequency = o.frequency;
        n.lacunarity = o.lacunarity;
        n.gain = o.gain;
        n.warp = o.warp;
        n.speed = o.noiseSpeed;
        n.edges = o.tiling == "wrap" ? EdgeMode::Wrap : o.tiling == "wrap-u" ? EdgeMode::WrapU : EdgeMode::Clamp;
        n.seed = float(o.seed % 1000u);
        c.surface = o.surfaceOptions();
        return c;
    }

    NoiseSurfaceEffect surface_;
    Mesh mesh_; ///< the plane, or the rounded box of --triplanar
    bool triplanar_;
    DirectionalLight light_;
    SurfaceRenderer renderer_;
    std::string message_;
};

} // namespace

std::unique_ptr<Scene> makeNoiseScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<NoiseScene>(cl, options);
}

} // namespace hfx::demo
