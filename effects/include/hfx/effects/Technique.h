#pragma once
// The surface techniques, and the one table that describes them: its rows drive the names the
// command line accepts, the help text, the shader each variant is built from (one file per
// technique in shaders/trace/, defining hfx_trace and hfx_shadow; shaders/trace/README.md), the
// defines prepended to it, and the docs (hfx-demo techniques prints the README's table, which a
// test holds to it). Adding a technique is one enumerator, one file and one row.
//
// Thread: any (constant data).

#include <array>
#include <cstddef>
#include <string>

namespace hfx {

enum class Technique {
    NormalMapping,     ///< "nm"
    ParallaxOffset,    ///< "parallax"
    SteepParallax,     ///< "steep"
    Relief,            ///< "relief"
    Secant,            ///< "secant"
    ParallaxOcclusion, ///< "pom"
    Hierarchical,      ///< "hier"
};

/// How a technique shadows itself: not at all, any blocker darkens fully, blockers weighted by
/// distance (Tatarchuk's soft shadows, sampled along the light ray), or the light ray traced
/// exactly (hard visibility) with a penumbra from the blocker distance.
enum class SelfShadow { None, Hard, Soft, Exact };

struct TechniqueInfo {
    Technique technique;
    const char* name;        ///< on the command line and in the docs
    const char* shader;      ///< its file under shaders/
    const char* summary;     ///< what it does, one line
    SelfShadow shadow;
    bool traces;             ///< displaces the texcoords (and writes gl_FragDepth); false: plain normal mapping
    bool needsPyramid;       ///< reads the per-frame height bounds (HeightBounds, which ExactTracer builds)
};

/// Every technique, in the order the docs and menus list them (cheapest first).
inline constexpr TechniqueInfo kTechniqueTable[] = {
    {Technique::NormalMapping, "nm", "trace/nm.glsl", "normal mapping, no parallax", SelfShadow::None, false, false},
    {Technique::ParallaxOffset, "parallax", "trace/parallax.glsl", "parallax mapping with offset limiting (Welsh 2004)",
     SelfShadow::None, true, false},
    {Technique::SteepParallax, "steep", "trace/steep.glsl",
     "steep parallax: linear search, the first sample under the surface (McGuire 2005)", SelfShadow::Hard, true, false},
    {Technique::Relief, "relief", "trace/relief.glsl",
     "relief mapping: linear search, then 6 binary steps (Policarpo 2005)", SelfShadow::Hard, true, false},
    {Technique::Secant, "secant", "trace/secant.glsl", "linear search refined by 3 secant steps", SelfShadow::Soft,
     true, false},
    {Technique::ParallaxOcclusion, "pom", "trace/pom.glsl",
     "parallax occlusion mapping: linear search, piecewise-linear hit (Tatarchuk 2006)", SelfShadow::Soft, true,
     false},
    {Technique::Hierarchical, "hier", "trace/hier.glsl",
     "height-bounds pyramid walk to the exact bilinear hit (per-frame pyramid)", SelfShadow::Exact, true, true},
};

inline constexpr std::size_t kTechniqueCount = std::size(kTechniqueTable);

/// The techniques in the table's order.
inline constexpr std::array<Technique, kTechniqueCount> kTechniques = [] {
    std::array<Technique, kTechniqueCount> t{};
    for (std::size_t i = 0; i < kTechniqueCount; ++i) t[i] = kTechniqueTable[i].technique;
    return t;
}();

/// The table's row of a technique.
const TechniqueInfo& techniqueInfo(Technique technique);
const char* techniqueName(Technique technique);
/// The technique of a name; throws hfx::Error naming the value and the known names otherwise.
Technique parseTechnique(const std::string& name);
/// "nm, parallax, steep, relief, secant, pom, hier" (for help texts).
std::string techniqueNames();
/// "none", "hard", "soft".
const char* selfShadowName(SelfShadow shadow);
/// The table as Markdown (name, what it does, self-shadow, needs the pyramid): the README's.
std::string techniqueTableMarkdown();

/// How the surface is lit once the relief is traced: one file per model under shaders/shade/.
enum class Shading {
    Lit,    ///< Blinn-Phong of albedo and normal
    Water,  ///< Fresnel-weighted sky reflection, sun glint, body colour by depth, distance haze
    Planet, ///< Blinn-Phong with a soft terminator of the sphere and an atmosphere rim
};
/// "shade/lit.glsl", "shade/water.glsl", "shade/planet.glsl".
const char* shadingShader(Shading shading);
/// Whether the model's colour is affine in the light factor (HfxSurfacePoint::lit), so that two
/// shadings give it for any self-shadow: what the exact tracer's deferred light walks rebuild a
/// pixel from (DrawOptions::deferShadowWalks). Lit and Planet add lit times their direct light;
/// Water's highlights roll off above a knee, which is not affine.
bool shadingAffineInLight(Shading shading);

} // namespace hfx
