//! Packages a stub native library (built with clang for aarch64-linux-android) with the real
//! `app/Cargo.toml` metadata and reads the APK back: manifest, library path, signatures.
#![cfg(not(target_os = "android"))]

mod common;

use std::path::Path;

use common::{scratch, stub_library};

use apk::Apk;
use regatta_apk::key::debug_identity;
use regatta_apk::metadata::CrateAndroid;
use regatta_apk::package::{ApkInputs, write_apk};

#[test]
fn a_missing_library_is_named() {
    let dir = scratch("missing");
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../app/Cargo.toml");
    let app = CrateAndroid::read(&manifest).unwrap();
    let (identity, _) = debug_identity(&dir.join("key.pem")).unwrap();
    let lib = dir.join("nothere/libregatta.so");
    let inputs = ApkInputs {
        app,
        library: lib.clone(),
        extra_libraries: vec![],
        dex: vec![],
        library_manifests: vec![],
    };
    let e = write_apk(&inputs, &manifest, identity, &dir.join("x.apk")).unwrap_err();
    assert!(
        e.0.starts_with(&format!("{}: cannot read", lib.display())),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_apk_carries_the_metadata_and_verifies() {
    let dir = scratch("apk");
    let Some(lib) = stub_library(&dir) else {
        regatta_apk::skip_unless_ci("no clang/lld for aarch64-linux-android");
        return;
    };
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../app/Cargo.toml");
    let app = CrateAndroid::read(&manifest).unwrap();
    let (identity, _) = debug_identity(&dir.join("key.pem")).unwrap();
    let out = dir.join("regatta.apk");
    let inputs = ApkInputs {
        app: app.clone(),
        library: lib,
        extra_libraries: vec![],
        dex: vec![],
        library_manifests: vec![],
    };
    let summary = write_apk(&inputs, &manifest, identity, &out).unwrap();
    assert_eq!(
        summary.libraries,
        vec!["lib/arm64-v8a/libregatta.so".to_string()]
    );
    assert!(
        summary.schemes.iter().any(|s| s.contains("v2")),
        "{:?}",
        summary.schemes
    );

    let mut apk = Apk::open(&out).unwrap();
    let m = apk.manifest().unwrap();
    assert_eq!(m.package(), Some(app.android.package.as_str()));
    assert_eq!(
        m.min_sdk().to_string(),
        app.android.sdk.min_sdk_version.to_string()
    );
    assert!(m.permissions().any(|p| p == "android.permission.CAMERA"));
    assert_eq!(m.launcher_activity(), Some("android.app.NativeActivity"));
    assert_eq!(m.native_activity_library(), Some(Ok("regatta")));
    let text = m.to_string();
    assert!(
        text.contains("com.google.ar.core") && text.contains("optional"),
        "{text}"
    );
    assert!(apk.read("lib/arm64-v8a/libregatta.so").is_ok());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_library_that_is_not_elf_is_refused_with_its_name() {
    let dir = scratch("bad");
    let lib = dir.join("libregatta.so");
    std::fs::write(&lib, b"not an ELF file").unwrap();
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../app/Cargo.toml");
    let app = CrateAndroid::read(&manifest).unwrap();
    let (identity, _) = debug_identity(&dir.join("key.pem")).unwrap();
    let out = dir.join("regatta.apk");
    let inputs = ApkInputs {
        app,
        library: lib.clone(),
        extra_libraries: vec![],
        dex: vec![],
        library_manifests: vec![],
    };
    let e = write_apk(&inputs, &manifest, identity, &out).unwrap_err();
    assert!(
        e.0.starts_with(&out.display().to_string()) || e.0.contains("libregatta"),
        "{e}"
    );
    assert!(!out.exists(), "no APK is left behind");
    std::fs::remove_dir_all(&dir).unwrap();
}
