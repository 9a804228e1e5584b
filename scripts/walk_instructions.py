#!/usr/bin/env python3
"""Instructions per step of the exact tracer's walks, from the compiled shader: a device-neutral
figure of what a step costs an instruction-issue-bound GPU.

The renderer's own sources (surface/uniforms.glsl, surface/heights.glsl, trace/common.glsl,
trace/hier.glsl; the pyramid as the mip chain a GPU reads, or with --defines HFX_PYRAMID_ATLAS=1
llvmpipe's atlas) are composed into a compute shader that runs the view walk (hfx_trace), the light
walk (hfx_shadow) and the beam walk (hfx_beam_depth), compiled to SPIR-V by glslangValidator
(OpenGL rules) and optimised by spirv-opt -O (inlining, constant folding, dead code). Each loop of
the result is a walk (or a loop inside one); a step is one trip around it: every path from the
loop's header back to it. Per loop and kind of step (one that reads a bound; one that solves a
patch) this prints the shortest and the longest such path that reads a texture or image (a walk
step fetches), counted in instructions that do work: everything but labels, merge annotations,
phis and unconditional branches. --limit holds the steps reading a bound to a budget. A loop
inside a loop (the older walk's shape) is printed with its nesting.

    python3 scripts/walk_instructions.py [--accessors renderer|mip] [--shaders DIR] [--defines D=1 ...]
                                         [--keep DIR] [--show LOOP]

With --shading MODEL (--water for water) it counts a shading model's instead (shade/MODEL.glsl's
hfx_shade, the sky and what the model includes with it, in a fragment shader that shades one
point): the instructions of the whole optimised shader, both sides of each branch and each loop's
body once, a device-neutral figure of what a change to it costs where no GPU is at hand to time it.

Needs glslang-tools and spirv-tools (scripts/setup.sh installs them).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

# The renderer's accessors count their reads (g_fetches) for the trace output alone (HFX_TRACE_OUTPUT,
# the accuracy probe's draws); a frame's draw never reads the count, so its compiler drops the
# counting, and so does this harness's by not writing it.
HARNESS_MAIN = """
layout(std430, binding = 1) readonly buffer HfxCountRays { vec4 rays[]; };
layout(std430, binding = 2) writeonly buffer HfxCountHits { vec4 hits[]; };
void main() {
    const uint i = gl_GlobalInvocationID.x;
    const vec4 a = rays[3 * i], b = rays[3 * i + 1], c = rays[3 * i + 2];
    const HfxRay ray = HfxRay(a.xy, a.zw, b.x, b.y, int(b.z), b.w, c.x);
    const HfxHit hit = hfx_trace(ray);
    const float shadow = hfx_shadow(HfxShadowRay(hit.uv, 1.0 - hit.depth, c.yz, 0.0, 8, b.x));
    const float start = hfx_beam_depth(a.xy, a.zw, c.w);
    hits[i] = vec4(hit.uv, shadow + start, 0.0);
}
"""

# --accessors mip: the least a harness's accessors can be: a bound one texelFetch at the cell,
# wrapped by a mask, at the level; a cell's samples one textureGather; no clamped edges. The
# walk's own instructions, without the renderer's options.
MIP_ACCESSORS = """
layout(binding = 0) uniform sampler2D s_surface;
layout(binding = 1) uniform sampler2D s_bounds;
layout(std140, binding = 0) uniform HfxCountField { ivec2 u_size; };
float g_fetches = 0.0;
float hfx_height(vec2 uv, float level) { return textureLod(s_surface, uv, level).w; }
ivec2 hfx_size() { return u_size; }
vec4 hfx_cell_samples(ivec2 cell) { return textureGather(s_surface, (vec2(cell) + 1.0) / vec2(u_size), 3); }
vec2 hfx_bounds(ivec2 cell, int level) { return texelFetch(s_bounds, cell & ((u_size >> level) - 1), level).rg; }
vec2 hfx_segment_bounds(vec2 a, vec2 b, float level) { return vec2(1.0, 0.0); }
"""

FETCH = re.compile(r"\bOp(ImageRead|ImageFetch|ImageGather|ImageSample\w*|ImageDrefGather)\b")
# Not counted: labels and annotations, phis and jumps (register allocation and block layout), and
# SPIR-V's plumbing (a vector's component, a splat, a shuffle, the image of a sampler), which a
# GPU's instructions read in place.
NOT_WORK = {"OpLabel", "OpSelectionMerge", "OpLoopMerge", "OpPhi", "OpBranch", "OpLine", "OpNoLine",
            "OpCompositeExtract", "OpCompositeConstruct", "OpVectorShuffle", "OpImage", "OpCopyObject",
            "OpMemoryBarrier"}
VECTOR = re.compile(r"= Op\w+ %v([234])(?:int|uint|float|bool)\b")


# --shading: one point shaded by hfx_shade, every field of the point from the inputs.
SHADE_MAIN = """
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
    YOUNG
    o_color = vec4(hfx_shade(p), 1.0);
}
"""


def expand(shaders, name, seen):
    """A shader file with its #include "..." lines replaced by the files (each once), as the
    renderer's embedding composes them."""
    if name in seen:
        return ""
    seen.add(name)
    with open(os.path.join(shaders, name)) as f:
        lines = f.read().split("\n")
    out = []
    for line in lines:
        m = re.match(r'\s*#include\s+"([^"]+)"', line)
        out.append(expand(shaders, m.group(1), seen) if m else line)
    return "\n".join(out)


def compose_shading(shaders, model):
    """One point shaded by shade/<model>.glsl's hfx_shade, the sky composed before it as in the
    surface program."""
    seen = set()
    parts = ["#version 450 core"]
    for name in ("bindings.glsl", "surface/uniforms.glsl", "shade/common.glsl", "shade/sky.glsl", f"shade/{model}.glsl"):
        parts.append(expand(shaders, name, seen))
    # Trees before the foam's young part (HfxSurfacePoint::foamYoung) compose too.
    young = "p.foamYoung = v_b.wzyx;" if "foamYoung" in parts[3] else ""
    parts.append(SHADE_MAIN.replace("YOUNG", young))
    return "\n".join(parts)


def compose(shaders, defines, accessors):
    parts = ["#version 450 core", "layout(local_size_x = 64) in;"]
    parts += [f"#define {d.replace('=', ' ', 1)}" for d in defines]
    names = ["trace/common.glsl", "trace/hier.glsl"]
    if accessors == "renderer":
        names = ["bindings.glsl", "surface/uniforms.glsl", "surface/heights.glsl"] + names
    else:
        parts.append(MIP_ACCESSORS)
    for name in names:
        with open(os.path.join(shaders, name)) as f:
            parts.append(f.read())
    parts.append(HARNESS_MAIN)
    return mark_solves("\n".join(parts))


# A step that solves a patch is told from one that does not by a marker the optimiser keeps: a
# barrier (not counted) before each walk's patch solve, hfx_patch_along's statement.
SOLVE = re.compile(r"^(\s*)(const vec3 along = hfx_patch_along\()", re.M)
MARKER = "OpMemoryBarrier"


def mark_solves(source):
    marked, n = SOLVE.subn(r"\1groupMemoryBarrier();\n\1\2", source)
    if n != 2:
        sys.exit(f"expected the view and the light walk's patch solves (hfx_patch_along), found {n}")
    return marked


def compile_spirv(source, work, stage="comp"):
    comp, spv, opt, asm = (os.path.join(work, n)
                           for n in (f"walk.{stage}", "walk.spv", "walk.opt.spv", "walk.spvasm"))
    with open(comp, "w") as f:
        f.write(source)
    for cmd in (["glslangValidator", "-G", "--auto-map-locations", "--auto-map-bindings", "-o", spv, comp],
                ["spirv-opt", "-O", spv, "-o", opt], ["spirv-dis", "--no-header", opt, "-o", asm]):
        try:
            run = subprocess.run(cmd, capture_output=True, text=True)
        except FileNotFoundError:
            sys.exit(f"{cmd[0]} is not installed (glslang-tools, spirv-tools: scripts/setup.sh installs them)")
        if run.returncode != 0:
            sys.exit(f"{' '.join(cmd[:1])} failed:\n{run.stdout}{run.stderr}")
    with open(asm) as f:
        return f.read().splitlines()


def parse_blocks(lines):
    """Blocks of main in order: label -> (instructions, successors, loop (merge, continue) or None)."""
    blocks, order, current = {}, [], None
    for raw in lines:
        line = raw.strip()
        if not line or line.startswith(";"):
            continue
        m = re.match(r"(%\w+) = OpLabel", line)
        if m:
            current = m.group(1)
            blocks[current] = {"ops": [], "succ": [], "loop": None}
            order.append(current)
            continue
        if current is None:
            continue
        op = re.search(r"\bOp\w+", line).group(0)
        block = blocks[current]
        block["ops"].append((op, line))
        if op == "OpLoopMerge":
            merge, cont = line.split()[1:3]
            block["loop"] = (merge, cont)
        elif op == "OpBranch":
            block["succ"] = [line.split()[1]]
        elif op == "OpBranchConditional":
            block["succ"] = line.split()[2:4]
        elif op == "OpSwitch":
            block["succ"] = [t for t in line.split()[2:] if t.startswith("%")]
        if op in ("OpBranch", "OpBranchConditional", "OpSwitch", "OpReturn", "OpReturnValue", "OpKill",
                  "OpUnreachable"):
            current = None
    return blocks, order


def loop_body(blocks, header):
    merge, _ = blocks[header]["loop"]
    body, stack = set(), [header]
    while stack:
        b = stack.pop()
        if b in body or b == merge:
            continue
        body.add(b)
        stack.extend(s for s in blocks[b]["succ"] if s != header)
    return body


def work(block):
    """(instructions, scalar operations): a vector operation is one SPIR-V instruction and one
    operation per component on a scalar GPU (a fetch is one either way)."""
    ops = [(op, line) for op, line in block["ops"] if op not in NOT_WORK]
    scalar = 0
    for op, line in ops:
        m = VECTOR.search(line)
        scalar += int(m.group(1)) if m and not FETCH.search(line) else 1
    return len(ops), scalar


def fetches(block):
    return sum(1 for _, line in block["ops"] if FETCH.search(line))


def solves(block):
    return any(op == MARKER for op, _ in block["ops"])


def step_kind(path, blocks):
    """What a step does: solves a patch (reading the cell's samples after its bound), or reads a
    bound."""
    return "solves a patch" if any(solves(blocks[b]) for b in path) else "a step (a bound)"


def step_paths(blocks, header, body, inner_headers, limit=200000):
    """(work, fetches, path, kind) of every acyclic path header -> ... -> header inside the body;
    an inner loop's body is entered at its header and left at its merge block, counted as its
    header only."""
    results, stack = [], [(header, (0, 0), 0, frozenset([header]), (header,))]
    while stack and len(results) < limit:
        b, w, f, seen, path = stack.pop()
        w = tuple(a + b for a, b in zip(w, work(blocks[b])))
        f += fetches(blocks[b])
        succ = blocks[b]["succ"]
        if b != header and b in inner_headers:
            succ = [blocks[b]["loop"][0]]
        for s in succ:
            if s == header:
                results.append((w, f, path, step_kind(path, blocks)))
            elif s in body and s not in seen:
                stack.append((s, w, f, seen | {s}, path + (s,)))
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shaders", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "shaders"))
    ap.add_argument("--defines", nargs="*", default=[])
    ap.add_argument("--accessors", choices=("renderer", "mip"), default="renderer",
                    help="the renderer's accessors (surface/heights.glsl), or a mip chain's (texelFetch, gather)")
    ap.add_argument("--keep", help="write the composed shader and its SPIR-V here")
    ap.add_argument("--show", type=int, help="print the instructions of this loop's fewest step")
    ap.add_argument("--show-most", type=int, help="print the instructions of this loop's longest one-fetch step")
    ap.add_argument("--limit", type=int, help="fail (exit 1) where a walk's step reading a bound takes more instructions")
    ap.add_argument("--water", action="store_true", help="count the water's shading instead of the walks")
    ap.add_argument("--shading", choices=("water", "planet", "lit", "rings"),
                    help="count this shading model's hfx_shade instead of the walks (--water: water; rings: "
                         "the planet's rings' own fragment shader, rings.frag)")
    args = ap.parse_args()
    work_dir = args.keep or tempfile.mkdtemp(prefix="hfx-walk-")
    os.makedirs(work_dir, exist_ok=True)
    model = "water" if args.water else args.shading
    if model:
        source = expand(args.shaders, "rings.frag", set()) if model == "rings" else compose_shading(args.shaders, model)
        blocks, order = parse_blocks(compile_spirv(source, work_dir, "frag"))
        total = [sum(work(blocks[b])[i] for b in order) for i in (0, 1)]
        loops = sum(1 for b in order if blocks[b]["loop"])
        what = "rings.frag" if model == "rings" else f"{model} hfx_shade"
        print(f"{what} ({os.path.normpath(args.shaders)}, spirv-opt -O): {total[0]} instructions "
              f"({total[1]} scalar operations), {loops} loops")
        return
    blocks, order = parse_blocks(compile_spirv(compose(args.shaders, args.defines, args.accessors), work_dir))
    headers = [b for b in order if blocks[b]["loop"]]
    bodies = {h: loop_body(blocks, h) for h in headers}
    print(f"{len(headers)} loops in the composed walks ({args.accessors} accessors, spirv-opt -O; defines: "
          f"{' '.join(args.defines) or 'none'})")
    print("| loop | nested in | blocks | step | fetches | instructions (scalar operations), fewest - most |")
    print("|---|---|---|---|---|---|")
    over = []
    for n, h in enumerate(headers, 1):
        outer = [str(headers.index(o) + 1) for o in headers if o != h and h in bodies[o]]
        inner = {o for o in headers if o != h and o in bodies[h]}
        paths = [p for p in step_paths(blocks, h, bodies[h], inner) if p[1] > 0]
        if not paths:
            print(f"| {n} | {','.join(outer) or '-'} | {len(bodies[h])} | - | 0 | (no step reads) |")
            continue
        shown = {args.show: min(paths)}
        if args.show_most is not None:
            shown[args.show_most] = max(p for p in paths if p[1] == 1 and p[3] != "solves a patch")
        if n in shown:
            for b in shown[n][2]:
                print("\n".join(f"    {line}" for op, line in blocks[b]["ops"] if op not in NOT_WORK))
        # Steps by what they do: a walk step reads one bound; the rare one that also solves a
        # patch reads the cell's samples after it.
        for kind in sorted({(p[3], p[1]) for p in paths}, key=lambda k: (k[0] == "solves a patch", k)):
            same = [p[0] for p in paths if (p[3], p[1]) == kind]
            lo, hi = min(same), max(same)
            what, fetched = kind
            print(f"| {n} | {','.join(outer) or '-'} | {len(bodies[h])} | {what} | "
                  f"{fetched} | {lo[0]} ({lo[1]}) - {hi[0]} ({hi[1]}) |")
            if args.limit is not None and what == "a step (a bound)" and hi[0] > args.limit:
                over.append(f"loop {n}: a step takes up to {hi[0]} instructions, more than {args.limit}")
    if over:
        sys.exit("\n".join(over))


if __name__ == "__main__":
    main()
