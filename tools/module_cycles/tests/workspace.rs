//! No import cycle between the modules of any crate of the workspace (see the library's doc for
//! what counts). A cycle fails with its modules named, e.g.
//! `render: frame → renderer → frame`.

use std::path::{Path, PathBuf};

use module_cycles::{Graph, describe};

/// Cycles tolerated by name, with the reason (none today: every crate's import graph is a DAG).
const ALLOWED: &[(&str, &str)] = &[];

/// Every crate directory of the workspace with a `src/`: `app`, `crates/*`, `tools/*`.
fn crate_dirs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut dirs = vec![root.join("app")];
    for group in ["crates", "tools"] {
        let mut more: Vec<PathBuf> = std::fs::read_dir(root.join(group))
            .expect("the workspace's crate folders")
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.join("src").is_dir())
            .collect();
        more.sort();
        dirs.extend(more);
    }
    dirs
}

fn name(dir: &Path) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let root = root.canonicalize().expect("workspace root");
    let dir = dir.canonicalize().expect("crate dir");
    dir.strip_prefix(&root)
        .expect("inside the workspace")
        .to_string_lossy()
        .into_owned()
}

#[test]
fn no_crate_has_an_import_cycle_between_its_modules() {
    let dirs = crate_dirs();
    assert!(dirs.len() >= 10, "found only {} crates", dirs.len());
    let mut found = Vec::new();
    let mut allowed_seen = Vec::new();
    for dir in &dirs {
        let krate = name(dir);
        let graph = Graph::of_crate(&dir.join("src")).expect("readable sources");
        assert!(!graph.edges.is_empty(), "{krate}: no modules read");
        for cycle in graph.cycles() {
            let text = describe(&cycle);
            if ALLOWED.contains(&(krate.as_str(), text.as_str())) {
                allowed_seen.push(format!("{krate}: {text}"));
            } else {
                found.push(format!("{krate}: {text}"));
            }
        }
    }
    for a in &allowed_seen {
        println!("allowed (see ALLOWED): {a}");
    }
    println!(
        "{} crates read, {} cycles outside ALLOWED",
        dirs.len(),
        found.len()
    );
    assert!(
        found.is_empty(),
        "import cycles between modules (break them by moving what both need into a module \
         of its own):\n{}",
        found.join("\n")
    );
}

/// The app's top-level folders import one way only: no back arrow between them (a cycle in
/// `Graph::folders`), and nothing outside `cli` imports `cli` (the command line is flags and
/// glue over the app; the crate root's `main` alone calls it).
#[test]
fn the_app_folders_have_no_back_arrow_and_only_the_root_imports_cli() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let graph = Graph::of_crate(&root.join("app/src")).expect("readable sources");
    let folders = graph.folders();
    assert!(folders.edges.len() >= 5, "{:?}", folders.edges.keys());
    let back: Vec<String> = folders.cycles().iter().map(|c| describe(c)).collect();
    let cli_importers = graph.importers_of("cli");
    println!("app folders: {:?}", folders.edges);
    assert!(
        back.is_empty() && cli_importers.is_empty(),
        "back arrows between app folders (move what both need below both):\n{}\n\
         folders importing cli: {cli_importers:?}",
        back.join("\n")
    );
}

/// Only the shells (`desktop`, `android`, `phone_sim`) and `wall_clock.rs` name the platforms'
/// crates or read the OS clock: every other file of the app is the platform-free core the shells
/// drive (ARCHITECTURE.md, "Module cycles"). Read as text, comments included, so a doc comment
/// that names `Instant` in a core file fails too: say "the OS clock" there instead.
#[test]
fn only_the_shells_name_winit_android_activity_or_the_os_clock() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../app/src");
    let shells = ["desktop", "android", "phone_sim", "wall_clock"];
    let words = [
        "winit::",
        "android_activity",
        "std::time::Instant",
        "Instant::now",
        "SystemTime",
    ];
    let files = module_cycles::module_files(&root).expect("readable sources");
    assert!(files.len() > 50, "read only {} files", files.len());
    let mut found = Vec::new();
    for (module, text) in &files {
        let folder = module.split("::").next().unwrap_or("");
        if shells.contains(&folder) {
            continue;
        }
        for w in words {
            if text.contains(w) {
                found.push(format!(
                    "{}: {w}",
                    if module.is_empty() { "crate" } else { module }
                ));
            }
        }
    }
    assert!(
        found.is_empty(),
        "platform or OS clock named outside the shells (hand the core events and wall \
         seconds instead):\n{}",
        found.join("\n")
    );
}
