#!/usr/bin/env bash
# Sets up, builds and runs every test through CTest. Labels: core, cl, gl, demo, package, soak
# (e.g. scripts/test.sh -L cl). Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j2 "$@"
