#include "hfx/effects/Technique.h"

#include "hfx/core/Error.h"
#include "hfx/core/Names.h"

namespace hfx {

const TechniqueInfo& techniqueInfo(Technique technique) {
    for (const TechniqueInfo& row : kTechniqueTable)
        if (row.technique == technique) return row;
    throw Error(str("technique ", int(technique), " has no row in kTechniqueTable"));
}

const char* techniqueName(Technique technique) { return techniqueInfo(technique).name; }

std::string techniqueNames() {
    std::string names;
    for (const TechniqueInfo& row : kTechniqueTable) names += (names.empty() ? "" : ", ") + std::string(row.name);
    return names;
}

Technique parseTechnique(const std::string& name) {
    for (const TechniqueInfo& row : kTechniqueTable)
        if (name == row.name) return row.technique;
    throw Error(str("unknown technique '", name, "' (expected one of ", techniqueNames(), ")"));
}

namespace {
constexpr NamedValue<SelfShadow> kShadowNames[] = {
    {SelfShadow::None, "none"}, {SelfShadow::Hard, "hard"}, {SelfShadow::Soft, "soft"},
    {SelfShadow::Exact, "exact"}};
constexpr NamedValue<Shading> kShadingShaders[] = {
    {Shading::Lit, "shade/lit.glsl"}, {Shading::Water, "shade/water.glsl"}, {Shading::Planet, "shade/planet.glsl"}};
} // namespace

const char* selfShadowName(SelfShadow shadow) { return nameOf(kShadowNames, shadow); }

std::string techniqueTableMarkdown() {
    std::string md = "| name | technique | self-shadow | needs the pyramid |\n| --- | --- | --- | --- |\n";
    for (const TechniqueInfo& row : kTechniqueTable)
        md += str("| `", row.name, "` | ", row.summary, " | ", selfShadowName(row.shadow), " | ",
                  row.needsPyramid ? "yes" : "no", " |\n");
    return md;
}

const char* shadingShader(Shading shading) { return nameOf(kShadingShaders, shading); }

bool shadingAffineInLight(Shading shading) { return shading != Shading::Water; }

} // namespace hfx
