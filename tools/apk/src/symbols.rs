//! Checks a native library's undefined dynamic symbols against Android's published symbol maps
//! (AOSP `*.map.txt`, in `shared/data/android/`) at the APK's minSdk: every strong undefined
//! symbol must be exported by some map at that API level on arm64; `_Unwind_*` must not be
//! undefined (phones export no libunwind); no symbol may need a glibc version.

use std::collections::BTreeMap;
use std::path::Path;

use crate::ApkError;

/// First arm64 API level of each app-visible symbol, over all maps read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SymbolMaps {
    pub first_api: BTreeMap<String, u32>,
}

const ARCHES: [&str; 6] = ["arm", "arm64", "x86", "x86_64", "riscv64", "x64_64"];

impl SymbolMaps {
    /// Reads every `*.map.txt` in each of `dirs`.
    pub fn read_dirs(dirs: &[&Path]) -> Result<Self, ApkError> {
        let mut maps = Self::default();
        for dir in dirs {
            maps.read_dir_into(dir)?;
        }
        Ok(maps)
    }

    /// Reads every `*.map.txt` in `dir`.
    pub fn read_dir(dir: &Path) -> Result<Self, ApkError> {
        let mut maps = Self::default();
        maps.read_dir_into(dir)?;
        Ok(maps)
    }

    fn read_dir_into(&mut self, dir: &Path) -> Result<(), ApkError> {
        let maps = self;
        let entries = std::fs::read_dir(dir).map_err(|e| {
            ApkError(format!(
                "{}: cannot list the symbol maps: {e}",
                dir.display()
            ))
        })?;
        let mut n = 0;
        for entry in entries.flatten() {
            let path = entry.path();
            if path.to_string_lossy().ends_with(".map.txt") {
                let text = std::fs::read_to_string(&path)
                    .map_err(|e| ApkError(format!("{}: cannot read: {e}", path.display())))?;
                maps.add(&text, &path)?;
                n += 1;
            }
        }
        if n == 0 {
            return Err(ApkError(format!(
                "{}: no *.map.txt symbol maps",
                dir.display()
            )));
        }
        Ok(())
    }

    /// Adds one version script. Blocks named `*_PRIVATE` or `*_PLATFORM`, and symbols tagged
    /// `apex`, `llndk`, `platform-only` or for other architectures only, are not for apps.
    pub fn add(&mut self, text: &str, path: &Path) -> Result<(), ApkError> {
        let mut block: Option<(bool, u32)> = None; // (for apps, block's first API)
        for (i, raw) in text.lines().enumerate() {
            let (code, comment) = raw.split_once('#').unwrap_or((raw, ""));
            let code = code.trim();
            if let Some(name) = code.strip_suffix('{').map(str::trim) {
                let for_apps = !(name.ends_with("_PRIVATE") || name.ends_with("_PLATFORM"));
                let api = api_of(comment, i, path)?.unwrap_or(1);
                block = Some((for_apps && !excluded(comment), api));
                continue;
            }
            if code.starts_with('}') {
                block = None;
                continue;
            }
            let Some((block_ok, block_api)) = block else {
                continue;
            };
            let Some(sym) = code.strip_suffix(';') else {
                continue;
            };
            if sym.ends_with(':')
                || sym == "*"
                || sym.contains(' ')
                || !block_ok
                || excluded(comment)
            {
                continue;
            }
            let tags: Vec<&str> = comment.split_whitespace().collect();
            let arch_tagged = tags.iter().any(|t| ARCHES.contains(t));
            if arch_tagged && !tags.contains(&"arm64") {
                continue;
            }
            let api = api_of(comment, i, path)?.unwrap_or(1).max(block_api);
            let e = self.first_api.entry(sym.to_string()).or_insert(api);
            *e = (*e).min(api);
        }
        Ok(())
    }
}

/// API levels of the release codenames the maps use.
fn codename_api(name: &str) -> Option<u32> {
    Some(match name {
        "Tiramisu" => 33,
        "UpsideDownCake" => 34,
        "VanillaIceCream" => 35,
        "Baklava" => 36,
        _ => return None,
    })
}

fn excluded(comment: &str) -> bool {
    comment
        .split_whitespace()
        .any(|t| matches!(t, "apex" | "llndk" | "platform-only"))
}

/// The API level a tag comment states for arm64: `introduced-arm64=N` wins over
/// `introduced=N`; `None` when neither is there.
fn api_of(comment: &str, line: usize, path: &Path) -> Result<Option<u32>, ApkError> {
    let mut generic = None;
    for tag in comment.split_whitespace() {
        let Some((key, value)) = tag.split_once('=') else {
            continue;
        };
        let parse = || {
            codename_api(value)
                .map_or_else(|| value.parse::<u32>(), Ok)
                .map_err(|_| {
                    ApkError(format!(
                        "{} line {}: API level '{value}' is not a number",
                        path.display(),
                        line + 1
                    ))
                })
        };
        match key {
            "introduced-arm64" => return parse().map(Some),
            "introduced" => generic = Some(parse()?),
            _ => {}
        }
    }
    Ok(generic)
}

/// One undefined dynamic symbol of the library.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Undefined {
    pub name: String,
    /// Weak: the dynamic linker leaves it null where absent, so any API level is fine.
    pub weak: bool,
}

/// The library's undefined dynamic symbols and the symbol versions it needs.
pub fn read_undefined(so: &Path) -> Result<(Vec<Undefined>, Vec<String>), ApkError> {
    let bytes =
        std::fs::read(so).map_err(|e| ApkError(format!("{}: cannot read: {e}", so.display())))?;
    let elf = goblin::elf::Elf::parse(&bytes)
        .map_err(|e| ApkError(format!("{}: not an ELF shared library: {e}", so.display())))?;
    let mut undefined = Vec::new();
    for sym in elf.dynsyms.iter() {
        if sym.st_shndx != 0 || sym.st_name == 0 {
            continue;
        }
        let name = elf
            .dynstrtab
            .get_at(sym.st_name)
            .unwrap_or_default()
            .to_string();
        undefined.push(Undefined {
            name,
            weak: sym.st_bind() == goblin::elf::sym::STB_WEAK,
        });
    }
    let mut versions = Vec::new();
    if let Some(verneed) = &elf.verneed {
        for file in verneed.iter() {
            for aux in file.iter() {
                versions.push(
                    elf.dynstrtab
                        .get_at(aux.vna_name)
                        .unwrap_or_default()
                        .to_string(),
                );
            }
        }
    }
    Ok((undefined, versions))
}

/// What the check found; `problems` empty means the library loads on every API ≥ min_sdk.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct SymbolReport {
    pub min_sdk: u32,
    pub undefined: usize,
    /// Weak symbols newer than min_sdk (resolved to null on older phones; callers check).
    pub weak_newer: Vec<String>,
    pub problems: Vec<String>,
}

/// Checks `undefined` and `versions` (from [`read_undefined`]) at `min_sdk`.
pub fn check(
    maps: &SymbolMaps,
    undefined: &[Undefined],
    versions: &[String],
    min_sdk: u32,
) -> SymbolReport {
    let mut r = SymbolReport {
        min_sdk,
        undefined: undefined.len(),
        ..Default::default()
    };
    for v in versions {
        if v.starts_with("GLIBC") {
            r.problems.push(format!(
                "needs glibc symbol version {v}: linked against the host's libc"
            ));
        }
    }
    for u in undefined {
        if u.name.starts_with("_Unwind_") {
            r.problems.push(format!(
                "{} is undefined: Android exports no unwinder; link the unwinding crate",
                u.name
            ));
            continue;
        }
        match maps.first_api.get(&u.name) {
            Some(&api) if api <= min_sdk => {}
            Some(&api) if u.weak => r.weak_newer.push(format!("{} (API {api})", u.name)),
            Some(&api) => r.problems.push(format!(
                "{} needs API {api}, above minSdk {min_sdk}",
                u.name
            )),
            None if u.weak => r.weak_newer.push(format!("{} (not in the maps)", u.name)),
            None => r.problems.push(format!(
                "{} is not exported to apps by any Android system library map",
                u.name
            )),
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    const MAP: &str = "\
LIBC {
  global:
    malloc;
    dl_iterate_phdr; # introduced-arm=21
    only_on_arm; # arm x86
    also_arm64; # arm arm64
    lseek64; # introduced=12
    __apex_thing; # apex
  local:
    *;
};
LIBC_N { # introduced-arm64=24 introduced-x86=24
  global:
    getifaddrs;
} LIBC;
LIBC_P { # introduced=28
  global:
    getrandom;
    later; # introduced=30
} LIBC_N;
LIBC_PRIVATE {
  global:
    __secret;
};
";

    fn maps() -> SymbolMaps {
        let mut m = SymbolMaps::default();
        m.add(MAP, Path::new("libc.map.txt")).unwrap();
        m
    }

    #[test]
    fn levels_and_exclusions_follow_the_tags() {
        let m = maps().first_api;
        assert_eq!(m.get("malloc"), Some(&1));
        assert_eq!(m.get("dl_iterate_phdr"), Some(&1));
        assert_eq!(m.get("only_on_arm"), None);
        assert_eq!(m.get("also_arm64"), Some(&1));
        assert_eq!(m.get("lseek64"), Some(&12));
        assert_eq!(m.get("__apex_thing"), None);
        assert_eq!(m.get("getifaddrs"), Some(&24));
        assert_eq!(m.get("getrandom"), Some(&28));
        assert_eq!(m.get("later"), Some(&30));
        assert_eq!(m.get("__secret"), None);
    }

    #[test]
    fn the_real_bionic_maps_give_getrandom_api_28() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/android");
        let Ok(m) = SymbolMaps::read_dir(&dir) else {
            crate::skip_unless_ci(&format!("{} not here", dir.display()));
            return;
        };
        assert_eq!(m.first_api.get("getrandom"), Some(&28));
        assert_eq!(m.first_api.get("malloc"), Some(&1));
        assert_eq!(m.first_api.get("__android_log_write"), Some(&1));
        let ours = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../android");
        let both = SymbolMaps::read_dirs(&[&dir, &ours]).unwrap();
        assert_eq!(both.first_api.get("ANativeWindow_acquire"), Some(&1));
        assert_eq!(both.first_api.get("AHardwareBuffer_lockPlanes"), Some(&29));
        assert_eq!(both.first_api.get("AInputQueue_fromJava"), Some(&33));
    }

    #[test]
    fn check_reports_each_kind_of_problem() {
        let u = |name: &str, weak| Undefined {
            name: name.into(),
            weak,
        };
        let undefined = [
            u("malloc", false),
            u("getrandom", true),
            u("later", false),
            u("_Unwind_Resume", false),
            u("__secret", false),
        ];
        let r = check(&maps(), &undefined, &["GLIBC_2.17".into()], 28);
        assert_eq!(r.weak_newer, Vec::<String>::new());
        assert_eq!(
            r.problems,
            vec![
                "needs glibc symbol version GLIBC_2.17: linked against the host's libc".to_string(),
                "later needs API 30, above minSdk 28".into(),
                "_Unwind_Resume is undefined: Android exports no unwinder; link the unwinding crate".into(),
                "__secret is not exported to apps by any Android system library map".into(),
            ]
        );
        let r = check(&maps(), &undefined[..2], &[], 24);
        assert!(r.problems.is_empty());
        assert_eq!(r.weak_newer, vec!["getrandom (API 28)".to_string()]);
    }

    #[test]
    fn a_bad_level_names_the_line() {
        let e = SymbolMaps::default()
            .add("LIBC {\n  x; # introduced=Q\n};\n", Path::new("m.map.txt"))
            .unwrap_err();
        assert_eq!(e.0, "m.map.txt line 2: API level 'Q' is not a number");
    }
}
