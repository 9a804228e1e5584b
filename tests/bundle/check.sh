#!/usr/bin/env bash
# CTest's Bundle.TheBundlesDemoRendersOutsideTheTree: builds the bundle (scripts/bundle.sh) into
# WORK, checks that its binaries load no library from outside it but the C runtime and the
# drivers, then renders one frame and runs the core tests from a folder outside the tree, in a
# clean environment, through its launcher.
#   check.sh SOURCE_DIR WORK_DIR [BUILD_DIR]
# BUILD_DIR (default WORK_DIR/build): the bundle's build tree, made afresh; beside the main tree,
# at its depth, the compiler cache serves it the main tree's objects (CMakeLists.txt).
set -euo pipefail
src=$1 work=$2 build=${3:-$2/build}
rm -rf "$work" "$build"
mkdir -p "$work"
# Only the programs it runs: the others are the same sources, built and tested in the main tree.
HFX_BUNDLE_BUILD="$build" HFX_BUNDLE_TARGETS="hfx-demo hfx-tests-core" bash "$src/scripts/bundle.sh" "$work/bundle"
bundle="$work/bundle"
runtime='^(linux-vdso|ld-linux|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|libstdc\+\+\.so|libgcc_s\.so)'
for b in "$bundle"/bin/*; do
    if LD_LIBRARY_PATH="$bundle/lib" ldd "$b" | grep -q "not found"; then
        echo "$(basename "$b") misses libraries:"; LD_LIBRARY_PATH="$bundle/lib" ldd "$b" | grep "not found"; exit 1
    fi
    LD_LIBRARY_PATH="$bundle/lib" ldd "$b" | awk '$3 ~ /^\// {print $1, $3}' | while read -r name path; do
        [[ $name =~ $runtime || $path == "$bundle/lib/"* ]] || { echo "$(basename "$b") loads $path from outside the bundle"; exit 1; }
    done
done
if ls "$bundle/lib" | grep -qi -E 'OpenImageIO|LLVM'; then echo "a heavy library is in the bundle"; exit 1; fi
outside=$(mktemp -d "${TMPDIR:-/tmp}/hfx-bundle-run.XXXXXX")
trap 'rm -rf "$outside"' EXIT
cd "$outside"
env -i PATH=/usr/bin:/bin HOME="$outside" bash "$bundle/run.sh" hfx-demo noise --headless --frames 1 --width 160 \
    --height 90 --field 64 --out "$outside/frames" 2>&1 | tee "$outside/demo.log"
[ -s "$outside/frames/noise_0000.png" ] || { echo "the bundle's demo wrote no frame"; exit 1; }
grep -q "hfx: GL EGL" "$outside/demo.log" || { echo "the bundle's demo did not render through EGL"; exit 1; }
env -i PATH=/usr/bin:/bin HOME="$outside" bash "$bundle/run.sh" hfx-tests-core --gtest_brief=1
echo "bundle: $(du -sh "$bundle" | cut -f1), $(ls "$bundle/lib" | wc -l) libraries; a frame and the core tests ran from $outside"
