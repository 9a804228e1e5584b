// The decal-damage user: a brick wall (or the user's maps) seen at a grazing angle, shot at by
// clicks (picked on the displaced surface), a key's explosions, or a replayed shot list. A flat
// shelf stands half sunk into the wall, so the depth output's clipping by the damage shows, and
// a shadow map of the traced relief lets the shelf and the bricks shadow each other. With
// --pillar the bricks and their damage cover a column instead (a cylinder, picked by pickMesh).

#include "Scene.h"

#include "hfx/tools/ImageFiles.h"

#include "hfx/core/Error.h"
#include "hfx/core/Random.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/ShadowMap.h"
#include "hfx/tools/ShotList.h"

#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>

#include <cmath>
#include <cstdio>

namespace hfx::demo {
namespace {

/// The wall: the map once across its 4 units, so that a shot's damage shows once (the map tiles:
/// texcoords running 0..2 showed each crater four times).
constexpr PlaneConfig kWall{.size = 4.0f, .texcoordScale = 1.0f, .subdivisions = 1};
/// --pillar's column: the map once around (its 3.8 units) and 0.8 of it up its 3.2 units, its
/// bricks the wall's.
const CylinderConfig kPillar{.radius = 0.6f, .height = 3.2f, .segments = 96, .texcoordScale = {1.0f, 0.8f}};

/// The column's capstones: a disc on its top facing up and one under it facing down, so a camera
/// above or below it sees a closed column rather than into an open tube (makeCylinder has no caps).
MeshData pillarCaps(const CylinderConfig& c) {
    MeshData caps;
    for (const float side : {1.0f, -1.0f}) {
        const glm::vec3 normal{0.0f, side, 0.0f};
        const auto centre = uint32_t(caps.vertices.size());
        const float y = 0.5f * c.height * side;
        caps.vertices.push_back({{0.0f, y, 0.0f}, normal, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -side}, {0.5f, 0.5f}});
        for (int i = 0; i < c.segments; ++i) {
            const float a = 6.2831853f * float(i) / float(c.segments);
            const glm::vec2 p{c.radius * std::cos(a), c.radius * std::sin(a)};
            caps.vertices.push_back({{p.x, y, p.y}, normal, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -side},
                                     {0.5f + 0.5f * std::cos(a), 0.5f + 0.5f * std::sin(a)}});
        }
        for (int i = 0; i < c.segments; ++i) {
            const uint32_t a = centre + 1 + uint32_t(i), b = centre + 1 + uint32_t((i + 1) % c.segments);
            // Counter-clockwise seen from the normal's side: (x, z) turns clockwise seen from +y.
            if (side > 0.0f) caps.indices.insert(caps.indices.end(), {centre, b, a});
            else caps.indices.insert(caps.indices.end(), {centre, a, b});
        }
    }
    return caps;
}

class DecalScene final : public Scene {
public:
    DecalScene(ClContext& cl, const SceneOptions& o)
        : wall_(cl, config(o)), pillar_(o.pillar), shape_(o.pillar ? makeCylinder(kPillar) : makePlane(kWall)),
          mesh_(shape_),
          post_(o.pillar ? pillarCaps(kPillar) : makePlane({.size = 0.5f, .texcoordScale = 1.0f, .subdivisions = 1})),
          random_(o.seed),
          width_(o.width), height_(o.height), saveDamage_(o.saveDamage) {
        applyOptions(o);
        if (!o.shots.empty()) {
            shots_ = readShotList(o.shots);
            replaying_ = true;
        }
        if (!o.loadDamage.empty()) {
            wall_.loadDamage(o.loadDamage);
            autoFire = false;
            std::printf("loaded %d impacts from %s\n", wall_.damage().size(), o.loadDamage.c_str());
        }
        // The wall stands in the XY plane facing +Z; the camera looks along it from the side. The
        // pillar stands up the Y axis, seen from a little above its middle.
        camera_ = pillar_ ? Camera::orbit({0.0f, 0.0f, 0.0f}, 3.4f, 0.6f, 0.2f)
                          : Camera::orbit({0.0f, 0.0f, 0.0f}, 3.4f, 1.15f, 0.15f);
        camera_.aspect = o.aspect();
        light_.direction = {-0.8f, 0.55f, 0.45f};
        light_.ambient = {0.22f, 0.22f, 0.25f};
    }

    void prepare(double /*dt*/) override {
        // Shots for the frame this update makes: the list's, or a seeded volley when none was
        // given. Frame 0 is the wall before any update, so shots listed at 0 land with frame 1.
        ++frame_;
        if (replaying_) {
            for (const Shot& shot : shots_)
                if (shot.frame == frame_ || (frame_ == 1 && shot.frame == 0)) apply(shot);
        } else if (autoFire) {
            volley();
        }
    }
    void draw() override {
        // A shelf half sunk into the wall: clipped where the relief is, by the traced depth. The
        // column's capstones instead.
        const glm::mat4 post = pillar_ ? glm::mat4(1.0f) : glm::translate(glm::mat4(1.0f), {0.9f, -0.6f, 0.0f});
        const glm::vec4 postColor = pillar_ ? glm::vec4(0.62f, 0.6f, 0.56f, 1.0f) : glm::vec4(0.75f, 0.72f, 0.2f, 1.0f);
        // The light's shadow map: the wall casts its traced relief and the shelf itself, so the
        // shelf's shadow falls into the mortar and the holes, and the bricks shade the shelf.
        shadowMap_.fit(light_.direction, {0.0f, 0.0f, 0.0f}, 2.9f);
        {
            const auto casting = shadowMap_.scope();
            renderer_.drawShadow(mesh(), model(), effect().layers(), effect().material(), shadowMap_, drawOptions());
            renderer_.drawFlatShadow(post_, post, shadowMap_);
        }
        DirectionalLight light = light_;
        light.shadowMap = &shadowMap_;
        drawSurface(renderer_, light);
        renderer_.drawFlat(post_, post, camera_, postColor, &light);
    }
    Effect& effect() override { return wall_; }
    const char* name() const override { return "decals"; }
    const Mesh& mesh() const override { return mesh_; }
    glm::mat4 model() const override {
        return pillar_ ? glm::mat4(1.0f) : glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    }

    void click(double x, double y, int width, int height) override {
        if (const auto hit = pick(x, y, width, height)) {
            wall_.shoot(hit->uv.x, hit->uv.y);
            record({.kind = Shot::Kind::Bullet, .frame = frame_ + 1, .a = hit->uv.x, .b = hit->uv.y});
        }
    }
    void explode(double x, double y, int width, int height) override {
        if (const auto hit = pick(x, y, width, height)) {
            const std::uint64_t seed = random_.nextBits() & 0xffffffu;
            wall_.explode(hit->uv.x, hit->uv.y, seed);
            record({.kind = Shot::Kind::Explosion, .frame = frame_ + 1, .a = hit->uv.x, .b = hit->uv.y, .seed = seed});
        }
    }
    void clear() override { wall_.clearDamage(); }
    void finish() override {
        if (saveDamage_.empty()) return;
        wall_.saveDamage(saveDamage_);
        std::printf("saved %d impacts to %s\n", wall_.damage().size(), saveDamage_.c_str());
    }
    void panel() override {
        ImGui::Checkbox("automatic volley", &autoFire);
        ImGui::Text("click: bullet hole, E: explosion, C: clear damage");
        const DamageLog& damage = wall_.damage();
        ImGui::Text("impacts %d of %d (%llu merged, %llu evicted)", damage.size(), damage.budget(),
                    (unsigned long long)damage.merged(), (unsigned long long)damage.evicted());
        if (ImGui::Button("clear damage")) wall_.clearDamage();
    }

    bool autoFire = true;

private:
    static DecalWallConfig config(const SceneOptions& o) {
        DecalWallConfig c;
        if (!o.heightMap.empty())
            c.maps = readSurfaceMaps(o.heightMap, o.normalMap, o.colorMap);
        else if (!o.normalMap.empty() || !o.colorMap.empty())
            throw Error(str("decals: a colour or normal map ('", o.colorMap.empty() ? o.normalMap : o.colorMap,
                            "') needs a --height-map to go with it"));
        if (o.fieldSize > 0) c.bricks.size = o.fieldSize;
        c.bricks.seed = o.seed;
        // The map spans the whole wall: twice the courses and bricks a course (where the map has
        // the texels for them: a small one keeps larger bricks), the stone grain twice as fine,
        // the impacts half as wide and the relief half as deep in its texture units (a texcoord
        // is 4 world units), so that bricks, holes and depth keep their size.
        BrickWallConfig twice = c.bricks;
        twice.rows *= 2;
        twice.bricksPerRow *= 2;
        if (twice.rows <= twice.size / 8 && twice.size % twice.rows == 0 && twice.size % (2 * twice.bricksPerRow) == 0)
            c.bricks = twice;
        c.grainNoise.frequency *= 2.0f;
        c.damage.look.bullet.radius *= 0.5f;
        c.damage.look.explosion.radius *= 0.5f;
        c.damage.mergeRadius *= 0.5f;
        c.material.depthScale *= 0.5f;
        c.surface = o.surfaceOptions();
        // The column's relief fades out where the view grazes its sides (no bricks smeared along
        // its outline).
        if (o.pillar) c.material.silhouetteFade = 0.2f;
        return c;
    }

    /// What pixel (x, y) (from the top) shows of the wall, at the draw's level of detail.
    std::optional<SurfacePick> pick(double x, double y, int width, int height) {
        const Ray ray = camera_.rayThroughPixel(x, height - y, width, height);
        return wall_.pick(ray, shape_, model(), wall_.material(),
                          PixelNeighbours::of(camera_, x, height - y, width, height));
    }

    void apply(const Shot& shot) {
        switch (shot.kind) {
        case Shot::Kind::Bullet: wall_.shoot(shot.a, shot.b); break;
        case Shot::Kind::Explosion: wall_.explode(shot.a, shot.b, shot.seed); break;
        case Shot::Kind::Click:
            if (shot.a < 0 || shot.b < 0 || shot.a >= width_ || shot.b >= height_)
                throw Error(str("shot list line ", shot.line, ": click at (", shot.a, ", ", shot.b,
                                ") is outside the ", width_, "x", height_, " image"));
            if (const auto hit = pick(shot.a, shot.b, width_, height_)) wall_.shoot(hit->uv.x, hit->uv.y);
            break;
        }
    }

    /// A seeded burst: a few bullets every frame and an explosion every twelfth.
    void volley() {
        for (int i = 0; i < 4; ++i) wall_.shoot(random_.uniform(0.05, 0.95), random_.uniform(0.05, 0.95));
        if (frame_ % 12 == 1) wall_.explode(random_.uniform(0.1, 0.9), random_.uniform(0.1, 0.9), random_.nextBits() & 0xffff);
    }

    void record(const Shot& shot) { std::printf("shot: %s\n", formatShot(shot).c_str()); }

    DecalWallEffect wall_;
    bool pillar_;
    MeshData shape_; ///< the wall's plane, or --pillar's column: drawn, and picked by its triangles
    Mesh mesh_, post_; ///< post_: the wall's shelf, or the column's capstones
    DirectionalLight light_;
    SurfaceRenderer renderer_;
    ShadowMap shadowMap_{1024};
    SplitMix64 random_;
    std::vector<Shot> shots_;
    bool replaying_ = false;
    int frame_ = 0;
    int width_, height_;
    std::string saveDamage_;
};

} // namespace

std::unique_ptr<Scene> makeDecalScene(ClContext& cl, const SceneOptions& options) {
    return std::make_unique<DecalScene>(cl, options);
}

} // namespace hfx::demo
