#!/usr/bin/env bash
# Checks an APK built by scripts/build-apk.sh with the SDK's own tools where Debian has them:
# apksigner verify; aapt dump badging (package, minSdk, camera permission, native activity,
# arm64-v8a library); ARCore's library only with ARCore's classes (classes.dex, hasCode): an APK
# with libarcore_sdk_c.so and no DEX fails (AR could not start), one with neither passes
# (regatta-apk check, and aapt list); the "Open with"/"Share" intent filters of app/Cargo.toml
# read back with aapt dump xmltree; and every undefined dynamic symbol of the native library against Android's
# symbol maps at the declared minSdk (regatta-apk check-symbols: no symbol newer than minSdk, no
# _Unwind_*, no glibc version); and no code of the bench in it (regatta-apk check-bench-free).
# Usage: scripts/check-apk.sh [APK]
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
entries=$(aapt list "$apk") || fail "aapt cannot list it"
grep -qx 'lib/arm64-v8a/libregatta.so' <<<"$entries" || fail "has no lib/arm64-v8a/libregatta.so"

# ARCore's native library loads its Java half through JNI: the library without classes.dex is
# an APK in which AR cannot start (regatta-apk check reads the archive and the binary manifest;
# aapt's listing is the cross-check).
cargo build -p regatta-apk --quiet
"${CARGO_TARGET_DIR:-target}/debug/regatta-apk" check --apk "$apk" >/dev/null \
  || fail "regatta-apk check refused it (above)"
if grep -q '/libarcore_sdk_c\.so$' <<<"$entries"; then
  grep -qx 'classes.dex' <<<"$entries" || fail "aapt list: libarcore_sdk_c.so without classes.dex"
  arcore="with ARCore and its classes ($(grep -c '^classes.*\.dex$' <<<"$entries") DEX)"
else
  arcore="without ARCore (3D view only)"
fi

# The intent filters: every MIME type app/Cargo.toml declares, on the VIEW and SEND actions.
tree=$(aapt dump xmltree "$apk" AndroidManifest.xml) || fail "aapt cannot read its manifest"
for action in android.intent.action.VIEW android.intent.action.SEND; do
  grep -qF "\"$action\"" <<<"$tree" || fail "aapt dump xmltree: no intent filter with $action"
done
mimes=$(sed -n 's/.*mime_type *= *"\([^"]*\)".*/\1/p' app/Cargo.toml | sort -u)
[ -n "$mimes" ] || fail "app/Cargo.toml declares no intent filter mime_type"
while read -r mime; do
  grep -qF "android:mimeType(0x01010026)=\"$mime\"" <<<"$tree" || fail "aapt dump xmltree: no mimeType $mime"
done <<<"$mimes"

# The library as packaged (the build's copy is byte-identical: rust-apk stores it uncompressed).
so="${CARGO_TARGET_DIR:-target}/aarch64-linux-android/${APK_PROFILE:-release}/libregatta.so"
[ -f "$so" ] || fail "$so is missing"
maps="${ANDROID_SYMBOL_MAPS:-$(cd .. && pwd)/shared/data/android}"
[ -d "$maps" ] || fail "no Android symbol maps at $maps (set ANDROID_SYMBOL_MAPS)"
report=$("${CARGO_TARGET_DIR:-target}/debug/regatta-apk" check-symbols --lib "$so" --maps "$maps" --maps android) \
  || fail "undefined symbols of $so not all available at minSdk $min_sdk (above)"
weak=$(grep -c '(API\|(not in the maps)' <<<"$report" || true)
# The bench (tools/bench, `regatta bench`) is a program of its own: no symbol of the library's
# symbol table is its code (its crate, its budget model and shader cost, plotters).
"${CARGO_TARGET_DIR:-target}/debug/regatta-apk" check-bench-free --lib "$so" >/dev/null \
  || fail "the library holds the bench's code (above)"
# Cross-check with LLVM's own reader: nothing glibc-versioned, no unwinder import.
if llvm-nm -D --undefined-only "$so" | grep -E '@GLIBC|_Unwind_' ; then
  fail "llvm-nm finds glibc-versioned or _Unwind_ imports above"
fi
printf 'check-apk: %s ok (package %s, minSdk %s, %s; opens %s MIME types; %s undefined symbols, all on API %s but %s weak ones)\n' \
  "$apk" "$package" "$min_sdk" "$arcore" "$(wc -l <<<"$mimes")" "$(llvm-nm -D --undefined-only "$so" | wc -l)" "$min_sdk" "$weak" >&2
