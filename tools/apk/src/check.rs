//! Reads a built APK back and refuses one in which AR could not start: ARCore's native
//! library (`libarcore_sdk_c.so`) loads its Java half through JNI (`SessionCreateJniHelper`,
//! the install activity `com.google.ar.core.InstallActivity`), so an APK that carries the
//! library must carry ARCore's classes as DEX code (`classes.dex`, from the AAR's
//! `classes.jar` dexed with d8) and declare it (`android:hasCode="true"`); without them
//! `ArCoreApk_requestInstall` aborts the process or leaves a Java exception pending. An APK
//! with neither the library nor DEX is fine: the app runs the 3D view without AR.
//!
//! The report also lists the activity's intent filters (the files the app opens from "Open
//! with" and "Share") as the packaged manifest declares them.

use std::path::Path;

use apk::Apk;
use apk::prelude::*;
use apk::xml::Element;

use crate::ApkError;

/// ARCore's native library, as packaged from its AAR.
pub const ARCORE_LIBRARY: &str = "libarcore_sdk_c.so";

/// What an APK holds, as read back from the archive and its binary manifest.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct ApkReport {
    /// `lib/<abi>/<file>` entries.
    pub libraries: Vec<String>,
    /// `classes*.dex` entries.
    pub dex_files: Vec<String>,
    /// `android:hasCode` of `<application>` (Android's default: true).
    pub has_code: bool,
    /// The activities' intent filters other than the launcher's.
    pub opens: Vec<OpenFilter>,
}

/// One intent filter, flattened: what the packaged manifest says the app accepts.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct OpenFilter {
    pub actions: Vec<String>,
    pub categories: Vec<String>,
    pub schemes: Vec<String>,
    pub mime_types: Vec<String>,
    pub path_patterns: Vec<String>,
}

/// The rule, on names: ARCore's library goes only with DEX code. `libraries` are file names
/// (`libarcore_sdk_c.so`), `dex_files` how many DEX files are packaged.
pub fn arcore_has_its_classes<'a>(
    libraries: impl IntoIterator<Item = &'a str>,
    dex_files: usize,
) -> Result<(), String> {
    let arcore = libraries.into_iter().any(|l| l == ARCORE_LIBRARY);
    if arcore && dex_files == 0 {
        return Err(format!(
            "has ARCore's {ARCORE_LIBRARY} but no classes.dex: the library needs ARCore's Java \
             classes (the AAR's classes.jar, dexed with d8 from the Android SDK build-tools), so \
             AR could not start on a phone; build with d8, or without ARCore"
        ));
    }
    Ok(())
}

fn android_name(e: &Element) -> Option<String> {
    e.android_attr(attr::NAME).map(ToString::to_string)
}

fn values(filter: &Element, tag: &str, def: &apk::android::AttrDef) -> Vec<String> {
    filter
        .elements_named(tag)
        .filter_map(|e| e.android_attr(def).map(ToString::to_string))
        .collect()
}

/// Reads `path` and checks it: ARCore's library only with DEX code, DEX code only when
/// declared, declared code only when there is some. Errors are one sentence naming the APK.
pub fn check_apk(path: &Path) -> Result<ApkReport, ApkError> {
    let at = |what: String| ApkError(format!("{}: {what}", path.display()));
    let mut apk = Apk::open(path).map_err(|e| at(format!("cannot be read as an APK ({e})")))?;
    let names: Vec<String> = apk.entries().map(str::to_owned).collect();
    let libraries: Vec<String> = names
        .iter()
        .filter(|n| n.starts_with("lib/") && n.ends_with(".so"))
        .cloned()
        .collect();
    let dex_files: Vec<String> = names
        .iter()
        .filter(|n| n.starts_with("classes") && n.ends_with(".dex") && !n.contains('/'))
        .cloned()
        .collect();
    let manifest = apk
        .manifest()
        .map_err(|e| at(format!("has no readable AndroidManifest.xml ({e})")))?;
    let has_code = manifest.has_code();
    arcore_has_its_classes(
        libraries.iter().filter_map(|l| l.rsplit('/').next()),
        dex_files.len(),
    )
    .map_err(at)?;
    match (has_code, dex_files.is_empty()) {
        (false, false) => {
            return Err(at(
                "has classes.dex but declares android:hasCode=\"false\": Android would not load ARCore's classes".into(),
            ));
        }
        (true, true) => {
            return Err(at(
                "declares android:hasCode=\"true\" but has no classes.dex: Android would fail to start it".into(),
            ));
        }
        _ => {}
    }
    let mut opens = Vec::new();
    for activity in manifest.activities() {
        for filter in activity.elements_named("intent-filter") {
            let actions: Vec<String> = filter
                .elements_named("action")
                .filter_map(android_name)
                .collect();
            if actions.iter().any(|a| a == "android.intent.action.MAIN") {
                continue;
            }
            opens.push(OpenFilter {
                categories: filter
                    .elements_named("category")
                    .filter_map(android_name)
                    .collect(),
                schemes: values(filter, "data", attr::SCHEME),
                mime_types: values(filter, "data", attr::MIME_TYPE),
                path_patterns: values(filter, "data", attr::PATH_PATTERN),
                actions,
            });
        }
    }
    Ok(ApkReport {
        libraries,
        dex_files,
        has_code,
        opens,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arcore_without_dex_is_refused_and_the_rest_passes() {
        let e = arcore_has_its_classes(["libregatta.so", ARCORE_LIBRARY], 0).unwrap_err();
        assert!(e.contains("no classes.dex") && e.contains("d8"), "{e}");
        assert!(arcore_has_its_classes(["libregatta.so", ARCORE_LIBRARY], 1).is_ok());
        assert!(arcore_has_its_classes(["libregatta.so"], 0).is_ok());
    }
}
