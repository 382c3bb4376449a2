#!/usr/bin/env bash
# Checks an APK built by scripts/build-apk.sh with the SDK's own tools where Debian has them:
# apksigner verify; aapt dump badging (package, minSdk, camera permission, native activity,
# arm64-v8a library); and every undefined dynamic symbol of the native library against Android's
# symbol maps at the declared minSdk (regatta-apk check-symbols: no symbol newer than minSdk, no
# _Unwind_*, no glibc version).   Usage: scripts/check-apk.sh [APK]
set -euo pipefail
cd "$(dirname "$0")/.."
apk="${1:-${CARGO_TARGET_DIR:-target}/apk/regatta.apk}"
fail() { printf 'check-apk: %s: %s\n' "$apk" "$*" >&2; exit 1; }
[ -f "$apk" ] || fail "no such APK (run scripts/build-apk.sh)"

package=$(sed -n 's/^package *= *"\(.*\)".*/\1/p' app/Cargo.toml | head -1)
min_sdk=$(sed -n 's/^min_sdk_version *= *\([0-9]*\).*/\1/p' app/Cargo.toml | head -1)

apksigner verify "$apk" >/dev/null || fail "apksigner verify refused the signature"
badging=$(aapt dump badging "$apk") || fail "aapt cannot read it"
expect() { grep -qF -- "$1" <<<"$badging" || fail "aapt dump badging lacks: $1"; }
expect "package: name='$package'"
expect "sdkVersion:'$min_sdk'"
expect "uses-permission: name='android.permission.CAMERA'"
expect "launchable-activity: name='android.app.NativeActivity'"
expect "native-code: 'arm64-v8a'"
aapt list "$apk" | grep -qx 'lib/arm64-v8a/libregatta.so' || fail "has no lib/arm64-v8a/libregatta.so"

# The library as packaged (the build's copy is byte-identical: rust-apk stores it uncompressed).
so="${CARGO_TARGET_DIR:-target}/aarch64-linux-android/${APK_PROFILE:-release}/libregatta.so"
[ -f "$so" ] || fail "$so is missing"
maps="${ANDROID_SYMBOL_MAPS:-$(cd .. && pwd)/shared/data/android}"
[ -d "$maps" ] || fail "no Android symbol maps at $maps (set ANDROID_SYMBOL_MAPS)"
cargo build -p regatta-apk --quiet
report=$("${CARGO_TARGET_DIR:-target}/debug/regatta-apk" check-symbols --lib "$so" --maps "$maps" --maps android) \
  || fail "undefined symbols of $so not all available at minSdk $min_sdk (above)"
weak=$(grep -c '(API\|(not in the maps)' <<<"$report" || true)
# Cross-check with LLVM's own reader: nothing glibc-versioned, no unwinder import.
if llvm-nm -D --undefined-only "$so" | grep -E '@GLIBC|_Unwind_' ; then
  fail "llvm-nm finds glibc-versioned or _Unwind_ imports above"
fi
printf 'check-apk: %s ok (package %s, minSdk %s; %s undefined symbols, all on API %s but %s weak ones)\n' \
  "$apk" "$package" "$min_sdk" "$(llvm-nm -D --undefined-only "$so" | wc -l)" "$min_sdk" "$weak" >&2
