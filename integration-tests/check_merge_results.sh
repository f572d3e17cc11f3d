#!/usr/bin/env bash
# scripts/lib/merge_results.py (scripts/measure.sh tradeoffs' KEEP_FROM) on the interleaved tiny
# sweep: its directional rows kept from one file and its spot rows from another give back every row
# and the same profile choice as the whole run; a file whose rows share a kind of light with the
# kept ones, or measured with other frame counts, is refused.
# Usage: check_merge_results.sh TYNDALL_BENCH SWEEP_DIR WORK_DIR (absolute paths)
set -euo pipefail
bench="$1"
sweep="$2"
work="$3"
repo="$(cd "$(dirname "$0")/.." && pwd)"
merge="$repo/scripts/lib/merge_results.py"
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$work"
mkdir -p "$work"

# The whole run split by kind of light.
python3 - "$sweep/results.json" "$work" <<'PY'
import json, sys
run = json.load(open(sys.argv[1]))
for name, keep in (("directional", lambda r: r["light"] == "directional"), ("spot", lambda r: r["light"] != "directional")):
    part = dict(run, rows=[r for r in run["rows"] if keep(r)])
    assert part["rows"], f"the tiny sweep has no {name} rows"
    json.dump(part, open(f"{sys.argv[2]}/{name}.json", "w"))
# Spot rows and a directional scene of its own: the kept directional scene's kind mixes runs.
mixed = dict(run, rows=[r for r in run["rows"] if r["light"] != "directional"]
             + [dict(r, scene="another-" + r["scene"]) for r in run["rows"] if r["light"] == "directional"])
json.dump(mixed, open(f"{sys.argv[2]}/mixed.json", "w"))
other = dict(run, frames=run["frames"] + 1, rows=[r for r in run["rows"] if r["light"] != "directional"])
json.dump(other, open(f"{sys.argv[2]}/other-frames.json", "w"))
PY

python3 "$merge" "$work/spot.json" "$work/directional.json" "$work/merged.json"
python3 - "$sweep/results.json" "$work/merged.json" <<'PY'
import json, sys
whole, merged = (json.load(open(p)) for p in sys.argv[1:])
key = lambda r: json.dumps(r, sort_keys=True)
assert sorted(map(key, whole["rows"])) == sorted(map(key, merged["rows"])), "the merge lost or changed rows"
assert "from an earlier run" in merged["command"], merged["command"]
PY
"$bench" --from "$work/merged.json" --out "$work/from-merged" 2>/dev/null
cmp "$sweep/choice.json" "$work/from-merged/choice.json" || fail "the merged run chose other profile rows"

if python3 "$merge" "$work/mixed.json" "$work/directional.json" "$work/refused.json" 2>"$work/mixed.err"; then
  fail "a file with directional rows merged over directional rows"
fi
grep -q "share a kind of light" "$work/mixed.err" || fail "mixed kinds refused without saying why: $(cat "$work/mixed.err")"
if python3 "$merge" "$work/other-frames.json" "$work/directional.json" "$work/refused.json" 2>"$work/frames.err"; then
  fail "runs of other frame counts merged"
fi
grep -q "differ in frames" "$work/frames.err" || fail "other frame counts refused without saying why: $(cat "$work/frames.err")"
echo "merge_results: rows and choice identical to the whole run; mixed kinds and frame counts refused"
