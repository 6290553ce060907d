#!/usr/bin/env bash
# Runs one fuzz target for SECONDS (default 600) with the limits FUZZING.md states, on a
# working corpus fuzz/work/TARGET seeded from the committed fuzz/corpus/TARGET, and
# writes its log to fuzz/work/TARGET.log. Crashes land in fuzz/artifacts/TARGET/.
#
#   bash fuzz/run_fuzz.sh ply_ascii 600
#   SHERD_FUZZ_NO_BUILD=1 bash fuzz/run_fuzz.sh stl 600   # run the binary already built
#   bash fuzz/run_fuzz.sh pipeline 600 30                  # a unit may take 30 s (default 10)
#
# Needs cargo-fuzz (cargo install cargo-fuzz) and, on a stable toolchain,
# RUSTC_BOOTSTRAP=1 for the sanitizer flags cargo fuzz passes (set here).
set -euo pipefail
cd "$(dirname "$0")"
target=$1
seconds=${2:-600}
timeout=${3:-10}
export RUSTC_BOOTSTRAP=1
if [ -z "${SHERD_FUZZ_NO_BUILD:-}" ]; then cargo fuzz build "$target"; fi
mkdir -p "work/$target" "artifacts/$target"
binary="target/x86_64-unknown-linux-gnu/release/$target"
"$binary" "work/$target" "corpus/$target" \
  -max_total_time="$seconds" -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout="$timeout" \
  -print_final_stats=1 -artifact_prefix="artifacts/$target/" > "work/$target.log" 2>&1
