#!/usr/bin/env bash
# Copies the sample programs (tyndall-render, tyndall-bench, tyndall-compare) and every shared
# library they load beyond the C runtime and the Vulkan driver into one folder, laid out like a
# build folder (DEST/samples/<program>, DEST/lib/), so that the measurement scripts run on a machine
# that has a Vulkan driver but none of the packages scripts/install-deps.sh installs (a GPU
# benchmark box):
#   LD_LIBRARY_PATH=DEST/lib scripts/measure-gpu.sh DEST
# The Vulkan loader (libvulkan.so.1) and glvnd's dispatch libraries are bundled too; the driver
# (its ICD) is the machine's own: on an NVIDIA machine whose ICD file the loader does not find, set
# VK_DRIVER_FILES to it (e.g. /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json) and add the
# driver's library folder (/usr/local/nvidia/lib64) to LD_LIBRARY_PATH.
# The shaders are compiled into the programs, so nothing else is needed besides samples/scenes/.
# Usage: scripts/bundle-binaries.sh [build-dir] [dest] (defaults: build, out/bundle)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
dest="${2:-out/bundle}"
programs=(tyndall-render tyndall-bench tyndall-compare)
for p in "${programs[@]}"; do
  [ -x "$build/samples/$p" ] || { echo "build first: $build/samples/$p not found" >&2; exit 1; }
done
rm -rf "$dest"
mkdir -p "$dest/samples" "$dest/lib"
for p in "${programs[@]}"; do
  cp "$build/samples/$p" "$dest/samples/"
done
# The C runtime (glibc's libraries and the dynamic loader) must be the target machine's own; any
# newer glibc runs these programs. libstdc++ and libgcc_s travel: an older distribution's may lack
# the symbol versions this build needs.
c_runtime='/(libc|libm|libdl|libpthread|librt|ld-linux[^/]*)\.so'
ldd "${programs[@]/#/$build/samples/}" | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u |
  grep -v -E "$c_runtime" | while read -r lib; do cp -L "$lib" "$dest/lib/"; done
# NVIDIA's Vulkan driver (libGLX_nvidia.so.0, named by its ICD file) needs glvnd's dispatch
# libraries, which a bare GPU machine may lack: without them the loader finds no compatible driver
# (VK_ERROR_INCOMPATIBLE_DRIVER). They travel in DEST/lib too; a Mesa driver ignores them.
for lib in libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libOpenGL.so.0; do
  path="$(ldconfig -p | awk -v name="$lib" '$1 == name && /x86-64/ {print $NF; exit}')"
  [ -n "$path" ] || { echo "$lib not found: apt-get install libglvnd0 libglx0 libegl1 libopengl0 (scripts/install-deps.sh)" >&2; exit 1; }
  cp -L "$path" "$dest/lib/"
done
# Every other library must now load from the bundle, not from this machine's system folders.
bundle_lib="$(cd "$dest/lib" && pwd)"
outside="$(LD_LIBRARY_PATH="$bundle_lib" ldd "$dest"/samples/* |
  awk '$2 == "=>" {print $1, $3}' | grep -v -E "$c_runtime" | grep -v -F " $bundle_lib/" || true)"
[ -z "$outside" ] || { echo "not loaded from the bundle:" >&2; echo "$outside" >&2; exit 1; }
echo "bundled ${#programs[@]} programs and $(ls "$dest/lib" | wc -l) libraries ($(du -sh "$dest" | cut -f1)) in $dest"
