#pragma once
// Draws a mesh with a height-field surface: parallax occlusion mapping (shaders/surface.frag) or
// plain normal mapping. It draws into whatever framebuffer and context the caller has bound and
// restores the GL state it changes (program, vertex array, depth test, texture units 0-3).
//
// Thread: the thread whose GL context is current; shader programs are built per variant on
// first use and kept.

#include "hfx/core/Camera.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/ShaderProgram.h"
#include "hfx/core/SurfaceTextures.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <map>
#include <tuple>
#include <string>

namespace hfx {

/// The surface techniques, one shader variant each, same inputs and outputs. The numbers are
/// the shader's HFX_TECHNIQUE.
enum class Technique {
    NormalMapping = 0,     ///< "nm": no parallax
    ParallaxOcclusion = 1, ///< "pom": linear search + piecewise-linear hit, soft shadows (Tatarchuk 2006)
    ParallaxOffset = 2,    ///< "parallax": one offset with offset limiting (Welsh 2004)
    SteepParallax = 3,     ///< "steep": linear search, first sample under, hard shadows (McGuire 2005)
    Relief = 4,            ///< "relief": linear then 6 binary steps, hard shadows (Policarpo 2005)
    Secant = 5,            ///< "secant": linear search refined by 3 secant steps, soft shadows
    Hierarchical = 6,      ///< "hier": max-height pyramid walk to the exact bilinear hit, soft shadows
};
inline constexpr Technique kTechniques[] = {Technique::NormalMapping, Technique::ParallaxOffset,
                                            Technique::SteepParallax, Technique::Relief,
                                            Technique::Secant,        Technique::ParallaxOcclusion,
                                            Technique::Hierarchical};
/// "nm", "pom", "parallax", "steep", "relief", "secant", "hier"; throws hfx::Error naming the
/// value and the known names otherwise.
Technique parseTechnique(const std::string& name);
const char* techniqueName(Technique technique);
/// "nm, parallax, steep, relief, secant, pom, hier" (for help texts).
std::string techniqueNames();

/// How the surface is lit once the relief is traced.
enum class Shading {
    Lit,    ///< Blinn-Phong of albedo and normal
    Water,  ///< Fresnel-weighted sky reflection, sun glint, body colour by depth, distance haze
    Planet, ///< Blinn-Phong with a soft terminator of the sphere and an atmosphere rim
};

/// The water look (Shading::Water). Colours are linear RGB.
struct WaterLook {
    glm::vec3 deepColor{0.004f, 0.035f, 0.07f};    ///< troughs: light travels far in the water
    glm::vec3 shallowColor{0.02f, 0.16f, 0.17f};   ///< crests: thin water scatters the sun
    glm::vec3 skyZenith{0.12f, 0.3f, 0.65f};       ///< procedural sky, used without environment
    glm::vec3 skyHorizon{0.62f, 0.72f, 0.82f};
    float fresnelF0 = 0.02f;                       ///< reflectance of water seen head-on
    float glintPower = 900.0f;                     ///< sharpness of the sun's reflection
    float glintStrength = 40.0f;
    float hazeDistance = 90.0f;                    ///< world units where half the colour is haze
    /// Optional equirectangular sky (a GL texture the caller owns; 0 = procedural sky).
    unsigned environment = 0;
    bool operator==(const WaterLook&) const = default;
};

struct SurfaceMaterial {
    float depthScale = 0.05f;    ///< texture units between h = 1 and h = 0
    int minSamples = 8;          ///< linear-search steps seen head-on
    int maxSamples = 50;         ///< ... at grazing angles
    float lodThreshold = 4.0f;   ///< mip level where POM has faded to normal mapping
    bool shadows = true;
    int shadowSamples = 8;
    float shadowSharpness = 2.0f;
    bool clipToPatch = false;    ///< discard rays that leave patchBounds (finite patches)
    glm::vec4 patchBounds{0, 0, 1, 1};
    float specularStrength = 0.4f;
    float specularPower = 48.0f;
    Shading shading = Shading::Lit;
    WaterLook water;
    /// Curved meshes: the relief fades out where the view grazes the geometry (cos below this),
    /// so silhouettes keep the mesh's outline instead of smearing texels. 0 = off.
    float silhouetteFade = 0.0f;
    void validate() const;
    bool operator==(const SurfaceMaterial&) const = default;       ///< throws hfx::Error naming the field and its value
};

struct DirectionalLight {
    glm::vec3 direction{0.4f, 0.6f, 0.3f}; ///< towards the light, need not be unit length
    glm::vec3 color{1.0f, 0.97f, 0.9f};
    glm::vec3 ambient{0.18f, 0.2f, 0.24f};
};

struct DrawOptions {
    Technique technique = Technique::ParallaxOcclusion;
    bool traceOutput = false; ///< write (u, v, depth fraction, fetches) to colour attachment 1
};

class SurfaceRenderer {
public:
    SurfaceRenderer() = default;

    void draw(const Mesh& mesh, const glm::mat4& model, const SurfaceTextures& textures,
              const SurfaceMaterial& material, const Camera& camera, const DirectionalLight& light,
              const DrawOptions& options = {});

    /// Draws a mesh in one flat colour with its own depth (for scenes and tests).
    void drawFlat(const Mesh& mesh, const glm::mat4& model, const Camera& camera,
                  const glm::vec4& color);

    /// Builds the shader variant now (start-up) instead of on the first draw.
    const ShaderProgram& program(const DrawOptions& options, Shading shading = Shading::Lit);

private:
    std::map<std::tuple<int, bool, int>, ShaderProgram> programs_;
    ShaderProgram flat_;
};

} // namespace hfx
