#!/usr/bin/env bash
# Renders the README's gallery: one 1280x720 picture of each scene, headless, at the scenes'
# default grazing cameras, after enough frames for the field to develop (the decal volley, the
# planet's storms). Writes docs/gallery/{water,decals,planet}.jpg.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p docs/gallery
render() { # scene frames [options...]
    local scene=$1 frames=$2
    shift 2
    ./build/demo/hfx-demo "$scene" --headless --frames "$frames" --format jpg --out "$work/$scene" "$@"
    cp "$(ls "$work/$scene"/*.jpg | tail -n 1)" "docs/gallery/$scene.jpg"
}
render water 30
render decals 36
render planet 120
ls -l docs/gallery
