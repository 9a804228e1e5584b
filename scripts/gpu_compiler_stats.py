#!/usr/bin/env python3
"""What a GPU's shader compiler makes of the surface program, without a GPU: each variant's
surface.vert + surface.frag (composed as the renderer composes them: its includes, the technique's
tracer and the shading model in their slots, its defines), compiled to SPIR-V by glslangValidator
and built into a graphics pipeline on RADV's null device (Mesa's Vulkan driver for AMD GPUs, with
RADV_FORCE_FAMILY: no hardware needed), whose compiler (ACO) reports the fragment shader's
statistics (RADV_DEBUG=shaderstats): vector registers (and before scheduling: how far the count is
from the next step of the allocation), the waves a SIMD then holds, instructions,
ACO's estimates of latency and inverse throughput (cycles), and the clauses of memory reads (a
clause issues its fetches back to back: fetches that do not wait for each other).

A device-neutral figure of what the variants cost a GPU beside walk_instructions.py's count: the
registers set how many waves hide a fetch's latency, and the clauses show which fetches a compiler
could batch. It is one compiler for one architecture (RDNA2 by default), not NVIDIA's.

    python3 scripts/gpu_compiler_stats.py [--family navi21] [--shaders DIR] [VARIANT ...]

A variant is a technique and defines, "hier" or "hier:HFX_TEXEL_SHADOWS=1,HFX_BEAM_START=1", with
the shading model after a slash where it is not lit ("pom/water:HFX_LAYERS=4,HFX_TRACED_LAYERS=3",
the ocean's); without any, POM, hier and hier with texel shadows and the beam start, as
bench-tracers draws them.
A compute shader of the shaders folder and its defines, "trace/hier/deferred.comp:HFX_LAYERS=1",
is built into a compute pipeline, and its statistics are the compute shader's.
Needs glslang-tools, spirv-tools, Mesa's Vulkan drivers and the Vulkan loader (apt-get install
mesa-vulkan-drivers libvulkan1) and Python's vulkan bindings (pip install vulkan).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import walk_instructions  # noqa: E402  (its include expansion, the renderer's)

ICD = "/usr/share/vulkan/icd.d/radeon_icd.x86_64.json"
DEFAULT_VARIANTS = ["pom", "hier", "hier:HFX_TEXEL_SHADOWS=1,HFX_BEAM_START=1"]
STATS = ("VGPRs", "Pre-Sched VGPRs", "Subgroups per SIMD", "Instructions", "Latency", "Inverse Throughput", "VMEM Clause")


def compose(shaders, stage, tracer, defines, shading="lit", path=None):
    """surface.<stage> (or the file `path`) with its slots filled and includes expanded, the
    defines after #version. Vulkan's GLSL has no gl_DepthRange: the default range (0, 1) stands
    in for it."""
    with open(os.path.join(shaders, path or f"surface.{stage}")) as f:
        source = f.read()
    source = source.replace("#include <tracer>", f'#include "trace/{tracer}.glsl"')
    source = source.replace("#include <shading>", f'#include "shade/{shading}.glsl"')
    out, seen = [], set()
    for line in source.split("\n"):
        m = re.match(r'\s*#include\s+"([^"]+)"', line)
        out.append(walk_instructions.expand(shaders, m.group(1), seen) if m else line)
        if line.startswith("#version"):
            out += [f"#define {k} {v}" for k, v in defines.items()]
    text = "\n".join(out)
    for name, value in (("diff", "1.0"), ("near", "0.0"), ("far", "1.0")):
        text = text.replace(f"gl_DepthRange.{name}", value)
    return text


def spirv(source, stage, work):
    src, spv = os.path.join(work, f"surface.{stage}"), os.path.join(work, f"{stage}.spv")
    with open(src, "w") as f:
        f.write(source)
    # Images, storage and uniform buffers moved off the samplers' binding numbers: one set.
    # -R: loose uniforms (a pass's own, beside the blocks) gathered into a default uniform block.
    run = subprocess.run(["glslangValidator", "-V", "-R", "--auto-map-bindings", "--target-env", "vulkan1.2", "--auto-map-locations",
                          "--shift-image-binding", "100", "--shift-ssbo-binding", "200", "--shift-UBO-binding", "300",
                          "-o", spv, src], capture_output=True, text=True)
    if run.returncode:
        sys.exit(f"glslangValidator failed on {src}:\n{run.stdout}{run.stderr}")
    return spv


def descriptors(spv_paths):
    """binding -> (descriptor type name, count) of every resource the modules declare."""
    found = {}
    for path in spv_paths:
        dis = subprocess.run(["spirv-dis", path], capture_output=True, text=True, check=True).stdout
        defs = dict(re.findall(r"^\s*(%\w+) = (Op\w+.*)$", dis, re.M))
        for var, binding in re.findall(r"OpDecorate (%\w+) Binding (\d+)", dis):
            _, pointer, storage = defs[var].split()[:3]
            pointee = defs[pointer].split()[-1]
            kind, count = defs[pointee].split()[0], 1
            if kind == "OpTypeArray":
                element, length = defs[pointee].split()[1:3]
                kind, count = defs[element].split()[0], int(defs[length].split()[-1])
            name = {("UniformConstant", "OpTypeSampledImage"): "COMBINED_IMAGE_SAMPLER",
                    ("UniformConstant", "OpTypeImage"): "STORAGE_IMAGE",
                    ("Uniform", "OpTypeStruct"): "UNIFORM_BUFFER",
                    ("StorageBuffer", "OpTypeStruct"): "STORAGE_BUFFER"}.get((storage, kind))
            if name is None:
                sys.exit(f"{path}: binding {binding} of {storage} {kind} has no descriptor type here")
            found[int(binding)] = (name, count)
    return found


def _info(vk, cls, kind, **kw):
    return getattr(vk, cls)(sType=getattr(vk, "VK_STRUCTURE_TYPE_" + kind), **kw)


def _device_and_layout(spv_paths):
    """The first Vulkan device (the null device the caller's environment names), a loader for
    the modules' code, and a pipeline layout of one set holding every resource they declare."""
    import vulkan as vk
    app = _info(vk, "VkApplicationInfo", "APPLICATION_INFO", pApplicationName="hfx", apiVersion=vk.VK_MAKE_VERSION(1, 2, 0))
    instance = vk.vkCreateInstance(_info(vk, "VkInstanceCreateInfo", "INSTANCE_CREATE_INFO", pApplicationInfo=app), None)
    physical = vk.vkEnumeratePhysicalDevices(instance)[0]
    queue = _info(vk, "VkDeviceQueueCreateInfo", "DEVICE_QUEUE_CREATE_INFO", queueFamilyIndex=0, queueCount=1,
                  pQueuePriorities=[1.0])
    device = vk.vkCreateDevice(physical, _info(vk, "VkDeviceCreateInfo", "DEVICE_CREATE_INFO", queueCreateInfoCount=1,
                                                pQueueCreateInfos=[queue]), None)

    def module(path):
        with open(path, "rb") as f:
            code = f.read()
        return vk.vkCreateShaderModule(device, _info(vk, "VkShaderModuleCreateInfo", "SHADER_MODULE_CREATE_INFO",
                                                     codeSize=len(code), pCode=code), None)

    bindings = [vk.VkDescriptorSetLayoutBinding(binding=b, descriptorType=getattr(vk, "VK_DESCRIPTOR_TYPE_" + t),
                                                descriptorCount=n, stageFlags=vk.VK_SHADER_STAGE_ALL)
                for b, (t, n) in sorted(descriptors(spv_paths).items())]
    set_layout = vk.vkCreateDescriptorSetLayout(device, _info(vk, "VkDescriptorSetLayoutCreateInfo",
                                                              "DESCRIPTOR_SET_LAYOUT_CREATE_INFO",
                                                              bindingCount=len(bindings), pBindings=bindings), None)
    layout = vk.vkCreatePipelineLayout(device, _info(vk, "VkPipelineLayoutCreateInfo", "PIPELINE_LAYOUT_CREATE_INFO",
                                                     setLayoutCount=1, pSetLayouts=[set_layout]), None)
    return device, module, layout


def build_compute(comp):
    """Builds the compute pipeline; the driver prints the shader's statistics as it compiles it."""
    import vulkan as vk
    device, module, layout = _device_and_layout([comp])
    stage = _info(vk, "VkPipelineShaderStageCreateInfo", "PIPELINE_SHADER_STAGE_CREATE_INFO",
                  stage=vk.VK_SHADER_STAGE_COMPUTE_BIT, module=module(comp), pName="main")
    vk.vkCreateComputePipelines(device, None, 1, [_info(vk, "VkComputePipelineCreateInfo", "COMPUTE_PIPELINE_CREATE_INFO",
                                                        stage=stage, layout=layout)], None)


def build_pipeline(vert, frag):
    """Builds the graphics pipeline on the first Vulkan device (the null device the caller's
    environment names); the driver prints the shaders' statistics as it compiles them."""
    import vulkan as vk

    def info(cls, kind, **kw):
        return _info(vk, cls, kind, **kw)

    device, module, layout = _device_and_layout([vert, frag])
    attachment = vk.VkAttachmentDescription(
        format=vk.VK_FORMAT_R16G16B16A16_SFLOAT, samples=vk.VK_SAMPLE_COUNT_1_BIT,
        loadOp=vk.VK_ATTACHMENT_LOAD_OP_CLEAR, storeOp=vk.VK_ATTACHMENT_STORE_OP_STORE,
        stencilLoadOp=vk.VK_ATTACHMENT_LOAD_OP_DONT_CARE, stencilStoreOp=vk.VK_ATTACHMENT_STORE_OP_DONT_CARE,
        initialLayout=vk.VK_IMAGE_LAYOUT_UNDEFINED, finalLayout=vk.VK_IMAGE_LAYOUT_GENERAL)
    subpass = vk.VkSubpassDescription(pipelineBindPoint=vk.VK_PIPELINE_BIND_POINT_GRAPHICS, colorAttachmentCount=1,
                                      pColorAttachments=[vk.VkAttachmentReference(
                                          attachment=0, layout=vk.VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL)])
    render_pass = vk.vkCreateRenderPass(device, info("VkRenderPassCreateInfo", "RENDER_PASS_CREATE_INFO", attachmentCount=1,
                                                     pAttachments=[attachment], subpassCount=1, pSubpasses=[subpass]), None)
    stages = [info("VkPipelineShaderStageCreateInfo", "PIPELINE_SHADER_STAGE_CREATE_INFO", stage=bit, module=module(path),
                   pName="main")
              for bit, path in ((vk.VK_SHADER_STAGE_VERTEX_BIT, vert), (vk.VK_SHADER_STAGE_FRAGMENT_BIT, frag))]
    # surface.vert's attributes: position, normal, tangent, bitangent (vec3), texcoord (vec2).
    formats = [vk.VK_FORMAT_R32G32B32_SFLOAT] * 4 + [vk.VK_FORMAT_R32G32_SFLOAT]
    vertex = info("VkPipelineVertexInputStateCreateInfo", "PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO",
                  vertexBindingDescriptionCount=1,
                  pVertexBindingDescriptions=[vk.VkVertexInputBindingDescription(binding=0, stride=56,
                                                                                 inputRate=vk.VK_VERTEX_INPUT_RATE_VERTEX)],
                  vertexAttributeDescriptionCount=len(formats),
                  pVertexAttributeDescriptions=[vk.VkVertexInputAttributeDescription(location=i, binding=0, format=f,
                                                                                     offset=12 * i)
                                                for i, f in enumerate(formats)])
    pipeline = info(
        "VkGraphicsPipelineCreateInfo", "GRAPHICS_PIPELINE_CREATE_INFO", stageCount=2, pStages=stages,
        pVertexInputState=vertex,
        pInputAssemblyState=info("VkPipelineInputAssemblyStateCreateInfo", "PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO",
                                 topology=vk.VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST),
        pViewportState=info("VkPipelineViewportStateCreateInfo", "PIPELINE_VIEWPORT_STATE_CREATE_INFO", viewportCount=1,
                            scissorCount=1),
        pRasterizationState=info("VkPipelineRasterizationStateCreateInfo", "PIPELINE_RASTERIZATION_STATE_CREATE_INFO",
                                 polygonMode=vk.VK_POLYGON_MODE_FILL, cullMode=0, frontFace=0, lineWidth=1.0),
        pMultisampleState=info("VkPipelineMultisampleStateCreateInfo", "PIPELINE_MULTISAMPLE_STATE_CREATE_INFO",
                               rasterizationSamples=vk.VK_SAMPLE_COUNT_1_BIT),
        pColorBlendState=info("VkPipelineColorBlendStateCreateInfo", "PIPELINE_COLOR_BLEND_STATE_CREATE_INFO",
                              attachmentCount=1,
                              pAttachments=[vk.VkPipelineColorBlendAttachmentState(blendEnable=0, colorWriteMask=0xF)]),
        pDynamicState=info("VkPipelineDynamicStateCreateInfo", "PIPELINE_DYNAMIC_STATE_CREATE_INFO", dynamicStateCount=2,
                           pDynamicStates=[vk.VK_DYNAMIC_STATE_VIEWPORT, vk.VK_DYNAMIC_STATE_SCISSOR]),
        layout=layout, renderPass=render_pass, subpass=0)
    vk.vkCreateGraphicsPipelines(device, None, 1, [pipeline], None)


def stats(shaders, family, tracer, defines, shading="lit"):
    """The fragment shader's statistics (name -> number) of one variant; a compute shader's
    where `tracer` names a .comp file."""
    work = tempfile.mkdtemp(prefix="hfx-gpu-stats-")
    if tracer.endswith(".comp"):
        files, shader = [spirv(compose(shaders, "comp", None, defines, path=tracer), "comp", work)], "Compute Shader"
    else:
        files = [spirv(compose(shaders, "vert", tracer, defines, shading), "vert", work),
                 spirv(compose(shaders, "frag", tracer, defines, shading), "frag", work)]
        shader = "Pixel Shader"
    env = dict(os.environ, RADV_FORCE_FAMILY=family, RADV_DEBUG="shaderstats,nocache", VK_ICD_FILENAMES=ICD,
               XDG_RUNTIME_DIR=os.environ.get("XDG_RUNTIME_DIR", work))
    run = subprocess.run([sys.executable, os.path.abspath(__file__), "--build", *files], env=env,
                         capture_output=True, text=True)
    text = run.stdout + run.stderr
    m = re.search(shader + r":\s*\*\*\* SHADER STATS \*\*\*(.*?)\*{8}", text, re.S)
    if run.returncode or not m:
        sys.exit(f"no {shader.lower()} statistics from RADV's null device ({family}):\n{text[-3000:]}")
    return {k: float(v) for k, v in re.findall(r"^([A-Za-z -]+): (\d+)", m.group(1), re.M)}


def main():
    if len(sys.argv) in (3, 4) and sys.argv[1] == "--build":
        try:
            build_pipeline(sys.argv[2], sys.argv[3]) if len(sys.argv) == 4 else build_compute(sys.argv[2])
        except ImportError:
            sys.exit("Python's vulkan bindings are not installed (pip install vulkan)")
        return
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("variants", nargs="*", default=DEFAULT_VARIANTS)
    ap.add_argument("--family", default="navi21", help="the AMD GPU to compile for (RADV_FORCE_FAMILY)")
    ap.add_argument("--shaders", default=os.path.join(HERE, "..", "shaders"))
    args = ap.parse_args()
    if not os.path.exists(ICD):
        sys.exit(f"{ICD} is missing: apt-get install mesa-vulkan-drivers libvulkan1")
    print(f"RADV null device ({args.family}), ACO; the fragment shader of surface.frag per variant (a .comp: its own) "
          f"({os.path.normpath(args.shaders)})\n")
    print("| variant | " + " | ".join(STATS) + " |")
    print("|---" * (len(STATS) + 1) + "|")
    for variant in args.variants:
        program, _, rest = variant.partition(":")
        # A compute shader is named by its path ("trace/hier/trace.comp"); a surface program as
        # tracer/shading ("pom/water").
        tracer, shading = (program, "") if program.endswith(".comp") else program.partition("/")[::2]
        defines = dict(d.split("=", 1) for d in rest.split(",") if d)
        s = stats(args.shaders, args.family, tracer, defines, shading or "lit")
        print(f"| {variant} | " + " | ".join(f"{s.get(k, float('nan')):.0f}" for k in STATS) + " |")


if __name__ == "__main__":
    main()
