#!/usr/bin/env bash
# Installs every Debian 12 package that Tyndall's build, tests and samples need.
# Idempotent; run as root (or with sudo available). Nothing else is downloaded.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools
  libglm-dev libopencolorio-dev libopenexr-dev libimath-dev libstb-dev
  nlohmann-json3-dev libtinygltf-dev libgtest-dev libgmock-dev
  python3  # scripts/measure.sh's tables, scripts/generate-forest.py
  python3-matplotlib  # scripts/plot-pareto.py: tyndall-bench's plots
  clang libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer with AddressSanitizer and UBSan
  libglvnd0 libglx0 libegl1 libopengl0  # scripts/bundle-binaries.sh: GL dispatch for a GPU's driver
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
if [ ${#missing[@]} -gt 0 ]; then
  "${sudo_cmd[@]}" apt-get update
  "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi

