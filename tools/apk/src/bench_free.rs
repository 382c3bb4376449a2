//! The Android library carries none of the bench (`tools/bench`, `regatta bench`): its defined
//! symbols (the ELF's `.symtab`, which `scripts/build-apk.sh` keeps: it strips debug info only)
//! name no bench code. Rust's legacy mangling writes a path as length-prefixed parts
//! (`_ZN13regatta_bench12budget_model10frame_work17h…E`) and a generic's argument path with
//! `..` between parts; both are read back as `a::b::c` and searched for the bench's paths.

use std::path::Path;

use crate::ApkError;

/// Paths that only the bench has: its crate, the module it was in the app, the drawing crate
/// only it uses, and its budget model's and shader cost's modules (a copy of them moved back
/// into the app under another parent is found too).
pub const BENCH_PATHS: [&str; 5] = [
    "regatta_bench::",
    "regatta::bench::",
    "plotters::",
    "::budget_model::",
    "::shader_cost::",
];

/// A legacy-mangled Rust symbol as `a::b::c` (generic arguments' `..` read as `::` too); the
/// name unchanged when it is not one.
pub fn readable(symbol: &str) -> String {
    let Some(mut rest) = symbol.strip_prefix("_ZN") else {
        return symbol.to_string();
    };
    let mut parts = Vec::new();
    while !rest.starts_with('E') {
        let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
        let Ok(len) = rest[..digits].parse::<usize>() else {
            return symbol.to_string();
        };
        let Some(part) = rest.get(digits..digits + len) else {
            return symbol.to_string();
        };
        parts.push(part.replace("..", "::"));
        rest = &rest[digits + len..];
    }
    format!("::{}", parts.join("::"))
}

/// The symbols among `names` that are the bench's code.
pub fn bench_symbols<'a>(names: impl IntoIterator<Item = &'a str>) -> Vec<String> {
    names
        .into_iter()
        .filter(|n| {
            let path = readable(n);
            BENCH_PATHS.iter().any(|b| path.contains(b))
        })
        .map(str::to_string)
        .collect()
}

/// The library's defined symbols from its symbol table; an error when it has none (a stripped
/// library would pass any check of its names).
pub fn defined_symbols(so: &Path) -> Result<Vec<String>, ApkError> {
    let bytes =
        std::fs::read(so).map_err(|e| ApkError(format!("{}: cannot read: {e}", so.display())))?;
    let elf = goblin::elf::Elf::parse(&bytes)
        .map_err(|e| ApkError(format!("{}: not an ELF file: {e}", so.display())))?;
    let names: Vec<String> = elf
        .syms
        .iter()
        .filter(|s| s.st_shndx != 0 && s.st_name != 0)
        .filter_map(|s| elf.strtab.get_at(s.st_name).map(str::to_string))
        .collect();
    if names.is_empty() {
        return Err(ApkError(format!(
            "{}: has no symbol table, so whether it holds the bench cannot be checked (link it with --strip-debug, not --strip-all)",
            so.display()
        )));
    }
    Ok(names)
}

/// The check: `Ok(symbols checked)` when no symbol is the bench's, else an error naming the
/// first few.
pub fn check_bench_free(so: &Path) -> Result<usize, ApkError> {
    let names = defined_symbols(so)?;
    let found = bench_symbols(names.iter().map(String::as_str));
    if found.is_empty() {
        return Ok(names.len());
    }
    let shown: Vec<String> = found.iter().take(3).map(|s| readable(s)).collect();
    Err(ApkError(format!(
        "{}: {} of its symbols are the bench's code (tools/bench belongs in no Android library), e.g. {}",
        so.display(),
        found.len(),
        shown.join(", ")
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path mangled as rustc's legacy scheme writes it, with a hash part.
    fn mangle(parts: &[&str]) -> String {
        let body: String = parts.iter().map(|p| format!("{}{p}", p.len())).collect();
        format!("_ZN{body}17h0123456789abcdefE")
    }

    #[test]
    fn legacy_names_read_as_paths_with_generic_arguments() {
        // The form of a real name (llvm-nm of the host-built regatta-bench; hash replaced).
        assert_eq!(
            readable("_ZN13regatta_bench12budget_model10frame_work17h0123456789abcdefE"),
            "::regatta_bench::budget_model::frame_work::h0123456789abcdef"
        );
        let generic = mangle(&[
            "core",
            "ptr",
            "drop_in_place$LT$regatta..bench..budget_run..Row$GT$",
        ]);
        assert_eq!(
            readable(&generic),
            "::core::ptr::drop_in_place$LT$regatta::bench::budget_run::Row$GT$::h0123456789abcdef"
        );
        assert_eq!(readable("android_main"), "android_main");
        // A length past the end is no legacy name: left as it is.
        assert_eq!(readable("_ZN99short"), "_ZN99short");
    }

    #[test]
    fn bench_code_is_found_and_the_apps_is_not() {
        let names = [
            // The bench's crate, the module it was in the app, a generic over its type, plotters.
            mangle(&["regatta_bench", "run_all"]),
            mangle(&["regatta", "bench", "shader_cost", "entry_cost"]),
            mangle(&["core", "ptr", "drop_in_place$LT$regatta..bench..Table$GT$"]),
            mangle(&["plotters", "chart", "builder"]),
            // The budget model back in the app under another parent.
            mangle(&["regatta", "core", "budget_model", "phone"]),
            // The app's own: a tier, the bench's word inside other identifiers, C names.
            mangle(&["regatta", "tier_render", "TierRender", "renderer"]),
            mangle(&["regatta", "core", "benchmarked"]),
            mangle(&["regatta", "bench_", "run"]),
            "android_main".to_string(),
            "ANativeActivity_onCreate".to_string(),
        ];
        let found = bench_symbols(names.iter().map(String::as_str));
        assert_eq!(found, names[..5].to_vec());
    }
}
