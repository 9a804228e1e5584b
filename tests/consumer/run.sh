#!/usr/bin/env bash
# Installs HFX from BUILD into WORK/prefix, builds the consumer project against it, runs it.
#   run.sh BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1 source=$2 work=$3
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work.install.log" 2>&1 || { cat "$work.install.log"; exit 1; }
cmake -S "$source" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" -Wno-dev
cmake --build "$work/build" -j2
# The installed tree alone: no path into HFX's sources or build may be needed.
if grep -rq "$(cd "$source/../.." && pwd)" "$work/prefix/lib/cmake/hfx"; then
    echo "the installed package config refers to the source tree"; exit 1
fi
# hfx::hfx is GL-only: neither its exported targets nor the consumer's link mention GLFW.
if grep -qi "glfw" "$work/prefix/lib/cmake/hfx/hfxTargets.cmake"; then
    echo "hfx::hfx's exported targets link GLFW"; exit 1
fi
if grep -rqi "glfw" "$work/build/CMakeFiles/hfx-consumer.dir/link.txt" || ldd "$work/build/hfx-consumer" | grep -qi glfw; then
    echo "the consumer links GLFW through hfx::hfx"; exit 1
fi
"$work/build/hfx-consumer"
