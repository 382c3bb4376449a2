//! Opening a race: the list of races in a folder (the phone's `…/files/races/`, where
//! `adb push` puts them; see docs/panels.md), the "Races" panel that shows it, and the one
//! sentence an import error becomes. Which files make a race: each file directly in the
//! folder is a race of its own; each sub-folder is one race of all the race files in it (two
//! boats' GPX and the marks' JSON, say).

use std::path::{Path, PathBuf};

use egui::{Color32, RichText, Ui};

/// File extensions the importer reads (it detects the format by content; these only pick the
/// files out of a folder): tracks and logs, watch files (FIT, TCX), tracker exports (KML,
/// KMZ), and any of them gzipped (`.gz`).
pub const RACE_EXTENSIONS: [&str; 12] = [
    "json", "gpx", "csv", "xml", "nmea", "log", "txt", "fit", "tcx", "kml", "kmz", "gz",
];

/// At most this many races are listed (a folder of thousands would not be read through).
pub const MAX_LISTED: usize = 200;

/// One race in the folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RaceEntry {
    /// The file's or sub-folder's name.
    pub name: String,
    /// The race files, sorted.
    pub files: Vec<PathBuf>,
}

fn is_race_file(p: &Path) -> bool {
    p.is_file()
        && p.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| RACE_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

fn sorted_entries(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            // Hidden files (".DS_Store", editors' swap files) are no races.
            !p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with('.'))
        })
        .collect();
    v.sort();
    Ok(v)
}

/// The races in `dir`, by name. A missing folder is an empty list (nothing was pushed yet);
/// an unreadable one is an error sentence naming it.
pub fn list_races(dir: &Path) -> Result<Vec<RaceEntry>, String> {
    if !dir.exists() {
        return Ok(Vec::new());
    }
    let shown = input::show_path(dir);
    let entries = sorted_entries(dir).map_err(|e| format!("{shown} could not be read ({e})"))?;
    let mut out = Vec::new();
    for p in entries {
        let name = input::escape_controls(&p.file_name().unwrap_or_default().to_string_lossy());
        if p.is_dir() {
            let files: Vec<PathBuf> = sorted_entries(&p)
                .unwrap_or_default()
                .into_iter()
                .filter(|f| is_race_file(f))
                .collect();
            if !files.is_empty() {
                out.push(RaceEntry { name, files });
            }
        } else if is_race_file(&p) {
            out.push(RaceEntry {
                name,
                files: vec![p],
            });
        }
        if out.len() == MAX_LISTED {
            break;
        }
    }
    Ok(out)
}

/// What the "Races" panel asks of the app this frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OpenRequest {
    /// Load these files as the new race.
    Files(Vec<PathBuf>),
    /// Show the desktop's file dialog.
    Dialog,
    /// Read the folder again.
    Rescan,
}

/// The "Races" panel: the race shown, the last import error (one sentence, the race before
/// stays), the folder's races to open, and on the desktop a button for the file dialog.
#[derive(Clone, Copy, Debug, Default)]
pub struct RacesPanel<'a> {
    pub current: &'a str,
    pub error: Option<&'a str>,
    pub entries: &'a [RaceEntry],
    /// Where the list comes from, as a person should read it (e.g. the `adb push` target).
    pub folder: Option<&'a str>,
    /// Whether the platform has a file dialog (desktop) and takes dropped files.
    pub dialog: bool,
}

/// Draws the panel; returns what the user asked for.
pub fn races_ui(ui: &mut Ui, p: &RacesPanel<'_>) -> Option<OpenRequest> {
    let mut out = None;
    ui.label(RichText::new(format!("Showing: {}", p.current)).strong());
    if let Some(e) = p.error {
        ui.add(egui::Label::new(RichText::new(e).color(Color32::from_rgb(255, 170, 80))).wrap());
    }
    if p.dialog {
        ui.horizontal_wrapped(|ui| {
            if ui.button("📂 Open race files…").clicked() {
                out = Some(OpenRequest::Dialog);
            }
            ui.label(RichText::new("or drop them on the window").weak());
        });
    }
    if let Some(folder) = p.folder {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(format!("Races in {folder}")).weak());
            if ui
                .small_button("⟳")
                .on_hover_text("Read the folder again")
                .clicked()
            {
                out = Some(OpenRequest::Rescan);
            }
        });
        if p.entries.is_empty() {
            ui.label(RichText::new("none yet: see docs/panels.md for adb push").weak());
        }
        egui::ScrollArea::vertical()
            .max_height(200.0)
            .auto_shrink([false, true])
            .show(ui, |ui| {
                for e in p.entries {
                    let files = if e.files.len() == 1 {
                        String::new()
                    } else {
                        format!("  ({} files)", e.files.len())
                    };
                    if ui.button(format!("{}{files}", e.name)).clicked() {
                        out = Some(OpenRequest::Files(e.files.clone()));
                    }
                }
            });
    }
    out
}
