//! Merges an Android library's (AAR's) `AndroidManifest.xml` into the app's manifest, as the
//! Android Gradle plugin's manifest merger does for the parts Regatta's AARs use (ARCore's:
//! the `com.google.ar.core.min_apk_version` meta-data, the `com.google.ar.core.InstallActivity`
//! activity, the `<queries>` entry for `com.google.ar.core`): the library's
//! `<uses-permission>`, `<uses-feature>` and `<queries>`, and the children of its
//! `<application>`. `${applicationId}` in values becomes the app's package. The library's
//! `<uses-sdk>` is not merged (the app's minSdk stands); an element the app already has (same
//! tag and `android:name`) is kept as the app wrote it.

use std::path::Path;

use apk::Manifest;
use apk::prelude::*;
use apk::res::Value;
use apk::xml::{Element, Node};

use crate::ApkError;

/// Root elements of a library manifest that are merged.
const MERGED_ROOT: [&str; 3] = ["uses-permission", "uses-feature", "queries"];

/// The package whose visibility ARCore needs from Android 11 (targetSdk ≥ 30): the app asks
/// "Google Play Services for AR" whether it is installed.
pub const ARCORE_PACKAGE: &str = "com.google.ar.core";

fn name_of(e: &Element) -> Option<String> {
    e.android_attr(attr::NAME).map(ToString::to_string)
}

/// Whether `parent` has a child element like `e` (same tag and `android:name`; for nameless
/// elements such as `<queries>`, the same tag and content).
fn has_like(parent: &Element, e: &Element) -> bool {
    parent.elements_named(&e.name).any(|x| match name_of(e) {
        Some(n) => name_of(x).as_deref() == Some(n.as_str()),
        None => x == e,
    })
}

/// `${applicationId}` → `package` in every string attribute of `e` and its children.
fn substitute(e: &mut Element, package: &str) {
    for a in &mut e.attributes {
        if let Value::String(s) = &mut a.value
            && s.contains("${applicationId}")
        {
            *s = s.replace("${applicationId}", package);
        }
    }
    for child in &mut e.children {
        if let Node::Element(c) = child {
            substitute(c, package);
        }
    }
}

/// Merges the library manifest text `library` (read from `path`, for messages) into `app`;
/// returns what was added, as `tag name` lines, for the packaging summary.
pub fn merge_library_manifest(
    app: &mut Manifest,
    library: &str,
    path: &Path,
) -> Result<Vec<String>, ApkError> {
    let lib = Manifest::parse(library)
        .map_err(|e| ApkError(format!("{}: not a library manifest: {e}", path.display())))?;
    let package = app.package().unwrap_or_default().to_owned();
    let mut added = Vec::new();
    let describe = |e: &Element| format!("{} {}", e.name, name_of(e).unwrap_or_default());
    for e in lib.root().elements() {
        if MERGED_ROOT.contains(&e.name.as_str()) && !has_like(app.root(), e) {
            let mut e = e.clone();
            substitute(&mut e, &package);
            added.push(describe(&e));
            app.root_mut().push_child(e);
        }
    }
    if let Some(application) = lib.root().element("application") {
        for e in application.elements() {
            if !has_like(app.application_mut(), e) {
                let mut e = e.clone();
                substitute(&mut e, &package);
                added.push(describe(&e));
                app.application_mut().push_child(e);
            }
        }
    }
    Ok(added)
}

/// Adds `<queries><package android:name="com.google.ar.core"/></queries>` unless the manifest
/// already names that package in a `<queries>`: from targetSdk 30 Android hides other apps'
/// packages, and ARCore's availability check needs to see Google Play Services for AR.
pub fn ensure_arcore_query(app: &mut Manifest) -> bool {
    let seen = app.root().elements_named("queries").any(|q| {
        q.elements_named("package")
            .any(|p| name_of(p).as_deref() == Some(ARCORE_PACKAGE))
    });
    if !seen {
        let query = Element::new("queries")
            .with_child(Element::new("package").with_attr(attr::NAME, ARCORE_PACKAGE));
        app.root_mut().push_child(query);
    }
    !seen
}
