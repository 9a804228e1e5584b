#include "hfx/effects/Technique.h"

#include "hfx/core/Error.h"

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

const char* selfShadowName(SelfShadow shadow) {
    switch (shadow) {
    case SelfShadow::None: return "none";
    case SelfShadow::Hard: return "hard";
    case SelfShadow::Soft: return "soft";
    }
    return "?";
}

std::string techniqueTableMarkdown() {
    std::string md = "| name | technique | self-shadow | needs the pyramid |\n| --- | --- | --- | --- |\n";
    for (const TechniqueInfo& row : kTechniqueTable)
        md += str("| `", row.name, "` | ", row.summary, " | ", selfShadowName(row.shadow), " | ",
                  row.needsPyramid ? "yes" : "no", " |\n");
    return md;
}

const char* shadingShader(Shading shading) {
    switch (shading) {
    case Shading::Lit: return "shade/lit.glsl";
    case Shading::Water: return "shade/water.glsl";
    case Shading::Planet: return "shade/planet.glsl";
    }
    throw Error(str("shading ", int(shading), " has no shader"));
}

} // namespace hfx
