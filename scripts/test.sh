#!/usr/bin/env bash
# The one test command: installs what it needs when missing, then runs every check.
# Under CI=true a GPU test that finds no adapter fails; it never skips silently.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)

# Each step says how long the run has taken so far: where a clean CI run's time goes.
step() { printf '\n==> [%s s] %s\n' "$(( $(date +%s) - start ))" "$*" >&2; }
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

# --- install what is missing --------------------------------------------------------------
need_pkgs=()
for p in mesa-vulkan-drivers libvulkan1 libegl-mesa0 libgl1-mesa-dri xvfb xauth clang lld llvm apksigner aapt; do
  dpkg -s "$p" >/dev/null 2>&1 || need_pkgs+=("$p")
done
if [ ${#need_pkgs[@]} -gt 0 ]; then
  step "installing ${need_pkgs[*]}"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq "${need_pkgs[@]}" >/dev/null
fi
if ! rustup target list --installed | grep -qx aarch64-linux-android; then
  step "adding rustup target aarch64-linux-android"
  rustup target add aarch64-linux-android
fi
rustup component list --installed | grep -q '^clippy' || rustup component add clippy
rustup component list --installed | grep -q '^rustfmt' || rustup component add rustfmt

export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/regatta-xdg-$(id -u)}"
mkdir -p "$XDG_RUNTIME_DIR"; chmod 700 "$XDG_RUNTIME_DIR"
# GPU tests run on Mesa's lavapipe (Vulkan on the CPU).
lvp=$(ls /usr/share/vulkan/icd.d/lvp_icd*.json 2>/dev/null | head -1 || true)
if [ -n "$lvp" ]; then export VK_ICD_FILENAMES="$lvp"; export VK_DRIVER_FILES="$lvp"; fi
export REGATTA_REQUIRE_GPU="${CI:-false}"
# A clean CI clone has no incremental state to reuse: writing it only slows the build (cargo's
# own advice for CI). Local runs keep it.
if [ "${CI:-false}" = true ]; then export CARGO_INCREMENTAL=0; fi
# Every test that skips (no GPU adapter, no xvfb-run, no Android clang or ../shared/data/android)
# appends one line to this file; the count is printed at the end, and under CI=true it must be 0.
REGATTA_SKIP_LOG=$(mktemp "${TMPDIR:-/tmp}/regatta-skips.XXXXXX")
export REGATTA_SKIP_LOG
skip_count() { grep -c . "$REGATTA_SKIP_LOG" || true; }
report_skips() {
  printf '\nGPU tests skipped: %s (tests that found no GPU adapter, xvfb-run, Android clang or data)\n' "$(skip_count)" >&2
  sed 's/^/  skipped: /' "$REGATTA_SKIP_LOG" >&2
  rm -f "$REGATTA_SKIP_LOG"
}
trap report_skips EXIT

step "cargo fmt --check"
cargo fmt --all -- --check
step "cargo clippy --workspace"
cargo clippy --workspace --all-targets -- -D warnings
step "cargo test --workspace"
cargo test --workspace
if [ "${CI:-false}" = true ] && [ "$(skip_count)" -gt 0 ]; then
  echo "CI=true but $(skip_count) test(s) skipped (listed below)" >&2
  exit 1
fi
# Clippy type-checks everything `cargo check` would (and lints it): one pass over the Android
# target, not two.
step "cargo clippy --workspace --target aarch64-linux-android"
cargo clippy --workspace --target aarch64-linux-android -- -D warnings
step "APK: scripts/build-apk.sh, then apksigner, aapt and the symbol check"
scripts/build-apk.sh >/dev/null
scripts/check-apk.sh
step "all checks passed in $(( $(date +%s) - start )) s"
