#!/usr/bin/env bash
# Long property/fuzz runs with random seeds. NOT part of scripts/test.sh or CI: those run every
# property test from a fixed seed with a fixed case count, so they never fail at random.
#
# Usage:
#   scripts/fuzz.sh [ROUNDS] [CASES]
#     ROUNDS  how many rounds, each with a fresh random seed (default 4; 0 = until stopped)
#     CASES   cases per property per round (default 20000)
#   REGATTA_FUZZ_SEED=S scripts/fuzz.sh 1 CASES   replays one seed (e.g. one a failure printed)
#   FUZZ_RELEASE=1 scripts/fuzz.sh ...            builds the tests with --release (faster cases)
#
# What it runs: every proptest in the workspace (crates/ocean/tests/properties.rs, the wake
# property in crates/ocean/src/wake/tests.rs, crates/race/tests/fuzz.rs, fuzz_formats.rs and
# state.rs). Each
# reads REGATTA_FUZZ_SEED (u64) and REGATTA_FUZZ_CASES (u32) instead of its fixed seed and case
# count (the convention: crates/ocean/tests/support/fuzz_config.rs and docs/testing.md). A new
# property test must follow it and be added to TARGETS below.
#
# When a round fails: the seed is printed before the round and in the test's output, with
# proptest's minimal failing input. To keep the case:
#   1. replay it: REGATTA_FUZZ_SEED=<seed> REGATTA_FUZZ_CASES=<cases> cargo test -p <crate> ...
#   2. fix the code, and add a plain #[test] next to the property that calls the same check with
#      the exact minimal input proptest printed (for file fuzzing: the exact input bytes as a
#      byte-string literal), named after what it exercises. Do not rely on proptest's
#      failure-persistence files (they are off).
#   3. the new #[test] must fail before the fix and pass after it.
set -euo pipefail
cd "$(dirname "$0")/.."

rounds="${1:-4}"
cases="${2:-20000}"
release=()
[ "${FUZZ_RELEASE:-0}" = 1 ] && release=(--release)

# crate | cargo test selectors | test-name filter
TARGETS=(
  "ocean|--test properties|"
  "ocean|--lib|wake::tests::no_nan_for_stops_reversals_and_jumps"
  "race|--test fuzz --test fuzz_formats --test state|"
)

random_seed() { od -An -N8 -tu8 /dev/urandom | tr -d ' '; }

round=0
while [ "$rounds" = 0 ] || [ "$round" -lt "$rounds" ]; do
  round=$((round + 1))
  seed="${REGATTA_FUZZ_SEED:-$(random_seed)}"
  echo "==> fuzz round $round: REGATTA_FUZZ_SEED=$seed REGATTA_FUZZ_CASES=$cases" >&2
  for target in "${TARGETS[@]}"; do
    IFS='|' read -r crate selectors filter <<<"$target"
    # shellcheck disable=SC2086 # selectors are several words on purpose
    if ! REGATTA_FUZZ_SEED="$seed" REGATTA_FUZZ_CASES="$cases" \
      cargo test "${release[@]}" -p "$crate" $selectors -- $filter; then
      echo "FUZZ FAILURE: crate $crate ($selectors $filter), REGATTA_FUZZ_SEED=$seed REGATTA_FUZZ_CASES=$cases" >&2
      echo "Replay with those variables, then keep the minimal input as a #[test] (see the top of $0)." >&2
      exit 1
    fi
  done
done
echo "==> $round fuzz round(s) passed" >&2
