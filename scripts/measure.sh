#!/usr/bin/env bash
# The measurements behind the documents, one part per command; each runs on whatever Vulkan device
# is present (TYNDALL_DEVICE picks one) from the programs of a build folder (or a
# scripts/bundle-binaries.sh bundle). scripts/measure-gpu.sh runs several parts in one GPU session.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/measure-common.sh

usage() {
  cat <<'USAGE'
usage: scripts/measure.sh PART [build-dir]      (build-dir: default build; extremes: build-tests)

tradeoffs    tyndall-bench's default sweep (every sample scene but the analytic ones, the default
             grid of the epipolar and prefiltered techniques, against the Reference and the floor
             pass), then its plots (scripts/plot-pareto.py, matplotlib); copies the document and
             plots into docs/ and its tables into docs/measurements/tradeoffs-lavapipe.md (for
             DOC=docs/TRADEOFFS-NAME.md: tradeoffs-name.md); for the profile table's document
             (docs/TRADEOFFS-H200.md: the table comes from a GPU's sweep) its choice and rows to
             docs/data/profile-table-{choice,results}.json (the profile table's test reads them), for
             docs/TRADEOFFS.md its rows to docs/data/tradeoffs-lavapipe-results.json.
             SIZES (1280x720: where users run it), SHADOW_MAPS (2048), FRAMES (20), SCENES (the bench's default),
             BENCH_OUT (out/tradeoffs); FROM=RESULTS.json writes the document again from an earlier
             run without measuring (FROM=docs/data/tradeoffs-lavapipe-results.json: the run
             docs/TRADEOFFS.md shows); KEEP_FROM=RESULTS.json measures only SCENES and takes the
             other scenes' rows from that earlier run (every scene of a kind of light must be
             measured again together: a profile row is chosen over its kind's scenes; the run's
             results.json is then the merged file); DOC (docs/TRADEOFFS.md, lavapipe's; another path
             keeps another device's run beside it: docs/TRADEOFFS-H200.md, whose choice is the
             code's profile table, FROM=docs/data/profile-table-results.json writes it again);
             PYTHON (the first python3 on PATH with matplotlib).
             On a GPU pass SIZES=1920x1080 SHADOW_MAPS=2048 for the issue's goals.
prefiltered  The prefiltered technique against the Reference: per storage variant and scene the
             relative RMSE of L_in, each pass's GPU time and the speedup over the Reference, then
             the evaluation's spread over the scenes. Prints a table; writes MEASURE_OUT
             (out/measure-prefiltered). SCENES (the directional scenes; names or scene files),
             BASES (all six), SIZE (640x360), SHADOW_MAP (1024), FRAMES (3), PREFILTERED (extra
             --prefiltered keys), REFERENCE_FROM (an earlier MEASURE_OUT with the same SIZE,
             SHADOW_MAP and FRAMES: its Reference renders are used instead of rendering them again).
cost         The prefiltered evaluation's cost against the one-lookup evaluation: the prefiltered
             part over the directional sample scenes and generated forests with the defaults and
             with one lookup, scene by scene back to back (the second against the first's Reference
             renders), each followed by the spread over the sample scenes and over the forests,
             then the defaults' evaluation time over one lookup's per scene and its maximum (issue
             42 asks at most 2x). Writes COST_OUT (out/cost-independence)/{forest-S.json,
             defaults.md,one-lookup.md,bound.md}. SIZE (640x360), SHADOW_MAP (2048), FRAMES (3),
             BASES (moments6_64), SCENES (pillars fence forest window-room analytic-spheres
             analytic-boxes analytic-mixed gltf-tetrahedron), SPACINGS (the forests' grid
             spacings, 16 8 4 1.4 1).
epipolar     The epipolar technique's profiles against the Reference in the same run: per scene,
             size and map, each pass's GPU time, speedup, relative RMSE, marched samples. Prints two
             tables; writes BENCH_OUT (out/bench-epipolar), rows.jsonl among them. SCENES (pillars
             forest window-room spot-lamp), SIZES (1280x720 1920x1080), SHADOW_MAPS (2048 4096),
             PROFILES (high balanced performance), RESOLUTIONS (full; any of full half quarter: each
             profile also at that resolution, tyndall-render --resolution), CASCADES (0: each scene's
             own; K: --cascades K for every render, e.g. "4 1" for colonnade), FRAMES (12),
             REFERENCE_FRAMES (4), RENDER and COMPARE (the programs, default the build's).
spot         The profiles against the Reference on the spot-light scenes and on each with its lamp a
             point light (same place, same occluders): relative RMSE of L_in per scene, size and
             profile, against the per-scene bars. Writes SPOT_OUT (out/spot-accuracy) and, with the
             default SCENES, SIZES and MAP, docs/measurements/spot-accuracy-lavapipe.md. SCENES
             (spot-lamp stained-glass spot-fan spot-fan-up spot-fan-narrow spot-fan-close spot-grille
             spot-lattice spot-foliage spot-street gltf-pergola-lamp), SIZES
             (320x180 480x270), MAP (2048), PROFILES (high balanced performance), FRAMES (3),
             POINT (1; 0 leaves out the point-light variants, whose Reference is slow on lavapipe),
             EPIPOLAR_HIGH, EPIPOLAR_BALANCED, EPIPOLAR_PERFORMANCE (a profile's run with these
             --epipolar settings instead of its row: every key the row sets, plus the ones tried),
             REFERENCE_FROM (an earlier SPOT_OUT with the same SIZES and MAP: its Reference renders
             are used instead of rendering them again).
reference    The Reference's GPU time per pass and wall-clock time per frame. Prints a table; writes
             REFERENCE_OUT (out/measure). SCENES (pillars), SIZES (640x360 1280x720), FRAMES (4).
translucent  The Reference's cost with translucent layers: per scene, its scattering pass with each
             layer count against the same scene with its translucent objects made opaque (same
             geometry, no layers), in one run. Prints a table; writes TRANSLUCENT_OUT
             (out/measure-translucent). SCENES (analytic-glass; scene files without glTF objects),
             LAYERS (1 4 8), SIZE (320x180), SHADOW_MAP (2048), FRAMES (3).
memory       Device memory a context holds per profile and size (Stats::deviceMemoryBytes after one
             frame). Prints a table; writes MEMORY_OUT (out/memory-footprint). SCENES (pillars
             spot-lamp), SIZES (1280x720 1920x1080 3840x2160), PROFILES (reference high balanced
             performance), RESOLUTIONS (full; each profile also at half or quarter with
             tyndall-render --resolution), SHADOW_MAP (2048).
extremes     Runs the extremes suite (build-dir/integration-tests/tyndall_extremes_tests, on
             TYNDALL_DEVICE, default llvmpipe) and writes docs/EXTREMES.md from what it prints; exits
             with the suite's status.
USAGE
}

# tradeoffs: tyndall-bench, its plots, and the document and plots copied into docs/.
part_tradeoffs() {
  local bench out doc python tables
  bench="$(program "$1" tyndall-bench)"
  python="$(plot_python)"
  out="${BENCH_OUT:-out/tradeoffs}"
  # Plots of an earlier run in the same folder (another size) would otherwise be copied to docs/.
  rm -f "$out"/pareto-*.svg "$out"/pareto-*.png
  doc="${DOC:-docs/TRADEOFFS.md}"
  # The document's tables: docs/TRADEOFFS[-X].md's go to docs/measurements/tradeoffs-lavapipe[x].md.
  case "$(basename "$doc" .md)" in
    TRADEOFFS) tables=tradeoffs-lavapipe.md ;;
    TRADEOFFS-*) tables="tradeoffs-$(basename "$doc" .md | cut -d- -f2- | tr '[:upper:]' '[:lower:]').md" ;;
    *) echo "DOC must be docs/TRADEOFFS.md or docs/TRADEOFFS-NAME.md (got $doc)" >&2; exit 1 ;;
  esac
  local link=(--measurements-link "measurements/$tables")
  if [ -n "${FROM:-}" ]; then
    "$bench" --from "$FROM" --out "$out" "${link[@]}"
  else
    local args=(--sizes "${SIZES:-1280x720}" --shadow-maps "${SHADOW_MAPS:-2048}" --frames "${FRAMES:-20}" --out "$out")
    [ -n "${SCENES:-}" ] && args+=(--scenes "$SCENES")
    "$bench" "${args[@]}" "${link[@]}"
    if [ -n "${KEEP_FROM:-}" ]; then
      [ -n "${SCENES:-}" ] || { echo "KEEP_FROM needs SCENES: the scenes to measure again" >&2; exit 1; }
      "$python" scripts/lib/merge_results.py "$out/results.json" "$KEEP_FROM" "$out/merged-results.json"
      "$bench" --from "$out/merged-results.json" --out "$out" "${link[@]}"
    fi
  fi
  "$python" scripts/plot-pareto.py "$out/pareto.json" "$out" >/dev/null
  cp "$out/tradeoffs-measurements.md" "docs/measurements/$tables"
  # The profile table comes from the GPU's sweep where users run it (plugin/src/profiles.cpp).
  local table_doc=docs/TRADEOFFS-H200.md
  if [ "$doc" = "$table_doc" ]; then
    cp "$out/tradeoffs.md" "$doc"
    cp "$out/choice.json" docs/data/profile-table-choice.json
    # The run shown, for FROM and KEEP_FROM (the same file when FROM is it).
    if [ -z "${FROM:-}" ] || [ "$(realpath -m "$FROM")" != "$(realpath -m docs/data/profile-table-results.json)" ]; then
      cp "$out/results.json" docs/data/profile-table-results.json
    fi
  else
    # Another device's or size's run: its choice is a measurement, not the code's profile table.
    { head -n 1 "$out/tradeoffs.md"
      printf '\n> A run on another device or size than %s, kept for its measurements: its "choice" is what this run would pick, not `plugin/src/profiles.cpp`'"'"'s table (%s is). Written by `DOC=%s scripts/measure.sh tradeoffs` (with `FROM=results.json` of a run on that device, or run there with SIZES and SHADOW_MAPS).\n' "$table_doc" "$table_doc" "$doc"
      tail -n +2 "$out/tradeoffs.md"; } >"$doc"
    if [ "$doc" = docs/TRADEOFFS.md ] && [ -z "${FROM:-}" ]; then
      cp "$out/results.json" docs/data/tradeoffs-lavapipe-results.json  # the run shown, for FROM and KEEP_FROM
    fi
  fi
  cp "$out"/pareto-*.svg "$out"/pareto-*.png docs/
  echo "wrote $doc, docs/measurements/$tables and docs/pareto-*.svg/.png from $out"
}

# The Reference render NAME.{exr,json} of scene FILE at W x H with a MAP² map over FRAMES frames, its
# path without the extension left in `ref`: REFERENCE_FROM's (an earlier run's folder, which must
# hold it) when set, else rendered into the caller's $out with the caller's $render.
reference_render() {
  local name="$1" file="$2" w="$3" h="$4" map="$5" frames="$6"
  if [ -n "${REFERENCE_FROM:-}" ]; then
    ref="$REFERENCE_FROM/$name"
    [ -f "$ref.exr" ] && [ -f "$ref.json" ] || { echo "no Reference render $ref.{exr,json}" >&2; exit 1; }
  else
    ref="$out/$name"
    "$render" --pipelines on-first-use "$file" --technique reference --width "$w" --height "$h" \
      --shadow-map-size "$map" --frames "$frames" --timings "$ref.json" --aov-scattering "$ref.exr" >/dev/null
  fi
}

# prefiltered: per scene the Reference (or REFERENCE_FROM's), then every variant against it.
part_prefiltered() {
  local render compare out size w h map frames extra evaluations entry file scene ref basis run
  render="$(program "$1" tyndall-render)"
  compare="$(program "$1" tyndall-compare)"
  out="${MEASURE_OUT:-out/measure-prefiltered}"
  mkdir -p "$out"
  size="${SIZE:-640x360}"
  w="$(width_of "$size")"; h="$(height_of "$size")"
  map="${SHADOW_MAP:-1024}"
  frames="${FRAMES:-3}"
  extra="${PREFILTERED:-}"
  evaluations="$out/evaluations-$size.tsv"  # variant, scene, evaluate ms: the spread below
  # MEASURE_APPEND: more rows of an earlier call's table (the cost part, one scene per call).
  if [ -z "${MEASURE_APPEND:-}" ]; then
    printf '| scene | variant | relative RMSE | moment map | rectify | prefix sums | evaluate | epipole block | prefiltered total ms | Reference ms | speedup |\n'
    printf '|---|---|---|---|---|---|---|---|---|---|---|\n'
    : >"$evaluations"
  fi
  for entry in ${SCENES:-pillars fence forest window-room analytic-spheres analytic-boxes analytic-mixed}; do
    file="$(scene_file "$entry")"; scene="$(scene_name "$entry")"
    reference_render "$scene-$size-reference" "$file" "$w" "$h" "$map" "$frames"
    for basis in ${BASES:-moments4_64 moments4_128 moments6_64 moments6_96 moments6_192 fourier32}; do
      run="$out/$scene-$size-$basis"
      "$render" --pipelines on-first-use "$file" --technique prefiltered --prefiltered "basis=$basis${extra:+,$extra}" \
        --width "$w" --height "$h" --shadow-map-size "$map" --frames "$frames" --timings "$run.json" \
        --aov-scattering "$run.exr" >/dev/null
      "$compare" "$run.exr" "$ref.exr" >"$run-error.json"
      python3 scripts/lib/measure_tables.py prefiltered-row "$run.json" "$run-error.json" "$ref.json" "$scene" "$basis" \
        "$evaluations"
    done
  done
  [ -n "${MEASURE_APPEND:-}" ] && return
  echo
  python3 scripts/lib/measure_tables.py spread "$evaluations"
}

# cost: the prefiltered part twice (defaults, one lookup) over the sample scenes and the forests,
# then the defaults' evaluation over one lookup's per scene.
part_cost() {
  local out scenes spacing run extra reference_from evaluations scene
  out="${COST_OUT:-out/cost-independence}"
  mkdir -p "$out/defaults" "$out/one-lookup"
  scenes="${SCENES:-pillars fence forest window-room analytic-spheres analytic-boxes analytic-mixed gltf-tetrahedron}"
  for spacing in ${SPACINGS:-16 8 4 1.4 1}; do
    python3 scripts/generate-forest.py --spacing "$spacing" --out "$out/forest-$spacing.json" >/dev/null
    scenes+=" $out/forest-$spacing.json"
  done
  export SIZE="${SIZE:-640x360}" SHADOW_MAP="${SHADOW_MAP:-2048}" FRAMES="${FRAMES:-3}" BASES="${BASES:-moments6_64}"
  # PrefilteredSettings with every per-ray decision off: klehm2014 and peters2017's evaluation.
  local one_lookup="taps=1,segments=0,depth-bounds=0,trim=0,texel-walk=0,short-rays=0"
  for run in defaults one-lookup; do
    : >"$out/$run/evaluations-$SIZE.tsv"
    { printf '| scene | variant | relative RMSE | moment map | rectify | prefix sums | evaluate | epipole block | prefiltered total ms | Reference ms | speedup |\n'
      printf '|---|---|---|---|---|---|---|---|---|---|---|\n'; } >"$out/$run.md"
  done
  # Scene by scene, the two runs back to back, so that a device whose speed drifts (a CPU driver
  # on a shared machine) times both alike; the second compares against the first's Reference.
  for scene in $scenes; do
    for run in defaults one-lookup; do
      extra=""; reference_from=""
      [ "$run" = one-lookup ] && extra="$one_lookup" && reference_from="$out/defaults"
      (MEASURE_OUT="$out/$run" MEASURE_APPEND=1 SCENES="$scene" PREFILTERED="$extra" REFERENCE_FROM="$reference_from" \
        part_prefiltered "$1") >>"$out/$run.md"
    done
  done
  for run in defaults one-lookup; do
    extra=""; [ "$run" = one-lookup ] && extra=" ($one_lookup)"
    evaluations="$out/$run/evaluations-$SIZE.tsv"
    { echo; python3 scripts/lib/measure_tables.py spread "$evaluations" --exclude-prefix forest- --title "the sample scenes"
      python3 scripts/lib/measure_tables.py spread "$evaluations" --prefix forest --title "the forests (forest is spacing 2)"
    } >>"$out/$run.md"
    echo "## $run$extra"; cat "$out/$run.md"; echo
  done
  echo "## the defaults' evaluation over one lookup's"
  python3 scripts/lib/measure_tables.py bound "$out/defaults/evaluations-$SIZE.tsv" "$out/one-lookup/evaluations-$SIZE.tsv" |
    tee "$out/bound.md"
}

# epipolar: per scene, size and map the Reference, then each profile against it.
part_epipolar() {
  local render compare out frames reference_frames rows first_scene first_size scene size w h map ref profile run
  local resolution label reduced cascades cascaded
  render="${RENDER:-$(program "$1" tyndall-render)}"
  compare="${COMPARE:-$(program "$1" tyndall-compare)}"
  out="${BENCH_OUT:-out/bench-epipolar}"
  mkdir -p "$out"
  frames="${FRAMES:-12}"
  reference_frames="${REFERENCE_FRAMES:-4}"
  rows="$out/rows.jsonl"
  : >"$rows"
  # Warm-up, discarded: a GPU's clocks ramp up over its first busy moments, so the first timed run
  # is slow.
  first_scene="$(set -- ${SCENES:-pillars}; echo "$1")"
  first_size="$(set -- ${SIZES:-1280x720}; echo "$1")"
  "$render" --pipelines on-first-use "samples/scenes/$first_scene.json" --technique reference \
    --width "$(width_of "$first_size")" --height "$(height_of "$first_size")" --frames 2 >/dev/null
  for scene in ${SCENES:-pillars forest window-room spot-lamp}; do
    for size in ${SIZES:-1280x720 1920x1080}; do
      w="$(width_of "$size")"; h="$(height_of "$size")"
      for map in ${SHADOW_MAPS:-2048 4096}; do
        for cascades in ${CASCADES:-0}; do
          # CASCADES: --cascades K for every render (a directional light's cascades), 0 the scene's.
          cascaded=() ref="$out/$scene-$size-$map-reference"
          if [ "$cascades" != 0 ]; then
            cascaded=(--cascades "$cascades") ref="$out/$scene-$size-${cascades}x$map-reference"
          fi
          "$render" --pipelines on-first-use "samples/scenes/$scene.json" --technique reference --width "$w" --height "$h" \
            --shadow-map-size "$map" "${cascaded[@]}" --frames "$reference_frames" --timings "$ref.json" \
            --aov-scattering "$ref.exr" >/dev/null
          for profile in ${PROFILES:-high balanced performance}; do
            for resolution in ${RESOLUTIONS:-full}; do
              # A reduced resolution is named in the tables after the profile ("performance half").
              label="$profile" run="${ref%-reference}-$profile" reduced=()
              if [ "$resolution" != full ]; then
                label="$profile $resolution" run="$run-$resolution" reduced=(--resolution "$resolution")
              fi
              "$render" --pipelines on-first-use "samples/scenes/$scene.json" --profile "$profile" --width "$w" --height "$h" \
                --shadow-map-size "$map" "${cascaded[@]}" --frames "$frames" --timings "$run.json" \
                --aov-scattering "$run.exr" "${reduced[@]}" >/dev/null
              "$compare" "$run.exr" "$ref.exr" >"$run-error.json"
              python3 scripts/lib/measure_tables.py epipolar-row "$run.json" "$run-error.json" "$ref.json" "$scene" "$size" \
                "$map" "$label" --cascades "$cascades" >>"$rows"
            done
          done
        done
      done
    done
  done
  python3 scripts/lib/measure_tables.py epipolar-tables "$rows"
}

# spot: per spot scene (and its point-light variant), size and profile the error against the Reference.
part_spot() {
  local render compare out rows map frames scene file size w h light ref profile run doc keys
  local default_scenes="spot-lamp stained-glass spot-fan spot-fan-up spot-fan-narrow spot-fan-close spot-grille"
  default_scenes+=" spot-lattice spot-foliage spot-street gltf-pergola-lamp"
  render="$(program "$1" tyndall-render)"
  compare="$(program "$1" tyndall-compare)"
  out="${SPOT_OUT:-out/spot-accuracy}"
  mkdir -p "$out"
  map="${MAP:-2048}"
  frames="${FRAMES:-3}"
  rows="$out/rows.jsonl"
  : >"$rows"
  for scene in ${SCENES:-$default_scenes}; do
    for light in spot point; do
      [ "$light" = point ] && [ "${POINT:-1}" = 0 ] && continue
      file="samples/scenes/$scene.json"
      if [ "$light" = point ]; then
        file="$out/$scene-point.json"
        python3 scripts/lib/measure_tables.py point-variant "samples/scenes/$scene.json" "$file"
      fi
      for size in ${SIZES:-320x180 480x270}; do
        w="$(width_of "$size")"; h="$(height_of "$size")"
        reference_render "$scene-$light-$size-reference" "$file" "$w" "$h" "$map" 1
        for profile in ${PROFILES:-high balanced performance}; do
          run="$out/$scene-$light-$size-$profile"
          keys="EPIPOLAR_${profile^^}"
          keys="${!keys:-}"
          "$render" --pipelines on-first-use "$file" --profile "$profile" ${keys:+--epipolar "$keys"} \
            --width "$w" --height "$h" --shadow-map-size "$map" --frames "$frames" --timings "$run.json" \
            --aov-scattering "$run.exr" >/dev/null
          "$compare" "$run.exr" "$ref.exr" --error-png "$run-error.png" >"$run-error.json"
          python3 scripts/lib/measure_tables.py epipolar-row "$run.json" "$run-error.json" "$ref.json" "$scene" \
            "$size" "$map" "$profile" | sed "s/^{/{\"light\": \"$light\", /" >>"$rows"
        done
      done
    done
  done
  python3 scripts/lib/measure_tables.py spot-tables "$rows" | tee "$out/spot-accuracy.md"
  if [ -z "${SCENES:-}${SIZES:-}${MAP:-}${PROFILES:-}${EPIPOLAR_HIGH:-}${EPIPOLAR_BALANCED:-}${EPIPOLAR_PERFORMANCE:-}" ] &&
    [ "${POINT:-1}" != 0 ]; then
    doc=docs/measurements/spot-accuracy-lavapipe.md
    { printf '# Spot lights: the profiles against the Reference per scene, with the point-light variant\n\n'
      printf 'Command:\n\n    TYNDALL_DEVICE=%s scripts/measure.sh spot\n\n' "${TYNDALL_DEVICE:-(default)}"
      printf 'Date: %s, commit %s. Shadow map %s², %s frames per profile run.\n\n' "$(date -u +%Y-%m-%d)" \
        "$(git rev-parse --short HEAD 2>/dev/null || echo unknown)" "$map" "$frames"
      cat "$out/spot-accuracy.md"; } >"$doc"
    echo "wrote $doc"
  fi
}

# reference: the Reference profile's timings per scene and size.
part_reference() {
  local render out scene size json
  render="$(program "$1" tyndall-render)"
  out="${REFERENCE_OUT:-out/measure}"
  mkdir -p "$out"
  printf '| scene | size | shadow map | reference_scattering ms | composite ms | Tyndall total ms | frame wall ms |\n'
  printf '|---|---|---|---|---|---|---|\n'
  for scene in ${SCENES:-pillars}; do
    for size in ${SIZES:-640x360 1280x720}; do
      json="$out/$scene-$size.json"
      "$render" --pipelines on-first-use "samples/scenes/$scene.json" --profile reference --width "$(width_of "$size")" \
        --height "$(height_of "$size")" --shadow-map-size 2048 --frames "${FRAMES:-4}" --timings "$json" >/dev/null
      python3 scripts/lib/measure_tables.py reference-row "$json" "$scene" "$size"
    done
  done
}

# translucent: the Reference with translucent layers against the same scene made opaque.
part_translucent() {
  local render out size map frames entry file name opaque layers json
  render="$(program "$1" tyndall-render)"
  out="${TRANSLUCENT_OUT:-out/measure-translucent}"
  size="${SIZE:-320x180}"
  map="${SHADOW_MAP:-2048}"
  frames="${FRAMES:-3}"
  mkdir -p "$out"
  run() {  # scene file, timings file, extra arguments
    "$render" --pipelines on-first-use "$1" --profile reference --width "$(width_of "$size")" \
      --height "$(height_of "$size")" --shadow-map-size "$map" --frames "$frames" --timings "$2" "${@:3}" >/dev/null
  }
  printf '| scene | size | map | translucent layers | reference_scattering ms | against opaque |\n|---|---|---|---|---|---|\n'
  for entry in ${SCENES:-analytic-glass}; do
    file="$(scene_file "$entry")"
    name="$(scene_name "$file")"
    opaque="$out/$name-opaque.json"
    python3 -c 'import json, sys
scene = json.load(open(sys.argv[1]))
for o in scene["objects"]: o.pop("opacity", None)
json.dump(scene, open(sys.argv[2], "w"))' "$file" "$opaque"
    run "$opaque" "$out/$name-opaque-timings.json"
    python3 scripts/lib/measure_tables.py translucent-row "$out/$name-opaque-timings.json" \
      "$out/$name-opaque-timings.json" "$name" "$size" "$map" "0 (opaque)"
    for layers in ${LAYERS:-1 4 8}; do
      json="$out/$name-$layers.json"
      run "$file" "$json" --translucent-layers "$layers"
      python3 scripts/lib/measure_tables.py translucent-row "$json" "$out/$name-opaque-timings.json" "$name" \
        "$size" "$map" "$layers"
    done
  done
}

# memory: one frame per profile, scene and size in a fresh context.
part_memory() {
  local render out map sizes size scene profile cells run technique mib resolution label name reduced
  render="$(program "$1" tyndall-render)"
  out="${MEMORY_OUT:-out/memory-footprint}"
  mkdir -p "$out"
  map="${SHADOW_MAP:-2048}"
  sizes="${SIZES:-1280x720 1920x1080 3840x2160}"
  printf '| scene | profile | technique |'
  for size in $sizes; do printf ' %s MiB |' "$size"; done
  printf '\n|---|---|---|'
  for size in $sizes; do printf -- '---|'; done
  printf '\n'
  for scene in ${SCENES:-pillars spot-lamp}; do
    for profile in ${PROFILES:-reference high balanced performance}; do
      for resolution in ${RESOLUTIONS:-full}; do
        cells="" label="$profile" name="$profile" reduced=()
        if [ "$resolution" != full ]; then
          label="$profile $resolution" name="$profile-$resolution" reduced=(--resolution "$resolution")
        fi
        for size in $sizes; do
          run="$out/$scene-$size-$name.json"
          "$render" "samples/scenes/$scene.json" --profile "$profile" --width "$(width_of "$size")" \
            --height "$(height_of "$size")" --shadow-map-size "$map" --frames 1 --timings "$run" \
            --output "$out/$scene-$size-$name.png" "${reduced[@]}" >/dev/null
          # The technique is the profile's, the same at every size: the last run's is printed.
          read -r technique mib < <(python3 scripts/lib/measure_tables.py memory-cell "$run")
          cells="$cells $mib |"
        done
        printf '| %s | %s | %s |%s\n' "$scene" "$label" "$technique" "$cells"
      done
    done
  done
}

# extremes: the suite, then docs/EXTREMES.md from its log; the suite's status is the part's.
part_extremes() {
  local binary="$1/integration-tests/tyndall_extremes_tests" log status=0
  [ -x "$binary" ] || { echo "build the tests first: $binary not found" >&2; exit 1; }
  log="$(mktemp)"
  TYNDALL_DEVICE="${TYNDALL_DEVICE:-llvmpipe}" "$binary" >"$log" 2>&1 || status=$?
  python3 scripts/lib/extremes_report.py "$log" "$status" >docs/EXTREMES.md
  rm -f "$log"
  echo "wrote docs/EXTREMES.md (suite exit status $status)"
  return "$status"
}

part="${1:-}"
case "$part" in
  tradeoffs | prefiltered | cost | epipolar | spot | reference | translucent | memory) "part_$part" "${2:-build}" ;;
  extremes) part_extremes "${2:-build-tests}" ;;
  -h | --help) usage ;;
  *) usage >&2; [ -z "$part" ] || echo "unknown part: $part" >&2; exit 2 ;;
esac
