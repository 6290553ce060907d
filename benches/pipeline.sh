#!/usr/bin/env bash
# Whole-pipeline figures of the sherd command: CPU seconds (user + sys), wall time and
# peak memory (max RSS) of each step on synthetic scans, from /usr/bin/time -v, and the
# batch throughput estimated from CPU time (the machine is shared: wall time depends on
# the load, printed beside). Prints Markdown tables for BENCHMARKS.md.
#
#   bash benches/pipeline.sh            # 500k-face rim scan (seed 200: oriented) + batch of 100 sherds of 200k faces
#   SHERD_BATCH_COUNT=20 bash benches/pipeline.sh   # a shorter batch
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin sherd
# The binary cargo just built, wherever CARGO_TARGET_DIR puts it (relative to the root).
target_dir=${CARGO_TARGET_DIR:-target}
case $target_dir in /*) ;; *) target_dir=$(pwd)/$target_dir ;; esac
sherd=$target_dir/release/sherd
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
count=${SHERD_BATCH_COUNT:-100}

measure() { # label, command...: prints "| label | CPU s | wall s | peak MiB | load |"
  local label=$1; shift
  /usr/bin/time -v -o "$work/time" "$@" >/dev/null 2>"$work/stderr" || [ "${ALLOW_EXIT_1:-0}" = 1 ] || { cat "$work/stderr"; exit 1; }
  local user sys wall kib
  user=$(awk -F': ' '/User time/ {print $2}' "$work/time")
  sys=$(awk -F': ' '/System time/ {print $2}' "$work/time")
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$work/time" | awk -F: '{s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; print s}')
  kib=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time")
  cpu=$(echo "$user + $sys" | bc)
  printf '| %s | %.2f | %.2f | %.0f | %s |\n' "$label" "$cpu" "$wall" "$((kib / 1024))" "$(cut -d' ' -f1-3 /proc/loadavg)"
}

"$sherd" synth -o "$work/big" --count 1 --seed 200 --faces 500000 --part rim >/dev/null
big=$(ls "$work"/big/*.ply | head -n 1)
echo "| step (500k-face scan: $(basename "$big")) | CPU s | wall s | peak MiB | load (1, 5, 15 min) |"
echo "|---|---|---|---|---|"
measure "sherd info" "$sherd" info "$big"
measure "sherd orient --json (read, repair, orient, refine, measure)" "$sherd" orient "$big" --json
"$sherd" orient "$big" --json >"$work/axis.json"
if grep -q '"status": "\(ok\|axis_uncertain\)"' "$work/axis.json"; then
  measure "sherd draw --axis (linear)" "$sherd" draw "$big" --axis "$work/axis.json" -o "$work/big.svg"
  measure "sherd draw --axis (all styles, PNG 300 dpi)" "$sherd" draw "$big" --axis "$work/axis.json" --style linear,colour,light,occlusion,stipple,regularity -o "$work/big.png"
  measure "sherd draw (whole pipeline, linear, SVG)" "$sherd" draw "$big" -o "$work/big2.svg"
else # a sherd without an axis cannot be drawn
  echo "| sherd draw --axis: skipped, the scan's status is $(grep -o '"status": "[a-z_]*"' "$work/axis.json") | | | | |"
fi

echo
"$sherd" synth -o "$work/batch" --count "$count" --seed 100 --faces 200000 >/dev/null
echo
echo "| batch | CPU s | wall s | peak MiB | load (1, 5, 15 min) |"
echo "|---|---|---|---|---|"
# Exit code 1 means some sherd's row is an error: still a complete run to measure.
ALLOW_EXIT_1=1 measure "sherd batch: $count sherds of 200k faces, SVG drawings, 2 jobs" "$sherd" batch "$work/batch" -o "$work/out" --jobs 2
python3 - "$cpu" "$count" "$work/out/report.json" <<'PY'
import collections, json, sys
cpu, count, report = float(sys.argv[1]), int(sys.argv[2]), json.load(open(sys.argv[3]))
statuses = collections.Counter("error" if r.get("error") or r["status"].startswith("error") else r["status"] for r in report)
print(f"\n{cpu / count:.2f} CPU-s per sherd; estimated {2 * 60 * count / cpu:.0f} sherds per minute on 2 idle cores "
      f"(an estimate from CPU time, not a wall-clock measurement); "
      + ", ".join(f"{n} {status}" for status, n in sorted(statuses.items())))
PY
