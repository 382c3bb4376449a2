#!/usr/bin/env bash
# Run `regatta bench --only budget` N separate times (default 5) and report how far the runs'
# estimates agree: for every phone and tier, the spread (max − min) / median of the timed fps
# and of the model fps over the runs. Not part of scripts/test.sh: each run takes minutes
# (docs/benchmarks.md, "Budget: run to run").
#
# Usage: scripts/budget-spread.sh [RUNS] [OUT]     (defaults: 5, bench-out/budget-spread)
# Env:   REGATTA_BIN (default target/release/regatta; `regatta bench` runs the regatta-bench
#        binary beside it, both built with `cargo build --release` if missing)
# Writes OUT/run-K/ (each run's report and budget.json) and OUT/spread.json, prints a table.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
out=${2:-bench-out/budget-spread}
bin=${REGATTA_BIN:-target/release/regatta}
if [ ! -x "$bin" ] || [ ! -x "$(dirname "$bin")/regatta-bench" ]; then
  cargo build --release -p regatta -p regatta-bench
fi
command -v jq >/dev/null || { echo "budget-spread: needs jq" >&2; exit 2; }
mkdir -p "$out"
for k in $(seq 1 "$runs"); do
  echo "budget-spread: run $k of $runs ($(date -u +%H:%M:%S))" >&2
  "$bin" bench --only budget --out "$out/run-$k" >"$out/run-$k.log" 2>&1 ||
    { echo "budget-spread: run $k failed, see $out/run-$k.log" >&2; exit 1; }
done
# One row per phone and tier: every run's timed and model fps, and their spread.
jq -s '
  def median: sort | if length % 2 == 1 then .[length / 2 | floor]
                     else (.[length / 2 - 1] + .[length / 2]) / 2 end;
  def spread: ((max - min) / median);
  [ [.[][]] | group_by([.phone, .tier])[] |
    { phone: .[0].phone, tier: .[0].tier, runs: length,
      timed_fps: map(.timed_fps), model_fps: map(.model_fps),
      timed_fps_spread: (map(.timed_fps) | spread),
      model_fps_spread: (map(.model_fps) | spread) } ]
' "$out"/run-*/budget.json >"$out/spread.json"
jq -r '
  (["phone", "tier", "timed fps (runs)", "timed spread", "model fps", "model spread"] | @tsv),
  (.[] | [.phone, .tier, (.timed_fps | map(. * 10 | round / 10) | join(" ")),
          ((.timed_fps_spread * 1000 | round) / 10 | tostring + " %"),
          (.model_fps[0] * 10 | round / 10),
          ((.model_fps_spread * 1000 | round) / 10 | tostring + " %")] | @tsv)
' "$out/spread.json" | column -t -s $'\t'
worst=$(jq '[.[] | .timed_fps_spread, .model_fps_spread] | max' "$out/spread.json")
echo "budget-spread: the largest spread over $runs runs: $(jq -n "$worst * 100 | . * 10 | round / 10") % (goal 15 %)"
