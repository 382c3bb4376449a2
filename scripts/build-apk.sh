#!/usr/bin/env bash
# Builds Regatta's signed APK on a machine without the Android NDK or SDK:
#   scripts/build-apk.sh [--arcore-aar PATH] [--profile NAME] [--out FILE.apk] [--key FILE.pem]
# 1. links the app's cdylib for aarch64-linux-android with the system's clang and lld through a
#    linker wrapper, against stub system libraries built here (libc, libm, libdl, liblog,
#    libandroid: empty, with the right sonames, each a DT_NEEDED entry); std's unwinder comes from
#    the `unwinding` crate instead of the NDK's libunwind.a;
# 2. packages, aligns and signs it with tools/apk (rust-apk), from the cargo-apk metadata in
#    app/Cargo.toml, with a debug key generated on first use;
# 3. with --arcore-aar, adds ARCore's libarcore_sdk_c.so, merges the AAR's manifest entries into
#    the app's (and its classes, dexed with d8 when d8 is installed: then hasCode="true");
#    without it the APK runs the 3D view without AR, and this script says so.
# Prints the packaging summary (JSON) on stdout; progress on stderr.
set -euo pipefail
cd "$(dirname "$0")/.."

aar="" profile="release" out="" key="${REGATTA_APK_KEY:-$HOME/.android/regatta-debug.pem}"
while [ $# -gt 0 ]; do
  case "$1" in
    --arcore-aar) aar="$2"; shift 2 ;;
    --profile) profile="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --key) key="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "build-apk.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
say() { printf 'build-apk: %s\n' "$*" >&2; }
die() { printf 'build-apk: %s\n' "$*" >&2; exit 1; }
[ -z "$aar" ] || [ -f "$aar" ] || die "$aar: no such ARCore AAR"
for tool in clang ld.lld llvm-ar; do
  command -v "$tool" >/dev/null || die "needs $tool (apt-get install clang lld llvm)"
done

triple=aarch64-linux-android
min_sdk=$(sed -n 's/^min_sdk_version *= *\([0-9]*\).*/\1/p' app/Cargo.toml | head -1)
[ -n "$min_sdk" ] || die "app/Cargo.toml: no min_sdk_version in [package.metadata.android.sdk]"
target_dir="${CARGO_TARGET_DIR:-target}"
work="$target_dir/apk"
out="${out:-$work/regatta.apk}"
mkdir -p "$work/stubs" "$work/bin" "$work/extra"
work=$(cd "$work" && pwd)

# --- stub system libraries: only their sonames matter; the phone provides the real ones -------
for lib in c m dl log android; do
  clang --target="$triple$min_sdk" -x c /dev/null -shared -nostdlib -fuse-ld=lld \
    -Wl,-soname,"lib$lib.so" -o "$work/stubs/lib$lib.so"
done

# --- linker and C compiler wrappers -----------------------------------------------------------
cat > "$work/bin/linker" <<WRAP
#!/usr/bin/env bash
# rustc's link line, minus what needs the NDK: -lunwind (the unwinding crate defines _Unwind_*)
# and --as-needed (every stub must stay a DT_NEEDED entry: the stubs define no symbols).
args=()
for a in "\$@"; do
  case "\$a" in -lunwind|-Wl,--as-needed) ;; *) args+=("\$a") ;; esac
done
exec clang --target=$triple$min_sdk -fuse-ld=lld -nostdlib -L"$work/stubs" \\
  -Wl,-z,max-page-size=16384 -Wl,--strip-debug "\${args[@]}"
WRAP
cat > "$work/bin/cc" <<WRAP
#!/usr/bin/env bash
exec clang --target=$triple$min_sdk "\$@"
WRAP
chmod +x "$work/bin/linker" "$work/bin/cc"

# --- the native library ----------------------------------------------------------------------
say "building libregatta.so for $triple (profile $profile, minSdk $min_sdk)"
start=$(date +%s)
env CARGO_TARGET_AARCH64_LINUX_ANDROID_LINKER="$work/bin/linker" \
    CC_aarch64_linux_android="$work/bin/cc" AR_aarch64_linux_android=llvm-ar \
    cargo build -p regatta --lib --target "$triple" --profile "$profile" >&2
say "native build took $(( $(date +%s) - start )) s"
profile_dir="$profile"; [ "$profile" = dev ] && profile_dir=debug
so="$target_dir/$triple/$profile_dir/libregatta.so"
[ -f "$so" ] || die "$so was not built"

# --- ARCore, when its AAR is given ------------------------------------------------------------
extra=()
if [ -n "$aar" ]; then
  [ -f "$aar" ] || die "$aar: no such ARCore AAR"
  rm -rf "$work/extra/aar" && mkdir -p "$work/extra/aar"
  command -v unzip >/dev/null || die "needs unzip to open $aar"
  unzip -q -o "$aar" -d "$work/extra/aar" || die "$aar: not a zip archive (AAR)"
  arcore_so="$work/extra/aar/jni/arm64-v8a/libarcore_sdk_c.so"
  [ -f "$arcore_so" ] || die "$aar: has no jni/arm64-v8a/libarcore_sdk_c.so"
  extra+=(--extra-lib "$arcore_so")
  # The AAR's manifest entries (min_apk_version meta-data, InstallActivity, <queries>) are
  # merged into the app's, as Gradle's manifest merger would: ARCore's client needs them.
  [ -f "$work/extra/aar/AndroidManifest.xml" ] || die "$aar: has no AndroidManifest.xml"
  extra+=(--merge-manifest "$work/extra/aar/AndroidManifest.xml")
  if command -v d8 >/dev/null && [ -f "$work/extra/aar/classes.jar" ]; then
    d8 --release --min-api "$min_sdk" --output "$work/extra/aar" "$work/extra/aar/classes.jar" >&2
    extra+=(--dex "$work/extra/aar/classes.dex")
  else
    say "d8 not found: ARCore's Java classes are not packaged; ArCoreApk_requestInstall will fail on the phone and the app falls back to the 3D view"
  fi
  say "ARCore: packaging $arcore_so"
else
  say "no --arcore-aar given: building WITHOUT AR (the app runs the 3D race view without camera)"
fi

# --- package, align, sign --------------------------------------------------------------------
cargo build -p regatta-apk --quiet >&2
"$target_dir/debug/regatta-apk" package --manifest app/Cargo.toml --lib "$so" --key "$key" --out "$out" "${extra[@]}"
say "wrote $out"
