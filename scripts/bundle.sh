#!/usr/bin/env bash
# Builds a relocatable bundle of HFX for a machine that has a GL and OpenCL driver (a GPU's, or
# Mesa and PoCL) but none of the build's packages:
#
#   bash scripts/bundle.sh DIR                  # here
#   bash DIR/run.sh hfx-demo bench-tracers      # there, from any folder
#   bash DIR/run.sh hfx-tests-gl --gtest_brief=1
#
# DIR/bin: hfx-demo, the test binaries (core, cl, gl) and hfx-bench-kernels, built with the light
# image codec (stb + tinyexr; OpenImageIO's closure is 360 MB); DIR/lib: their shared libraries
# (the ldd closure less glibc and libstdc++, which the target has); DIR/shaders: the shader
# sources the GL tests read; DIR/run.sh: the launcher (bundle libraries first on the loader path,
# every GL vendor and OpenCL driver the machine has, NVIDIA's included). Drivers are not carried:
# Mesa's EGL and llvmpipe, PoCL, NVIDIA's libraries come from the target. The build goes to
# HFX_BUNDLE_BUILD (default build-bundle/); HFX_BUNDLE_TARGETS may name fewer programs (CTest's
# check bundles the demo and the core tests, the ones it runs).
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: scripts/bundle.sh DIR" >&2; exit 2; }
out=$(realpath -m "$1")
build=$(realpath -m "${HFX_BUNDLE_BUILD:-build-bundle}")
bash scripts/setup.sh
read -r -a targets <<< "${HFX_BUNDLE_TARGETS:-hfx-demo hfx-tests-core hfx-tests-cl hfx-tests-gl hfx-bench-kernels}"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DHFX_IMAGE_IO=light -DHFX_BUILD_TESTS=ON -DHFX_BUILD_DEMO=ON \
    -Wno-dev > "$build.log" 2>&1 || { cat "$build.log"; exit 1; }
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}" >> "$build.log" 2>&1 || { tail -n 60 "$build.log"; exit 1; }

rm -rf "$out"
mkdir -p "$out/bin" "$out/lib"
for t in "${targets[@]}"; do
    f=$(find "$build" -type f -name "$t" -perm -u+x | head -1)
    [ -n "$f" ] || { echo "bundle: $t was not built" >&2; exit 1; }
    cp "$f" "$out/bin/"
done
strip --strip-unneeded "$out"/bin/*

# The ldd closure, less what every target has (glibc, the C++ runtime) and what must be the
# target's own (the GL vendor libraries behind glvnd's dispatch).
skip='^(linux-vdso|ld-linux|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|libstdc\+\+\.so|libgcc_s\.so|libGLX_|libEGL_)'
for b in "$out"/bin/*; do ldd "$b" | awk '$3 ~ /^\// {print $1, $3}'; done | sort -u | while read -r name path; do
    [[ $name =~ $skip ]] || cp -L "$path" "$out/lib/$name"
done
# The Vulkan loader, which the external-memory transfer path opens at run time (not in ldd's list).
vulkan=$(ldconfig -p 2>/dev/null | grep -o '/[^ ]*libvulkan\.so\.1$' | head -1 || true)
[ -n "$vulkan" ] && cp -L "$vulkan" "$out/lib/libvulkan.so.1"
if ls "$out/lib" | grep -qi -E 'OpenImageIO|LLVM|OSMesa'; then
    echo "bundle: a heavy library slipped in: $(ls "$out/lib" | grep -i -E 'OpenImageIO|LLVM|OSMesa')" >&2
    exit 1
fi
cp -r shaders "$out/shaders"
git rev-parse --short HEAD > "$out/commit" 2>/dev/null || echo unknown > "$out/commit"

cat > "$out/run.sh" <<'LAUNCHER'
#!/usr/bin/env bash
# HFX bundle launcher: bash run.sh PROGRAM [ARGS...] (hfx-demo, hfx-tests-core, hfx-tests-cl,
# hfx-tests-gl, hfx-bench-kernels), from any folder. Test output goes to ./hfx-test-output.
set -euo pipefail
b=$(cd "$(dirname "$0")" && pwd)
export LD_LIBRARY_PATH="$b/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# glvnd's EGL finds its vendors in the standard folders; NVIDIA's container runtime puts its
# vendor file elsewhere: every folder that has one is listed.
dirs=""
for d in /usr/share/glvnd/egl_vendor.d /etc/glvnd/egl_vendor.d /usr/local/share/glvnd/egl_vendor.d \
         /usr/local/nvidia/share/glvnd/egl_vendor.d; do
    [ -d "$d" ] && dirs="${dirs:+$dirs:}$d"
done
[ -n "$dirs" ] && export __EGL_VENDOR_LIBRARY_DIRS="$dirs"
# The OpenCL drivers the machine registers, plus NVIDIA's when its library is installed but not
# registered (a bare GPU image often lacks /etc/OpenCL/vendors): a folder of .icd files of our own.
icd=$(mktemp -d "${TMPDIR:-/tmp}/hfx-icd.XXXXXX")
trap 'rm -rf "$icd"' EXIT
for f in /etc/OpenCL/vendors/*.icd; do [ -f "$f" ] && cp "$f" "$icd/"; done
if ! grep -qs nvidia "$icd"/*.icd; then
    lib=$(ldconfig -p 2>/dev/null | grep -o '/[^ ]*libnvidia-opencl\.so\.1' | head -1 || true)
    [ -n "$lib" ] || lib=$(ls /usr/local/nvidia/lib64/libnvidia-opencl.so.1 /usr/lib/x86_64-linux-gnu/libnvidia-opencl.so.1 \
                              2>/dev/null | head -1 || true)
    [ -n "$lib" ] && echo "$lib" > "$icd/nvidia.icd"
fi
export OCL_ICD_VENDORS="$icd"
# NVIDIA's Vulkan driver is its GLX library; a container that mounts the library without its
# manifest gets one of ours, added to the loader's list (the external-memory transfer path).
if ! ls /usr/share/vulkan/icd.d/nvidia* /etc/vulkan/icd.d/nvidia* >/dev/null 2>&1; then
    glx=$(ldconfig -p 2>/dev/null | grep -o '/[^ ]*libGLX_nvidia\.so\.0' | head -1 || true)
    if [ -n "$glx" ]; then
        printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s", "api_version": "1.3.0"}}\n' \
            "$glx" > "$icd/nvidia_icd.json"
        export VK_ADD_DRIVER_FILES="$icd/nvidia_icd.json"
    fi
fi
export HFX_SHADER_SOURCE_DIR="$b/shaders"
export HFX_TEST_OUTPUT_DIR="${HFX_TEST_OUTPUT_DIR:-$PWD/hfx-test-output}"
[ $# -ge 1 ] || { echo "usage: run.sh PROGRAM [ARGS...]; programs: $(ls "$b/bin" | tr '\n' ' ')" >&2; exit 2; }
cmd=$1
shift
[ -x "$b/bin/$cmd" ] || { echo "run.sh: no program '$cmd' in $b/bin" >&2; exit 2; }
"$b/bin/$cmd" "$@"
LAUNCHER
chmod +x "$out/run.sh"
echo "bundle: $(du -sh "$out" | cut -f1) in $out ($(ls "$out/lib" | wc -l) libraries)"
