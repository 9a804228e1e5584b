#!/usr/bin/env bash
# Sets up, builds and runs the main job: the water scene, headless where no display exists,
# frames written to out/frames/. Extra arguments go to hfx-demo (try --help).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
if [ $# -eq 0 ]; then
    set -- water --frames 8 --out out/frames
fi
./build/demo/hfx-demo "$@"
