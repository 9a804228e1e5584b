#!/usr/bin/env bash
# Installs the Debian packages HFX builds and tests with, and any named as arguments (the checks
# that need more: `bash scripts/setup.sh clang`). Idempotent: when everything is already there it
# checks with dpkg and prints nothing.
set -euo pipefail

packages=(
    build-essential cmake pkg-config python3-glad
    libglm-dev libglfw3-dev libxrandr-dev libosmesa6-dev libgl-dev libegl-dev libegl-mesa0
    ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd
    libopenimageio-dev libstb-dev libtinyexr-dev libvkfft-dev libfftw3-dev libvulkan-dev mesa-vulkan-drivers
    libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev libimgui-dev ffmpeg xvfb xauth
    python3 glslang-tools spirv-tools ccache locales
    "$@"
)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
