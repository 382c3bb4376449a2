//! Builds, aligns (16 KiB pages for mapped native libraries) and signs the APK (v2 + v3, and v1
//! below API 24) from the crate's Android metadata.

use std::path::{Path, PathBuf};

use apk::manifest;
use apk::prelude::*;
use apk::xml::Element;

use crate::ApkError;
use crate::metadata::{CrateAndroid, IntentFilter};

/// Everything that goes into one APK.
#[derive(Clone, Debug)]
pub struct ApkInputs {
    pub app: CrateAndroid,
    /// The app's native library, `lib<crate>.so`, for arm64-v8a.
    pub library: PathBuf,
    /// More arm64-v8a libraries to package (ARCore's `libarcore_sdk_c.so`).
    pub extra_libraries: Vec<PathBuf>,
    /// DEX files (ARCore's Java classes), packaged as `classes.dex`, `classes2.dex`, ...
    pub dex: Vec<PathBuf>,
    /// Library manifests (ARCore's AAR's `AndroidManifest.xml`) merged into the app's.
    pub library_manifests: Vec<PathBuf>,
}

/// What was written, for the JSON summary on stdout.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ApkSummary {
    pub apk: PathBuf,
    pub package: String,
    pub min_sdk: u32,
    pub target_sdk: u32,
    pub permissions: Vec<String>,
    pub libraries: Vec<String>,
    pub dex_files: usize,
    /// What the library manifests added (`tag android:name`).
    pub merged: Vec<String>,
    pub schemes: Vec<String>,
    pub certificate_sha256: String,
}

fn err(what: impl std::fmt::Display) -> impl Fn(apk::Error) -> ApkError {
    move |e| ApkError(format!("{what}: {e}"))
}

/// The manifest the metadata describes (NativeActivity running `lib<crate>.so`).
pub fn builder(app: &CrateAndroid, manifest_file: &Path) -> Result<ApkBuilder, ApkError> {
    let a = &app.android;
    let field = |name: &str| {
        format!(
            "{} [package.metadata.android] {name}",
            manifest_file.display()
        )
    };
    let package: PackageName = a
        .package
        .parse()
        .map_err(|e| ApkError(format!("{}: {e}", field("package"))))?;
    let library: LibraryName = app
        .crate_name
        .parse()
        .map_err(|e| ApkError(format!("{}: {e}", field("[package] name"))))?;
    let level = |n: u32, name: &str| {
        ApiLevel::try_new(n).map_err(|e| ApkError(format!("{}: {e}", field(name))))
    };
    let min = level(a.sdk.min_sdk_version, "sdk.min_sdk_version")?;
    let target = level(a.sdk.target_sdk_version, "sdk.target_sdk_version")?;
    let code = VersionCode::try_new(a.version_code.unwrap_or(1))
        .map_err(|e| ApkError(format!("{}: {e}", field("version_code"))))?;

    let mut b = ApkBuilder::native_activity(package, library);
    b.label(a.application.label.clone())
        .version(code, a.version_name.as_deref().unwrap_or("0.1.0"))
        .min_sdk(min)
        .target_sdk(target)
        .debuggable(a.application.debuggable);
    for p in &a.uses_permission {
        let name: PermissionName = p
            .name
            .parse()
            .map_err(|e| ApkError(format!("{}: {e}", field("uses_permission"))))?;
        b.permission(name);
    }
    let m = b.manifest_mut();
    for f in &a.uses_feature {
        let feature = Element::new("uses-feature")
            .with_attr(attr::NAME, f.name.as_str())
            .with_attr(attr::REQUIRED, f.required);
        m.root_mut().push_child(feature);
    }
    let application = m.application_mut();
    for md in &a.application.meta_data {
        application.push_child(manifest::meta_data(&md.name, md.value.as_str()));
    }
    let filters = a
        .application
        .activity
        .intent_filter
        .iter()
        .map(intent_filter)
        .collect::<Vec<_>>();
    if !filters.is_empty() {
        let activity = application
            .element_mut("activity")
            .expect("native_activity adds the activity");
        for f in filters {
            activity.push_child(f);
        }
    }
    if let Some(orientation) = &a.application.activity.orientation {
        let value = attr::SCREEN_ORIENTATION.parse(orientation).map_err(|e| {
            ApkError(format!(
                "{}: {e}",
                field("application.activity.orientation")
            ))
        })?;
        let activity = application
            .element_mut("activity")
            .expect("native_activity adds the activity");
        activity.set_attr(attr::SCREEN_ORIENTATION, value);
    }
    Ok(b)
}

/// `<intent-filter>` with its actions, categories and data, as cargo-apk writes them.
fn intent_filter(f: &IntentFilter) -> Element {
    let mut e = Element::new("intent-filter");
    for action in &f.actions {
        e.push_child(Element::new("action").with_attr(attr::NAME, action.as_str()));
    }
    for category in &f.categories {
        e.push_child(Element::new("category").with_attr(attr::NAME, category.as_str()));
    }
    for d in &f.data {
        e.push_child(
            Element::new("data")
                .with_opt_attr(attr::SCHEME, d.scheme.as_deref())
                .with_opt_attr(attr::HOST, d.host.as_deref())
                .with_opt_attr(attr::MIME_TYPE, d.mime_type.as_deref())
                .with_opt_attr(attr::PATH_PATTERN, d.path_pattern.as_deref()),
        );
    }
    e
}

/// Writes the signed APK to `out` and verifies its signatures.
pub fn write_apk(
    inputs: &ApkInputs,
    manifest_file: &Path,
    identity: SigningIdentity,
    out: &Path,
) -> Result<ApkSummary, ApkError> {
    crate::check::arcore_has_its_classes(
        inputs
            .extra_libraries
            .iter()
            .filter_map(|l| l.file_name()?.to_str()),
        inputs.dex.len(),
    )
    .map_err(|e| ApkError(format!("{}: {e}", out.display())))?;
    let mut b = builder(&inputs.app, manifest_file)?;
    let mut libraries = Vec::new();
    for lib in std::iter::once(&inputs.library).chain(&inputs.extra_libraries) {
        // Read and parse first, so a bad library is named by its own path.
        let bytes = std::fs::read(lib)
            .map_err(|e| ApkError(format!("{}: cannot read: {e}", lib.display())))?;
        apk::native::ElfInfo::parse(&bytes).map_err(|e| {
            ApkError(format!(
                "{}: not an Android shared library: {e}",
                lib.display()
            ))
        })?;
        b.native_library(Abi::Arm64V8a, lib)
            .map_err(err(lib.display()))?;
        libraries.push(format!(
            "lib/arm64-v8a/{}",
            lib.file_name().unwrap_or_default().to_string_lossy()
        ));
    }
    for dex in &inputs.dex {
        let bytes = std::fs::read(dex)
            .map_err(|e| ApkError(format!("{}: cannot read: {e}", dex.display())))?;
        b.dex(bytes);
    }
    let merged = merge_libraries(&mut b, inputs)?;
    b.sign_with(Signer::new(identity));
    b.write(out).map_err(err(out.display()))?;

    let v = verify(out).map_err(err(format!("{} (verifying)", out.display())))?;
    let a = &inputs.app.android;
    Ok(ApkSummary {
        apk: out.to_owned(),
        package: a.package.clone(),
        min_sdk: a.sdk.min_sdk_version,
        target_sdk: a.sdk.target_sdk_version,
        permissions: a.uses_permission.iter().map(|p| p.name.clone()).collect(),
        libraries,
        dex_files: inputs.dex.len(),
        merged,
        schemes: v.schemes.iter_schemes().map(|s| s.to_string()).collect(),
        certificate_sha256: v
            .certificate()
            .sha256_fingerprint()
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect(),
    })
}

/// Merges the library manifests (ARCore's) into the app's, with the `<queries>` entry ARCore
/// needs; and, with DEX files, declares the code: `native_activity()` says `hasCode="false"`,
/// which Android (and rust-apk) refuse beside a `classes.dex`.
fn merge_libraries(b: &mut ApkBuilder, inputs: &ApkInputs) -> Result<Vec<String>, ApkError> {
    let mut merged = Vec::new();
    for path in &inputs.library_manifests {
        let text = std::fs::read_to_string(path)
            .map_err(|e| ApkError(format!("{}: cannot read: {e}", path.display())))?;
        merged.extend(crate::aar::merge_library_manifest(
            b.manifest_mut(),
            &text,
            path,
        )?);
    }
    if !inputs.library_manifests.is_empty() && crate::aar::ensure_arcore_query(b.manifest_mut()) {
        merged.push(format!("queries {}", crate::aar::ARCORE_PACKAGE));
    }
    if !inputs.dex.is_empty() {
        b.manifest_mut()
            .application_mut()
            .set_attr(attr::HAS_CODE, true);
    }
    Ok(merged)
}
