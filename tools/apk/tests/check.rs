//! The APK check (issue 26, defect 1): an APK that carries ARCore's `libarcore_sdk_c.so` but no
//! `classes.dex` (what `scripts/build-apk.sh --arcore-aar` made on a machine without d8) is
//! refused, by `regatta-apk check` and by packaging itself; an APK with neither passes; one with
//! both passes. The intent filters of `app/Cargo.toml` are read back from the packaged manifest
//! with `aapt dump xmltree` (Android's own reader of binary XML), as a phone would see them.
#![cfg(not(target_os = "android"))]

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use apk::prelude::*;
use common::{scratch, stand_in_dex, stub_library, stub_library_named};
use regatta_apk::check::check_apk;
use regatta_apk::key::debug_identity;
use regatta_apk::metadata::CrateAndroid;
use regatta_apk::package::{ApkInputs, builder, write_apk};

fn app_toml() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../app/Cargo.toml")
}

/// The app's library and ARCore's (stubs), or `None` without clang and lld.
fn libraries(dir: &Path) -> Option<(PathBuf, PathBuf)> {
    Some((
        stub_library(dir)?,
        stub_library_named(dir, "libarcore_sdk_c.so", "ArSession_create")?,
    ))
}

/// `aapt VERB APK [FILE]`'s output, or `None` without aapt.
fn aapt(verb: &[&str], apk: &Path, file: &[&str]) -> Option<String> {
    let out = Command::new("aapt")
        .args(verb)
        .arg(apk)
        .args(file)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

fn regatta_apk_check(apk: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_regatta-apk"))
        .args(["check", "--apk"])
        .arg(apk)
        .output()
        .unwrap()
}

#[test]
fn an_apk_with_arcores_library_and_no_dex_is_refused() {
    let dir = scratch("check-nodex");
    let Some((lib, arcore)) = libraries(&dir) else {
        regatta_apk::skip_unless_ci("no clang/lld for aarch64-linux-android");
        return;
    };
    // The APK the old build made without d8: both libraries, hasCode="false", no DEX. Built
    // with rust-apk directly, since `write_apk` now refuses to make it.
    let app = CrateAndroid::read(&app_toml()).unwrap();
    let (identity, _) = debug_identity(&dir.join("key.pem")).unwrap();
    let mut b = builder(&app, &app_toml()).unwrap();
    b.native_library(Abi::Arm64V8a, &lib).unwrap();
    b.native_library(Abi::Arm64V8a, &arcore).unwrap();
    b.sign_with(Signer::new(identity.clone()));
    let apk = dir.join("no-dex.apk");
    b.write(&apk).unwrap();
    if let Some(list) = aapt(&["list"], &apk, &[]) {
        // Android's own tool sees what the check must refuse.
        assert!(
            list.lines()
                .any(|l| l == "lib/arm64-v8a/libarcore_sdk_c.so")
        );
        assert!(!list.lines().any(|l| l.ends_with(".dex")), "{list}");
    }

    let e = check_apk(&apk).unwrap_err();
    assert!(
        e.0.starts_with(&apk.display().to_string()) && e.0.contains("no classes.dex"),
        "{e}"
    );
    assert!(!e.0.contains('\n'), "one sentence: {e}");
    let out = regatta_apk_check(&apk);
    assert!(!out.status.success(), "regatta-apk check passed it");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("libarcore_sdk_c.so but no classes.dex"),
        "{stderr}"
    );

    // Packaging refuses to make it in the first place, and leaves no APK behind.
    let out_apk = dir.join("refused.apk");
    let inputs = ApkInputs {
        app,
        library: lib,
        extra_libraries: vec![arcore],
        dex: vec![],
        library_manifests: vec![],
    };
    let e = write_apk(&inputs, &app_toml(), identity, &out_apk).unwrap_err();
    assert!(e.0.contains("no classes.dex"), "{e}");
    assert!(!out_apk.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_apk_with_neither_passes_and_one_with_both_passes() {
    let dir = scratch("check-pass");
    let Some((lib, arcore)) = libraries(&dir) else {
        regatta_apk::skip_unless_ci("no clang/lld for aarch64-linux-android");
        return;
    };
    let app = CrateAndroid::read(&app_toml()).unwrap();
    let (identity, _) = debug_identity(&dir.join("key.pem")).unwrap();
    let plain = dir.join("plain.apk");
    let inputs = ApkInputs {
        app: app.clone(),
        library: lib.clone(),
        extra_libraries: vec![],
        dex: vec![],
        library_manifests: vec![],
    };
    write_apk(&inputs, &app_toml(), identity.clone(), &plain).unwrap();
    let report = check_apk(&plain).unwrap();
    assert_eq!(report.libraries, ["lib/arm64-v8a/libregatta.so"]);
    assert!(
        report.dex_files.is_empty() && !report.has_code,
        "{report:?}"
    );
    assert!(regatta_apk_check(&plain).status.success());

    let with_arcore = dir.join("arcore.apk");
    let inputs = ApkInputs {
        extra_libraries: vec![arcore],
        dex: vec![stand_in_dex(&dir)],
        ..inputs
    };
    write_apk(&inputs, &app_toml(), identity, &with_arcore).unwrap();
    let report = check_apk(&with_arcore).unwrap();
    assert_eq!(report.dex_files, ["classes.dex"]);
    assert!(report.has_code);
    assert!(regatta_apk_check(&with_arcore).status.success());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_open_with_and_share_filters_read_back_with_aapt() {
    let dir = scratch("check-filters");
    let Some(lib) = stub_library(&dir) else {
        regatta_apk::skip_unless_ci("no clang/lld for aarch64-linux-android");
        return;
    };
    let app = CrateAndroid::read(&app_toml()).unwrap();
    let (identity, _) = debug_identity(&dir.join("key.pem")).unwrap();
    let apk = dir.join("regatta.apk");
    let inputs = ApkInputs {
        app: app.clone(),
        library: lib,
        extra_libraries: vec![],
        dex: vec![],
        library_manifests: vec![],
    };
    write_apk(&inputs, &app_toml(), identity, &apk).unwrap();
    let declared = &app.android.application.activity.intent_filter;
    assert!(declared.len() >= 2, "app/Cargo.toml declares its filters");
    // rust-apk's own reading of the packaged manifest: the filters as declared, the launcher's
    // aside.
    let report = check_apk(&apk).unwrap();
    assert_eq!(report.opens.len(), declared.len());
    for (got, want) in report.opens.iter().zip(declared) {
        assert_eq!(got.actions, want.actions);
        assert_eq!(got.categories, want.categories);
        let mimes: Vec<String> = want
            .data
            .iter()
            .filter_map(|d| d.mime_type.clone())
            .collect();
        assert_eq!(got.mime_types, mimes);
    }
    // Android's reader: every MIME type, action and path pattern declared is in the manifest.
    let Some(tree) = aapt(&["dump", "xmltree"], &apk, &["AndroidManifest.xml"]) else {
        regatta_apk::skip_unless_ci("no aapt to read the packaged manifest");
        return;
    };
    assert_eq!(
        tree.matches("E: intent-filter").count(),
        declared.len() + 1,
        "{tree}"
    );
    for f in declared {
        for a in f.actions.iter().chain(&f.categories) {
            assert!(tree.contains(&format!("=\"{a}\"")), "{a} missing:\n{tree}");
        }
        for d in &f.data {
            for (attr, v) in [
                ("mimeType", &d.mime_type),
                ("scheme", &d.scheme),
                ("host", &d.host),
                ("pathPattern", &d.path_pattern),
            ] {
                if let Some(v) = v {
                    // aapt prints a backslash of the value as two.
                    let v = v.replace('\\', "\\\\");
                    let want = format!("android:{attr}(0x");
                    assert!(
                        tree.lines()
                            .any(|l| l.contains(&want) && l.contains(&format!(")=\"{v}\""))),
                        "android:{attr}=\"{v}\" missing:\n{tree}"
                    );
                }
            }
        }
    }
    for mime in [
        "application/gpx+xml",
        "text/csv",
        "application/json",
        "text/xml",
    ] {
        assert!(tree.contains(&format!("=\"{mime}\"")), "{mime}:\n{tree}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
