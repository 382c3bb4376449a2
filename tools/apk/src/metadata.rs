//! The `[package.metadata.android]` table of a crate's Cargo.toml, in cargo-apk's layout (the
//! subset Regatta uses), as the one source of the APK's manifest for both ways to the APK.

use std::path::Path;

use serde::Deserialize;

use crate::ApkError;

/// What the manifest needs, read from `[package.metadata.android]`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct AndroidMetadata {
    /// Application id, e.g. `org.regatta.app`.
    pub package: String,
    #[serde(default)]
    pub version_code: Option<u32>,
    #[serde(default)]
    pub version_name: Option<String>,
    #[serde(default)]
    pub build_targets: Vec<String>,
    pub sdk: Sdk,
    #[serde(default)]
    pub uses_permission: Vec<Permission>,
    #[serde(default)]
    pub uses_feature: Vec<Feature>,
    pub application: Application,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct Sdk {
    pub min_sdk_version: u32,
    pub target_sdk_version: u32,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct Permission {
    pub name: String,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct Feature {
    pub name: String,
    #[serde(default = "yes")]
    pub required: bool,
}

fn yes() -> bool {
    true
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct Application {
    pub label: String,
    #[serde(default)]
    pub debuggable: bool,
    #[serde(default)]
    pub meta_data: Vec<MetaData>,
    #[serde(default)]
    pub activity: Activity,
}

#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct Activity {
    /// `android:screenOrientation` symbol, e.g. `fullSensor`.
    #[serde(default)]
    pub orientation: Option<String>,
    /// The activity's `<intent-filter>`s besides the launcher's (cargo-apk's
    /// `[[package.metadata.android.application.activity.intent_filter]]`): the files the app
    /// opens from "Open with" and "Share".
    #[serde(default)]
    pub intent_filter: Vec<IntentFilter>,
}

/// One `<intent-filter>`: its `<action>`s, `<category>`s and `<data>` elements.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct IntentFilter {
    #[serde(default)]
    pub actions: Vec<String>,
    #[serde(default)]
    pub categories: Vec<String>,
    #[serde(default)]
    pub data: Vec<IntentData>,
}

/// One `<data>` element of an intent filter (the attributes Regatta uses, in cargo-apk's
/// names).
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntentData {
    #[serde(default)]
    pub scheme: Option<String>,
    #[serde(default)]
    pub host: Option<String>,
    #[serde(default)]
    pub mime_type: Option<String>,
    #[serde(default)]
    pub path_pattern: Option<String>,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct MetaData {
    pub name: String,
    pub value: String,
}

#[derive(Deserialize)]
struct CargoToml {
    package: Option<PackageTable>,
}

#[derive(Deserialize)]
struct PackageTable {
    name: String,
    #[serde(default)]
    metadata: Option<MetadataTable>,
}

#[derive(Deserialize)]
struct MetadataTable {
    android: Option<AndroidMetadata>,
}

/// The crate's name (its library is `lib<name>.so`) and its Android metadata.
#[derive(Clone, Debug, PartialEq)]
pub struct CrateAndroid {
    pub crate_name: String,
    pub android: AndroidMetadata,
}

impl CrateAndroid {
    /// Reads `[package.metadata.android]` from the Cargo.toml at `path`.
    pub fn read(path: &Path) -> Result<Self, ApkError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| ApkError(format!("{}: cannot read: {e}", path.display())))?;
        Self::parse(&text, path)
    }

    /// Parses Cargo.toml text; `path` only names the file in messages.
    pub fn parse(text: &str, path: &Path) -> Result<Self, ApkError> {
        let at = |what: String| ApkError(format!("{}: {what}", path.display()));
        let toml: CargoToml = toml::from_str(text).map_err(|e| {
            let line = e
                .span()
                .map(|s| text[..s.start].lines().count().max(1))
                .map_or(String::new(), |l| format!("line {l}: "));
            at(format!("{line}[package.metadata.android]: {}", e.message()))
        })?;
        let package = toml
            .package
            .ok_or_else(|| at("has no [package] table".into()))?;
        let android = package
            .metadata
            .and_then(|m| m.android)
            .ok_or_else(|| at("has no [package.metadata.android] table".into()))?;
        let sdk = &android.sdk;
        if sdk.min_sdk_version == 0 || sdk.target_sdk_version < sdk.min_sdk_version {
            return Err(at(format!(
                "[package.metadata.android.sdk]: need 1 <= min_sdk_version <= target_sdk_version, got {} and {}",
                sdk.min_sdk_version, sdk.target_sdk_version
            )));
        }
        if !android.build_targets.is_empty()
            && !android
                .build_targets
                .iter()
                .any(|t| t == "aarch64-linux-android")
        {
            return Err(at(
                "[package.metadata.android] build_targets must include aarch64-linux-android"
                    .into(),
            ));
        }
        Ok(Self {
            crate_name: package.name.replace('-', "_"),
            android,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
[package]
name = "regatta"
version.workspace = true

[package.metadata.android]
package = "org.regatta.app"
build_targets = ["aarch64-linux-android"]
[package.metadata.android.sdk]
min_sdk_version = 28
target_sdk_version = 35
[[package.metadata.android.uses_permission]]
name = "android.permission.CAMERA"
[[package.metadata.android.uses_feature]]
name = "android.hardware.camera.ar"
required = false
[package.metadata.android.application]
label = "Regatta"
[[package.metadata.android.application.meta_data]]
name = "com.google.ar.core"
value = "optional"
"#;

    #[test]
    fn reads_the_cargo_apk_layout() {
        let c = CrateAndroid::parse(GOOD, Path::new("app/Cargo.toml")).unwrap();
        assert_eq!(c.crate_name, "regatta");
        assert_eq!(c.android.package, "org.regatta.app");
        assert_eq!(c.android.sdk.min_sdk_version, 28);
        assert_eq!(
            c.android.uses_permission[0].name,
            "android.permission.CAMERA"
        );
        assert!(!c.android.uses_feature[0].required);
        assert_eq!(c.android.application.meta_data[0].value, "optional");
    }

    #[test]
    fn the_real_app_manifest_parses() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../app/Cargo.toml");
        let c = CrateAndroid::read(&path).unwrap();
        assert_eq!(c.crate_name, "regatta");
        assert!(c.android.sdk.min_sdk_version >= 24, "ARCore needs API 24");
    }

    #[test]
    fn missing_table_is_named() {
        let e = CrateAndroid::parse("[package]\nname = \"x\"\n", Path::new("x/Cargo.toml"))
            .unwrap_err();
        assert_eq!(e.0, "x/Cargo.toml: has no [package.metadata.android] table");
    }

    #[test]
    fn min_above_target_is_refused() {
        let bad = GOOD.replace("target_sdk_version = 35", "target_sdk_version = 21");
        let e = CrateAndroid::parse(&bad, Path::new("app/Cargo.toml")).unwrap_err();
        assert!(
            e.0.contains("min_sdk_version <= target_sdk_version, got 28 and 21"),
            "{e}"
        );
    }

    #[test]
    fn wrong_type_names_the_line() {
        let bad = GOOD.replace("min_sdk_version = 28", "min_sdk_version = \"28\"");
        let e = CrateAndroid::parse(&bad, Path::new("app/Cargo.toml")).unwrap_err();
        assert!(e.0.starts_with("app/Cargo.toml: line 10: "), "{e}");
    }

    #[test]
    fn other_abi_only_is_refused() {
        let bad = GOOD.replace("[\"aarch64-linux-android\"]", "[\"x86_64-linux-android\"]");
        let e = CrateAndroid::parse(&bad, Path::new("app/Cargo.toml")).unwrap_err();
        assert!(e.0.contains("must include aarch64-linux-android"), "{e}");
    }
}
