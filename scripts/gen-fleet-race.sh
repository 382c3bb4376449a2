#!/usr/bin/env bash
# Regenerate the embedded sample race assets/races/fleet.json (deterministic: same bytes each run).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run --quiet --release -p race --example gen_fleet_race > assets/races/fleet.json
echo "wrote assets/races/fleet.json ($(wc -c < assets/races/fleet.json) bytes)" >&2
