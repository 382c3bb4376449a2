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
#    the app's, and packs the AAR's classes.jar dexed with d8 as classes.dex (hasCode="true"):
#    d8 from PATH, $ANDROID_HOME/build-tools/*/d8, or R8_JAR=r8.jar with java. Without a dexer
#    it stops (ARCore's library without its Java classes cannot start AR); without
#    --arcore-aar the APK runs the 3D view without AR, and this script says so.
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
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "build-apk.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
say() { printf 'build-apk: %s\n' "$*" >&2; }
# The dexer, as a command line: d8 on PATH, else the newest of the SDK's build-tools, else
# Google's r8.jar (R8_JAR) run with java (r8.jar's D8 is the same program).
find_d8() {
  if command -v d8 >/dev/null; then echo d8; return; fi
  local sdk="${ANDROID_HOME:-${ANDROID_SDK_ROOT:-}}" d
  if [ -n "$sdk" ]; then
    d=$(ls -d "$sdk"/build-tools/*/d8 2>/dev/null | sort -V | tail -1 || true)
    [ -n "$d" ] && [ -x "$d" ] && { echo "$d"; return; }
  fi
  if [ -n "${R8_JAR:-}" ] && [ -f "$R8_JAR" ] && command -v java >/dev/null; then
    echo "java -cp $R8_JAR com.android.tools.r8.D8"; return
  fi
  return 1
}
die() { printf 'build-apk: %s\n' "$*" >&2; exit 1; }
[ -z "$aar" ] || [ -f "$aar" ] || die "$aar: no such ARCore AAR"
# Before the long native build: ARCore without a dexer is refused now, not after it.
if [ -n "$aar" ]; then
  dexer=$(find_d8) || die "--arcore-aar needs d8 to pack ARCore's Java classes (without them AR cannot start on the phone): install the Android SDK build-tools (sdkmanager \"build-tools;35.0.0\") and put d8 on PATH or set ANDROID_HOME, or set R8_JAR to Google's r8.jar (run with java); Debian has no dexer. Leave out --arcore-aar to build without AR."
fi
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
  # ARCore's native library loads its Java half through JNI (SessionCreateJniHelper, the
  # install activity): without the AAR's classes as DEX, AR cannot start. No dexer, no ARCore.
  [ -f "$work/extra/aar/classes.jar" ] || die "$aar: has no classes.jar (ARCore's Java classes)"
  lib_jar=$(ls -d "${ANDROID_HOME:-${ANDROID_SDK_ROOT:-/nonexistent}}"/platforms/android-*/android.jar 2>/dev/null | sort -V | tail -1 || true)
  say "dexing ARCore's classes.jar with $dexer${lib_jar:+ (--lib $lib_jar)}"
  rm -f "$work/extra/aar/classes.dex"
  $dexer --release --min-api "$min_sdk" ${lib_jar:+--lib "$lib_jar"} --output "$work/extra/aar" \
    "$work/extra/aar/classes.jar" >&2 || die "d8 failed on $aar's classes.jar (above)"
  [ -f "$work/extra/aar/classes.dex" ] || die "d8 wrote no classes.dex from $aar's classes.jar"
  extra+=(--dex "$work/extra/aar/classes.dex")
  say "ARCore: packaging $arcore_so"
else
  say "no --arcore-aar given: building WITHOUT AR (the app runs the 3D race view without camera)"
fi

# --- package, align, sign --------------------------------------------------------------------
cargo build -p regatta-apk --quiet >&2
"$target_dir/debug/regatta-apk" package --manifest app/Cargo.toml --lib "$so" --key "$key" --out "$out" "${extra[@]}"
say "wrote $out"
