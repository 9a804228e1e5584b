#!/usr/bin/env bash
# Instructions of the water's shading (shade/water.glsl's hfx_shade, the sky and the foam with it),
# from the compiled shader: a device-neutral figure of what a change to it costs, where no GPU is
# at hand to time it. Composes a fragment shader from a shaders/ tree (default: this one) that
# shades one point, compiles it with glslangValidator (OpenGL rules), optimises it with
# spirv-opt -O and counts the instructions that do work, as scripts/walk_instructions.py does
# (not labels, merges, phis, unconditional branches, nor declarations). Static: both sides of a
# branch, a loop's body once.
#   bash scripts/water_instructions.sh [SHADER_DIR]
#   git archive REV shaders | tar -x -C DIR && bash scripts/water_instructions.sh DIR/shaders
set -euo pipefail
dir=${1:-"$(dirname "$0")/../shaders"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{
    echo "#version 450"
    grep "^#define" "$dir/bindings.glsl" | grep -v "HFX_BINDINGS_GLSL"
    cat "$dir/surface/uniforms.glsl" "$dir/shade/common.glsl" "$dir/shade/sky.glsl" "$dir/shade/water.glsl"
    cat <<'MAIN'
layout(location = 0) in vec4 v_a;
layout(location = 1) in vec4 v_b;
layout(location = 0) out vec4 o_color;
void main() {
    HfxSurfacePoint p;
    p.albedo = v_a.xyz;
    p.normal = normalize(v_b.xyz);
    p.geometricNormal = vec3(0.0, 1.0, 0.0);
    p.position = 10.0 * v_a.xyz;
    p.texcoord = v_a.xy;
    p.footprint = v_a.w;
    p.viewDir = normalize(v_b.zyx);
    p.lightDir = normalize(v_b.yxz);
    p.height = v_b.w;
    p.lit = v_a.z;
    p.cosView = v_a.w;
    p.diffuse = v_b.x;
    p.specular = v_b.y;
    p.roughness = 0.0;
    p.occlusion = 1.0;
    p.slopeVariance = v_a.x * v_a.y;
    p.foam = v_a;
    p.foamDetail = v_b;
MAIN
    if grep -q foamYoung "$dir/shade/common.glsl"; then echo "    p.foamYoung = v_b.wzyx;"; fi
    printf '    o_color = vec4(hfx_shade(p), 1.0);\n}\n'
} > "$work/water.frag"
glslangValidator -G -S frag "$work/water.frag" -o "$work/water.spv" > "$work/log" || { cat "$work/log"; exit 1; }
spirv-opt -O "$work/water.spv" -o "$work/opt.spv"
spirv-dis "$work/opt.spv" > "$work/opt.txt"
skip='OpLabel|OpSelectionMerge|OpLoopMerge|OpPhi|OpBranch\b|OpName|OpMemberName|OpDecorate|OpMemberDecorate'
skip+='|OpType|OpConstant|OpSpecConstant|OpVariable|OpExtInstImport|OpCapability|OpMemoryModel|OpEntryPoint'
skip+='|OpExecutionMode|OpSource|OpString|OpLine|OpModuleProcessed|OpFunction\b|OpFunctionEnd'
count=$(grep -E '^\s+(%\w+ = )?Op' "$work/opt.txt" | grep -v -E "$skip" | wc -l)
loops=$(grep -c OpLoopMerge "$work/opt.txt" || true)
echo "water hfx_shade: $count instructions, $loops loops ($dir)"
