//! `--arcore-aar` packaging (issue 19, defect 6) with a stand-in AAR built here (Google's AAR
//! cannot be fetched offline): its manifest entries are merged into the app's, and with its
//! classes (a DEX) the APK declares `hasCode="true"`. The packaged manifest is read back with
//! `aapt dump xmltree`, as a phone's package manager would see it.
#![cfg(not(target_os = "android"))]

mod common;

use std::path::Path;
use std::process::Command;

use common::{scratch, stand_in_dex, stub_library, stub_library_named};
use regatta_apk::key::debug_identity;
use regatta_apk::metadata::CrateAndroid;
use regatta_apk::package::{ApkInputs, write_apk};

/// The manifest of ARCore's AAR as published (SDK 1.4x): package `com.google.ar.core`, the
/// minimum ARCore APK version, the install activity, the package query.
const ARCORE_AAR_MANIFEST: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<manifest xmlns:android="http://schemas.android.com/apk/res/android"
    package="com.google.ar.core">
    <uses-sdk android:minSdkVersion="14" />
    <queries>
        <package android:name="com.google.ar.core" />
    </queries>
    <application>
        <meta-data android:name="com.google.ar.core.min_apk_version" android:value="240520000" />
        <activity
            android:name="com.google.ar.core.InstallActivity"
            android:configChanges="keyboardHidden|orientation|screenSize"
            android:excludeFromRecents="true"
            android:exported="false"
            android:launchMode="singleTop" />
    </application>
</manifest>
"#;

fn aapt_xmltree(apk: &Path) -> Option<String> {
    let out = Command::new("aapt")
        .args(["dump", "xmltree"])
        .arg(apk)
        .arg("AndroidManifest.xml")
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

fn package(dir: &Path, aar_manifest: &str) -> Result<std::path::PathBuf, String> {
    let lib = stub_library(dir).ok_or("no clang")?;
    let arcore =
        stub_library_named(dir, "libarcore_sdk_c.so", "ArSession_create").ok_or("no clang")?;
    let manifest_file = dir.join("AndroidManifest.xml");
    std::fs::write(&manifest_file, aar_manifest).unwrap();
    let cargo_toml = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../app/Cargo.toml");
    let (identity, _) = debug_identity(&dir.join("key.pem")).unwrap();
    let out = dir.join("regatta.apk");
    let inputs = ApkInputs {
        app: CrateAndroid::read(&cargo_toml).unwrap(),
        library: lib,
        extra_libraries: vec![arcore],
        dex: vec![stand_in_dex(dir)],
        library_manifests: vec![manifest_file],
    };
    write_apk(&inputs, &cargo_toml, identity, &out).map_err(|e| e.0)?;
    Ok(out)
}

#[test]
fn the_arcore_aar_is_packaged_with_its_code_and_manifest_entries() {
    let dir = scratch("aar");
    let apk = match package(&dir, ARCORE_AAR_MANIFEST) {
        Err(e) if e == "no clang" => {
            regatta_apk::skip_unless_ci("no clang/lld for aarch64-linux-android");
            return;
        }
        other => {
            other.expect("the APK with ARCore packages (before: hasCode=false refused the DEX)")
        }
    };
    let Some(tree) = aapt_xmltree(&apk) else {
        regatta_apk::skip_unless_ci("no aapt to read the packaged manifest");
        return;
    };
    // hasCode: aapt prints booleans as (type 0x12)0xffffffff for true.
    let has_code = tree
        .lines()
        .find(|l| l.contains("android:hasCode"))
        .expect(&tree);
    assert!(has_code.ends_with("0xffffffff"), "{has_code}");
    for expected in [
        "\"com.google.ar.core.min_apk_version\"",
        "\"com.google.ar.core.InstallActivity\"",
        "E: queries",
        "E: package",
        "\"com.google.ar.core\"",
        // The app's own entries stay.
        "\"android.app.NativeActivity\"",
        "\"android.permission.CAMERA\"",
    ] {
        assert!(
            tree.contains(expected),
            "the manifest lacks {expected}:\n{tree}"
        );
    }
    // The library's minSdk (14) is not merged: the app's stays.
    assert_eq!(tree.matches("E: uses-sdk").count(), 1, "{tree}");
    assert!(
        !tree.contains("(type 0x10)0xe\n"),
        "minSdk 14 leaked:\n{tree}"
    );
    // "com.google.ar.core" twice: the app's own meta-data ("optional") and the query.
    assert_eq!(
        tree.matches("\"com.google.ar.core\" (Raw").count(),
        2,
        "{tree}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_arcore_query_is_added_when_the_aar_has_none() {
    let dir = scratch("aar-noquery");
    let without_queries = ARCORE_AAR_MANIFEST.replace(
        "    <queries>\n        <package android:name=\"com.google.ar.core\" />\n    </queries>\n",
        "",
    );
    assert!(!without_queries.contains("queries"));
    let apk = match package(&dir, &without_queries) {
        Err(e) if e == "no clang" => {
            regatta_apk::skip_unless_ci("no clang/lld for aarch64-linux-android");
            return;
        }
        other => other.unwrap(),
    };
    let Some(tree) = aapt_xmltree(&apk) else {
        regatta_apk::skip_unless_ci("no aapt to read the packaged manifest");
        return;
    };
    assert_eq!(tree.matches("E: queries").count(), 1, "{tree}");
    std::fs::remove_dir_all(&dir).unwrap();
}
