#!/usr/bin/env bash
# Every shader HFX builds, as a GPU's driver would get it, checked by the reference GLSL compiler
# (glslangValidator): Mesa is the only GL this machine has, and a GPU's compiler (NVIDIA's) may
# refuse what Mesa takes; a refused program on a lent GPU costs its short run. The GL tests (but
# Shader.*, which feeds Mesa broken shaders on purpose) and each demo scene run with
# MESA_SHADER_DUMP_PATH, so Mesa writes the text of every stage compiled (defines, #includes and
# all) into build/glsl-dump/; each is then compiled as desktop GLSL by glslangValidator.
#   bash scripts/glsl_check.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
dump=build/glsl-dump
rm -rf "$dump" && mkdir -p "$dump"
export MESA_SHADER_DUMP_PATH=$PWD/$dump
./build/tests/hfx-tests-gl --gtest_filter='-Shader.*' > build/glsl-check-tests.log 2>&1 ||
    { tail -n 40 build/glsl-check-tests.log; echo "glsl: the GL tests failed (build/glsl-check-tests.log)"; exit 1; }
for args in "water" "water --beaufort 10" "decals" "decals --trace-pass compute" "planet --spin-up 0" "noise" \
    "noise --technique pom"; do
    # shellcheck disable=SC2086 # the scene's arguments, split on purpose
    ./build/demo/hfx-demo $args --headless --frames 2 --width 320 --height 180 --field 128 --no-progress \
        --out build/glsl-check-frames > /dev/null 2>&1 || { echo "glsl: hfx-demo $args failed"; exit 1; }
done
unset MESA_SHADER_DUMP_PATH
checked=0 failed=0
for f in "$dump"/*.glsl; do
    case $(basename "$f") in
        VS_*) stage=vert ;; FS_*) stage=frag ;; CS_*) stage=comp ;; GS_*) stage=geom ;;
        TCS_*) stage=tesc ;; TES_*) stage=tese ;; *) continue ;;
    esac
    checked=$((checked + 1))
    if ! out=$(glslangValidator -S "$stage" "$f" 2>&1); then
        failed=$((failed + 1))
        echo "glsl: $f"
        echo "$out" | grep -E "ERROR|WARNING" | head -n 8
    fi
done
echo "glsl: $checked stages checked, $failed refused by glslangValidator"
[ "$checked" -gt 0 ] && [ "$failed" -eq 0 ]
