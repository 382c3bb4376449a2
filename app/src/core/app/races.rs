//! The Races panel: on the phone the races in a folder, read again on resume, when
//! the panel opens and on its ⟳. On Android the folder is `races/` in the app's external files
//! folder, where `adb push` puts files (docs/panels.md); on the host (`regatta run --phone`,
//! `regatta phone-sim`) it is `$REGATTA_RACES_DIR`, else `races/` in the app's data folder. A
//! race chosen there replaces the one shown; one that fails to load is said in the panel in
//! one sentence and the race shown before stays. On the desktop the panel opens the file dialog
//! instead, and files dropped on the window open through the same [`App::open_race`].

use std::path::{Path, PathBuf};

use super::App;
use crate::core::table;
use crate::setup::RaceSetup;

/// Names the host's races folder.
pub const RACES_DIR_ENV: &str = "REGATTA_RACES_DIR";

/// The host's races folder: `$REGATTA_RACES_DIR`, else `races/` in `data_dir`.
pub fn host_races_dir(data_dir: Option<&Path>) -> Option<PathBuf> {
    std::env::var_os(RACES_DIR_ENV)
        .filter(|d| !d.is_empty())
        .map(PathBuf::from)
        .or_else(|| data_dir.map(|d| d.join("races")))
}

/// What the Races panel shows.
#[derive(Default)]
pub(super) struct RaceList {
    /// The folder, where the platform has one.
    pub(super) dir: Option<PathBuf>,
    /// The folder's races as last read.
    entries: Vec<ui::RaceEntry>,
    /// The last listing or loading error, one sentence.
    pub(super) error: Option<String>,
    /// The folder's entry (file or sub-folder name) of the race shown; `None` for the embedded
    /// race (see `shared.rs`).
    pub(super) shown: Option<String>,
    /// The folder as the panel names it.
    folder: String,
    /// The panel was open in the last frame (opening it reads the folder again).
    was_open: bool,
    /// The panel offers the platform's file dialog (the desktop).
    pub(super) dialog: bool,
}

impl RaceList {
    /// The desktop's list: no folder until one is set, the platform's file dialog offered.
    pub(super) fn with_dialog() -> RaceList {
        RaceList {
            dialog: true,
            ..Default::default()
        }
    }

    /// The panel's contents, showing `current`; `None` without a folder or a dialog.
    pub(super) fn panel<'a>(&'a self, current: &'a str) -> Option<ui::RacesPanel<'a>> {
        if self.dir.is_none() && !self.dialog {
            return None;
        }
        Some(ui::RacesPanel {
            current,
            error: self.error.as_deref(),
            entries: &self.entries,
            folder: self.dir.is_some().then_some(self.folder.as_str()),
            dialog: self.dialog,
        })
    }
}

impl App {
    /// Where the Races panel lists races from (`None`: no Races panel), read now.
    pub fn set_races_dir(&mut self, dir: Option<PathBuf>) {
        self.races.folder = dir.as_deref().map(input::show_path).unwrap_or_default();
        self.races.dir = dir;
        self.rescan_races();
    }

    /// Reads the races folder again (nothing without one).
    pub fn rescan_races(&mut self) {
        let Some(dir) = self.races.dir.as_deref() else {
            return;
        };
        match ui::list_races(dir) {
            Ok(entries) => self.races.entries = entries,
            Err(e) => {
                log::warn!("regatta: {e}");
                self.races.entries.clear();
                self.races.error = Some(e);
            }
        }
    }

    /// The races the panel lists, by name.
    pub fn listed_races(&self) -> Vec<&str> {
        self.races.entries.iter().map(|e| e.name.as_str()).collect()
    }

    /// The sentence the Races panel shows about the last failed listing or load.
    pub fn race_error(&self) -> Option<&str> {
        self.races.error.as_deref()
    }

    /// The race shown.
    pub fn race(&self) -> &race::Race {
        &self.world.race
    }

    /// Opens the listed race `name` (the panel's button): see [`App::open_race`].
    pub fn choose_race(&mut self, name: &str) -> Result<(), String> {
        let files = self
            .races
            .entries
            .iter()
            .find(|e| e.name == name)
            .map(|e| e.files.clone())
            .ok_or_else(|| format!("no race named {} is listed", input::quote(name)))?;
        self.open_race(&files)
    }

    /// Shows the race of `files` from now on; when it does not load, the panel says why in one
    /// sentence and the race shown before stays.
    pub fn open_race(&mut self, files: &[PathBuf]) -> Result<(), String> {
        match crate::panels::load_race_files(files) {
            Ok(race) => {
                log::info!("regatta: opened {}", race.name);
                self.races.shown = None;
                // The folder's entry these files are (the file itself, or its sub-folder).
                if let (Some(dir), Some(first)) = (self.races.dir.clone(), files.first()) {
                    let entry = match first.parent() {
                        Some(p) if p == dir.as_path() => Some(first.clone()),
                        Some(p) if p.parent() == Some(dir.as_path()) => Some(p.to_path_buf()),
                        _ => None,
                    };
                    if let Some(entry) = entry {
                        self.remember_shown(&dir, &entry);
                    }
                }
                self.set_race(race);
                self.races.error = None;
                Ok(())
            }
            Err(e) => {
                log::warn!("regatta: {e}");
                self.races.error = Some(e.clone());
                Err(e)
            }
        }
    }

    /// A new race on the same sea: fresh timeline, events and selection, its wakes; where the
    /// course stood on the table the new one stands, fitted to the table anew.
    pub(super) fn set_race(&mut self, race: race::Race) {
        let depth = table::table_depth();
        let pivot_on_table = self.course.map(|p| {
            p.race_to_ar()
                .transform_point3(table::course_pivot(self.world.race_bounds, depth))
        });
        self.world = self.world.with_race(race);
        crate::hud::panels_for_new_race(
            &self.world.race,
            &mut self.panels,
            &mut self.events,
            &mut self.overlays.settings.selected,
        );
        self.course = pivot_on_table.map(|at| {
            table::place_course(None, at, self.world.race_bounds, depth, self.table_room)
        });
        let wake = RaceSetup::new(self.profile()).wake_or_none(&self.world.race);
        if let Some(g) = self.graphics.as_mut() {
            g.set_race_wake(wake);
        }
    }

    /// Reads the folder again when the Races panel has just been opened.
    pub(super) fn races_panel_opened(&mut self) {
        let open = self.panels.show_races;
        if open && !self.races.was_open {
            self.rescan_races();
        }
        self.races.was_open = open;
    }

    /// What the Races panel asked for this frame.
    pub(super) fn races_request(&mut self, request: Option<ui::OpenRequest>) {
        match request {
            Some(ui::OpenRequest::Files(files)) => {
                // The error is in the panel.
                let _ = self.open_race(&files);
            }
            Some(ui::OpenRequest::Rescan) => self.rescan_races(),
            // The desktop's file dialog (the phone's panel offers none).
            #[cfg(not(target_os = "android"))]
            Some(ui::OpenRequest::Dialog) => {
                if let Some(files) = crate::panels::pick_race_files() {
                    let _ = self.open_race(&files);
                }
            }
            #[cfg(target_os = "android")]
            Some(ui::OpenRequest::Dialog) => {}
            None => {}
        }
    }
}
