//! Shared by the packaging tests: scratch folders and a stub arm64 library.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("regatta-apk-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A 16 KiB-aligned arm64 library `file` exporting `symbol`, or `None` without clang and lld.
pub fn stub_library_named(dir: &Path, file: &str, symbol: &str) -> Option<PathBuf> {
    let src = dir.join(format!("{file}.c"));
    std::fs::write(
        &src,
        format!("void {symbol}(void *a, void *s, unsigned long n) {{}}\n"),
    )
    .unwrap();
    let out = dir.join(file);
    let ok = Command::new("clang")
        .args([
            "--target=aarch64-linux-android24",
            "-shared",
            "-nostdlib",
            "-fuse-ld=lld",
        ])
        .args([
            "-Wl,-z,max-page-size=16384",
            &format!("-Wl,-soname,{file}"),
            "-o",
        ])
        .arg(&out)
        .arg(&src)
        .status()
        .is_ok_and(|s| s.success());
    ok.then_some(out)
}

/// The app's library: exports the NativeActivity entry point.
pub fn stub_library(dir: &Path) -> Option<PathBuf> {
    stub_library_named(dir, "libregatta.so", "ANativeActivity_onCreate")
}

/// A DEX header (`dex\n035\0`, then zeros) standing in for ARCore's classes: packaging and the
/// APK check do not look inside.
pub fn stand_in_dex(dir: &Path) -> PathBuf {
    let mut bytes = b"dex\n035\0".to_vec();
    bytes.resize(112, 0);
    let path = dir.join("classes.dex");
    std::fs::write(&path, bytes).unwrap();
    path
}
