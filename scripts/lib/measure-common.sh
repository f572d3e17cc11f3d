# shellcheck shell=bash
# Sourced by scripts/measure.sh and scripts/measure-gpu.sh: what every measurement part needs once.

# The program `name` of build folder `build` (a build, or a scripts/bundle-binaries.sh bundle), or a
# clear error.
program() {
  local path="$1/samples/$2"
  [ -x "$path" ] || { echo "build first: $path not found" >&2; exit 1; }
  echo "$path"
}

# Width and height of WxH.
width_of() { echo "${1%x*}"; }
height_of() { echo "${1#*x}"; }

# A scene name from samples/scenes/ or a scene file: its file, then its name.
scene_file() { case "$1" in *.json) echo "$1" ;; *) echo "samples/scenes/$1.json" ;; esac; }
scene_name() { basename "$1" .json; }

# The Python that draws the plots: PYTHON if set, else the first python3 on PATH that has
# matplotlib (a pyenv or virtualenv python3 may lack Debian's python3-matplotlib); none is an error.
plot_python() {
  local candidates=("${PYTHON:-}")
  [ -n "${PYTHON:-}" ] || mapfile -t candidates < <(type -ap python3)
  for python in "${candidates[@]}"; do
    if "$python" -c 'import matplotlib' 2>/dev/null; then
      echo "$python"
      return
    fi
  done
  echo "no python3 with matplotlib (${candidates[*]:-none on PATH}): apt-get install python3-matplotlib" \
    "(scripts/install-deps.sh), or set PYTHON" >&2
  exit 1
}
