#!/usr/bin/env bash
# The long runs alone (they are part of scripts/test.sh too): every user for HFX_SOAK_STEPS
# updates (default 10,000, the planet 4,000) with random parameter changes and stamp storms; prints the resident
# set after warm-up and at the end.
#   HFX_SOAK_STEPS=2000 scripts/soak.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -L soak -V "$@" | grep -E "soak|Passed|Failed|tests passed|Failure|Expected"
