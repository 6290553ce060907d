#!/usr/bin/env bash
# Whole-pipeline figures of the sherd command: wall time and peak memory (max RSS) of
# each step on synthetic scans, and the batch throughput. Prints a Markdown table for
# BENCHMARKS.md.
#
#   bash benches/pipeline.sh            # 500k-face scan + batch of 100 sherds of 200k faces
#   SHERD_BATCH_COUNT=20 bash benches/pipeline.sh   # a shorter batch
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin sherd
sherd=$(pwd)/target/release/sherd
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
count=${SHERD_BATCH_COUNT:-100}

measure() { # label, command...: prints "| label | seconds | MiB |"
  local label=$1; shift
  /usr/bin/time -f '%e %M' -o "$work/time" "$@" >/dev/null 2>"$work/stderr" || { cat "$work/stderr"; exit 1; }
  read -r seconds kib <"$work/time"
  printf '| %s | %.2f | %.0f |\n' "$label" "$seconds" "$((kib / 1024))"
}

"$sherd" synth -o "$work/big" --count 1 --seed 3 --faces 500000 --part rim >/dev/null
big=$(ls "$work"/big/*.ply | head -n 1)
echo "| step (500k-face scan: $(basename "$big")) | wall s | peak MiB |"
echo "|---|---|---|"
measure "sherd info" "$sherd" info "$big"
measure "sherd orient --json (read, repair, orient, refine, measure)" "$sherd" orient "$big" --json
"$sherd" orient "$big" --json >"$work/axis.json"
measure "sherd draw --axis (linear)" "$sherd" draw "$big" --axis "$work/axis.json" -o "$work/big.svg"
measure "sherd draw --axis (all styles, PNG 300 dpi)" "$sherd" draw "$big" --axis "$work/axis.json" --style linear,colour,light,occlusion,stipple,regularity -o "$work/big.png"
measure "sherd draw (whole pipeline, linear, SVG)" "$sherd" draw "$big" -o "$work/big2.svg"

echo
"$sherd" synth -o "$work/batch" --count "$count" --seed 100 --faces 200000 >/dev/null
start=$(date +%s.%N)
measure "sherd batch: $count sherds of 200k faces, SVG drawings, 2 jobs" "$sherd" batch "$work/batch" -o "$work/out" --jobs 2
end=$(date +%s.%N)
python3 - "$start" "$end" "$count" <<'PY'
import sys
start, end, count = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3])
print(f"\nbatch throughput: {count / ((end - start) / 60):.1f} sherds per minute")
PY
