//! Races opened the Android way: a race file from "Open with" or "Share" (the intent's
//! `content://` URI read through the ContentResolver, [`read_intent`]) is loaded and fitted to
//! the table, and kept in the races folder so that the Races panel lists it next time (a file
//! kept before is not kept twice: its race folder opens). A file
//! of the same race as the one shown (their time spans and areas overlap: another boat's
//! track of the same race) joins it, asking nothing: the race's sub-folder gets the file and
//! the race is read again with one more boat. Any other file opens as its own race, in a
//! sub-folder of its own (so that its other boats join it later). A file that does not load is
//! said in one sentence on the banner and in the Races panel; the race shown stays and the file
//! is not kept.
//!
//! Each share starts a new Activity on Android (a `NativeActivity` never sees `onNewIntent`),
//! so "the race shown" outlives the Activity: the races folder's `.shown` names the race last
//! opened, and a freshly started app that still shows the embedded race compares with that one.

use std::path::{Path, PathBuf};

use ar::arcore::ffi::{IntentJni, JavaObject};

use super::App;
use crate::hud::banner::Tone;

/// The largest file read from a share, bytes: the whole file is held in memory on the phone
/// (the importer's own limit for files on disk is 1 GiB; the longest real log here is 3 MB).
pub const SHARED_MAX_BYTES: u64 = 256 << 20;

/// How long the banner says what a share did, seconds of app time.
pub const NOTICE_S: f64 = 6.0;

/// The file in the races folder that names the race last opened there.
const SHOWN_FILE: &str = ".shown";

/// The extension a shared file is kept with when its name has no race extension, by the
/// intent's MIME type (the importer tells the format by content; the extension only makes the
/// Races panel list the file). The MIME types are those of app/Cargo.toml's intent filters.
pub const EXTENSION_OF_MIME: [(&str, &str); 9] = [
    ("application/gpx+xml", "gpx"),
    ("application/gpx", "gpx"),
    ("text/csv", "csv"),
    ("text/comma-separated-values", "csv"),
    ("application/csv", "csv"),
    ("text/xml", "xml"),
    ("application/xml", "xml"),
    ("application/json", "json"),
    ("text/plain", "txt"),
];

/// A file handed over by a share, read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SharedFile {
    /// The name it is kept under: no folders, no control characters, a race extension.
    pub name: String,
    pub bytes: Vec<u8>,
}

/// What opening a shared file did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Opened {
    /// A race of its own, shown now.
    Race,
    /// The file's boats joined the race shown.
    BoatsAdded(usize),
}

/// The name a shared file is kept under: the provider's display name, else the URI's last
/// segment; only its last path component, control and reserved characters dropped, at most
/// 100 characters; with the extension of `mime` appended when it has no race extension.
pub fn kept_name(display: Option<&str>, uri: &str, mime: Option<&str>) -> String {
    let raw = display
        .filter(|d| !d.trim().is_empty())
        .unwrap_or_else(|| uri.rsplit('/').next().unwrap_or(""));
    let last = raw.rsplit(['/', '\\']).next().unwrap_or("");
    let mut name: String = last
        .chars()
        .filter(|c| !c.is_control() && !":*?\"<>|".contains(*c))
        .collect();
    name = name.trim().trim_start_matches('.').to_string();
    if name.chars().count() > 100 {
        name = name.chars().skip(name.chars().count() - 100).collect();
    }
    if name.is_empty() {
        name = "shared".into();
    }
    let has_race_extension = Path::new(&name)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ui::open::RACE_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()));
    if !has_race_extension {
        let mime = mime.map(|m| {
            m.split(';')
                .next()
                .unwrap_or("")
                .trim()
                .to_ascii_lowercase()
        });
        let ext = EXTENSION_OF_MIME
            .iter()
            .find(|(m, _)| Some(*m) == mime.as_deref())
            .map_or("txt", |(_, e)| e);
        name = format!("{name}.{ext}");
    }
    name
}

/// The file the Activity was started with, read through the ContentResolver (at most
/// [`SHARED_MAX_BYTES`]); `Ok(None)` when it was started without one. An error is one
/// sentence naming the file.
pub fn read_intent(jni: &dyn IntentJni) -> Result<Option<SharedFile>, String> {
    let Some(intent) = jni.intent_file(JavaObject::Activity)? else {
        return Ok(None);
    };
    // A provider that cannot say the name still gives the bytes: the URI names the file then.
    let display = jni
        .content_name(JavaObject::Activity, &intent.uri)
        .unwrap_or_else(|e| {
            log::warn!(
                "regatta: {}: no display name ({e})",
                input::escape_controls(&intent.uri)
            );
            None
        });
    let name = kept_name(display.as_deref(), &intent.uri, intent.mime.as_deref());
    let shown = input::quote(&name);
    let bytes = jni
        .read_content(JavaObject::Activity, &intent.uri, SHARED_MAX_BYTES)
        .map_err(|e| input::one_line(&format!("{shown} could not be read ({e})")))?;
    if bytes.len() as u64 > SHARED_MAX_BYTES {
        return Err(format!(
            "{shown} is over the {} MB a shared race file may have",
            SHARED_MAX_BYTES >> 20
        ));
    }
    Ok(Some(SharedFile { name, bytes }))
}

/// Where and when a race happened: absolute seconds (Unix time) and degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Footprint {
    seconds: [f64; 2],
    lat: [f64; 2],
    lon: [f64; 2],
}

/// The race's time span in Unix seconds and its bounds in latitude and longitude; `None` for
/// a race without wall-clock time or geographic origin (it is never "the same race").
fn footprint(race: &race::Race) -> Option<Footprint> {
    let start = race.start_time?;
    let [lo, hi] = race.bounds()?;
    let zero = start.unix_timestamp_nanos() as f64 * 1e-9;
    let (a, z) = race.time_span();
    let mut lat = [f64::INFINITY, f64::NEG_INFINITY];
    let mut lon = lat;
    for xz in [lo, hi, [lo[0], hi[1]], [hi[0], lo[1]]] {
        let g = race.to_geo(xz)?;
        lat = [lat[0].min(g.lat), lat[1].max(g.lat)];
        lon = [lon[0].min(g.lon), lon[1].max(g.lon)];
    }
    Some(Footprint {
        seconds: [zero + a, zero + z],
        lat,
        lon,
    })
}

/// Whether two races are one: their time spans overlap and so do their areas.
fn same_race(a: &Footprint, b: &Footprint) -> bool {
    let meet = |x: [f64; 2], y: [f64; 2]| x[0] <= y[1] && y[0] <= x[1];
    meet(a.seconds, b.seconds) && meet(a.lat, b.lat) && meet(a.lon, b.lon)
}

/// `dir/stem`, or `dir/stem-2`, `-3`, … : the first that does not exist.
fn unused(dir: &Path, stem: &str, ext: Option<&str>) -> PathBuf {
    let named = |n: String| dir.join(ext.map_or(n.clone(), |e| format!("{n}.{e}")));
    let first = named(stem.to_string());
    if !first.exists() {
        return first;
    }
    (2..)
        .map(|i| named(format!("{stem}-{i}")))
        .find(|p| !p.exists())
        .expect("some name is free")
}

/// Writes `file` into the race folder `folder` (made when missing) unless the same bytes are
/// there under its name already; returns the path and whether it was written.
fn write_into(folder: &Path, file: &SharedFile) -> Result<(PathBuf, bool), String> {
    let fail =
        |p: &Path, e: std::io::Error| format!("{} could not be kept ({e})", input::show_path(p));
    std::fs::create_dir_all(folder).map_err(|e| fail(folder, e))?;
    let at = folder.join(&file.name);
    if std::fs::read(&at).is_ok_and(|b| b == file.bytes) {
        return Ok((at, false));
    }
    let path = Path::new(&file.name);
    let at = if at.exists() {
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("shared");
        unused(folder, stem, path.extension().and_then(|e| e.to_str()))
    } else {
        at
    };
    std::fs::write(&at, &file.bytes).map_err(|e| fail(&at, e))?;
    Ok((at, true))
}

impl App {
    /// Reads the Activity's intent and opens its file, if it has one (the Android adapter, at
    /// start; `open FILE` in a phone-sim script).
    pub fn open_intent(&mut self, jni: &dyn IntentJni) -> Option<Result<Opened, String>> {
        match read_intent(jni) {
            Ok(None) => None,
            Ok(Some(file)) => Some(self.open_shared(&file)),
            Err(e) => Some(Err(self.shared_failed(e))),
        }
    }

    /// Opens a shared race file: its own race, or more boats of the race shown (see the module
    /// docs). On failure the banner and the Races panel say why in one sentence and the race
    /// shown stays.
    pub fn open_shared(&mut self, file: &SharedFile) -> Result<Opened, String> {
        match self.open_shared_inner(file) {
            Ok((opened, race)) => {
                let what = match &opened {
                    Opened::Race => format!("Opened {}.", input::quote(&file.name)),
                    Opened::BoatsAdded(0) => {
                        format!("{} is in this race already.", input::quote(&file.name))
                    }
                    Opened::BoatsAdded(n) => format!(
                        "Added {} boat{} from {} to this race.",
                        n,
                        if *n == 1 { "" } else { "s" },
                        input::quote(&file.name)
                    ),
                };
                log::info!("regatta: {what}");
                self.set_race(race);
                self.races.error = None;
                self.notice = Some((what, Tone::Hint, self.now + NOTICE_S));
                self.rescan_races();
                Ok(opened)
            }
            Err(e) => Err(self.shared_failed(e)),
        }
    }

    fn shared_failed(&mut self, e: String) -> String {
        let e = input::one_line(&e);
        log::warn!("regatta: {e}");
        self.races.error = Some(e.clone());
        self.notice = Some((e.clone(), Tone::Warning, self.now + NOTICE_S));
        e
    }

    /// The race of `file`, with the race shown's boats when it is the same race; keeps the
    /// file in the races folder.
    fn open_shared_inner(&mut self, file: &SharedFile) -> Result<(Opened, race::Race), String> {
        // The file alone first: a broken file is refused before anything is kept.
        let alone = race::Race::from_files(&[(file.name.as_str(), file.bytes.as_slice())])
            .map_err(|e| e.to_string())?;
        if alone.boats.is_empty() {
            return Err(format!(
                "{}: no boat tracks in it (only marks or a course?); share the boats' files",
                input::quote(&file.name)
            ));
        }
        let Some(dir) = self.races.dir.clone() else {
            log::warn!("regatta: no races folder: {} is shown, not kept", file.name);
            return Ok((Opened::Race, alone));
        };
        if let Some((entry, files)) = self.open_entry(&dir)
            && let Some(open) = self.race_of_entry(&entry, &files)
            && let (Some(a), Some(b)) = (footprint(&open), footprint(&alone))
            && same_race(&a, &b)
        {
            let folder = dir.join(&entry);
            if folder.is_file() {
                // A race kept as one file becomes a folder, so its boats stay together.
                let stem = Path::new(&entry).file_stem().and_then(|s| s.to_str());
                let moved_into = unused(&dir, stem.unwrap_or("shared"), None);
                std::fs::create_dir_all(&moved_into)
                    .and_then(|()| std::fs::rename(&folder, moved_into.join(&entry)))
                    .map_err(|e| {
                        format!("{} could not be kept ({e})", input::show_path(&folder))
                    })?;
                return self.join(&dir, &moved_into, file, open.boats.len());
            }
            return self.join(&dir, &folder, file, open.boats.len());
        }
        let path = Path::new(&file.name);
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("shared");
        // The same file kept before (shared again another day): its race folder, all boats.
        let before = dir.join(stem);
        if std::fs::read(before.join(&file.name)).is_ok_and(|b| b == file.bytes)
            && let Ok(race) = crate::panels::load_race_files(&race_files(&before))
        {
            self.remember_shown(&dir, &before);
            return Ok((Opened::Race, race));
        }
        let folder = unused(&dir, stem, None);
        let (kept, _) = write_into(&folder, file)?;
        self.remember_shown(&dir, &folder);
        log::info!("regatta: kept {}", input::show_path(&kept));
        Ok((Opened::Race, alone))
    }

    /// Adds `file` to the race folder `folder` (whose race had `boats_before` boats) and reads
    /// the race again from all its files.
    fn join(
        &mut self,
        dir: &Path,
        folder: &Path,
        file: &SharedFile,
        boats_before: usize,
    ) -> Result<(Opened, race::Race), String> {
        let (kept, written) = write_into(folder, file)?;
        let files = race_files(folder);
        match crate::panels::load_race_files(&files) {
            Ok(race) => {
                self.remember_shown(dir, folder);
                let added = race.boats.len().saturating_sub(boats_before);
                Ok((Opened::BoatsAdded(added), race))
            }
            Err(e) => {
                if written {
                    let _ = std::fs::remove_file(&kept);
                }
                Err(e)
            }
        }
    }

    /// The race open now, as an entry of the races folder and its files: the one shown, else
    /// (the embedded race is shown: a fresh start) the one last opened.
    fn open_entry(&self, dir: &Path) -> Option<(String, Vec<PathBuf>)> {
        let name = match &self.races.shown {
            Some(n) => n.clone(),
            None => std::fs::read_to_string(dir.join(SHOWN_FILE))
                .ok()?
                .trim()
                .to_string(),
        };
        let path = dir.join(&name);
        let files = if path.is_dir() {
            race_files(&path)
        } else {
            vec![path]
        };
        (!name.is_empty() && files.iter().all(|f| f.is_file()) && !files.is_empty())
            .then_some((name, files))
    }

    /// The race of the entry `name`: the one shown when it is that entry, else read from its
    /// files (`None` when they no longer load).
    fn race_of_entry(&self, name: &str, files: &[PathBuf]) -> Option<race::Race> {
        if self.races.shown.as_deref() == Some(name) {
            return Some(self.world.race.clone());
        }
        crate::panels::load_race_files(files).ok()
    }

    /// Notes `entry` (a path in `dir`) as the race shown, here and in the folder's `.shown`.
    pub(super) fn remember_shown(&mut self, dir: &Path, entry: &Path) {
        let name = entry
            .strip_prefix(dir)
            .unwrap_or(entry)
            .to_string_lossy()
            .into_owned();
        if let Err(e) = std::fs::write(dir.join(SHOWN_FILE), &name) {
            log::warn!("regatta: {}: {e}", input::show_path(&dir.join(SHOWN_FILE)));
        }
        self.races.shown = Some(name);
    }
}

/// The race files of a race folder, sorted (as the Races panel lists them).
fn race_files(folder: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(folder)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    files.retain(|p| {
        p.is_file()
            && !p
                .file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with('.'))
            && p.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                ui::open::RACE_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str())
            })
    });
    files.sort();
    files
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_name_has_no_folders_or_controls_and_a_race_extension() {
        assert_eq!(
            kept_name(Some("boat.gpx"), "content://p/1", None),
            "boat.gpx"
        );
        assert_eq!(
            kept_name(Some("../../etc/passwd"), "content://p/1", None),
            "passwd.txt"
        );
        assert_eq!(
            kept_name(Some("a\u{1b}[31mb.GPX"), "content://p/1", None),
            "a[31mb.GPX"
        );
        assert_eq!(
            kept_name(
                None,
                "content://p/docs/race%201",
                Some("application/gpx+xml")
            ),
            "race%201.gpx"
        );
        assert_eq!(
            kept_name(Some("  "), "content://p/", Some("text/csv; charset=utf-8")),
            "shared.csv"
        );
        assert_eq!(
            kept_name(Some(".hidden.json"), "content://p/1", None),
            "hidden.json"
        );
        let long = format!("{}.gpx", "x".repeat(300));
        assert_eq!(kept_name(Some(&long), "u", None).chars().count(), 100);
    }

    #[test]
    fn races_meet_only_when_time_and_area_both_overlap() {
        let a = Footprint {
            seconds: [0.0, 100.0],
            lat: [39.0, 39.1],
            lon: [-0.3, -0.2],
        };
        assert!(same_race(&a, &a));
        let later = Footprint {
            seconds: [101.0, 200.0],
            ..a
        };
        assert!(!same_race(&a, &later));
        let elsewhere = Footprint {
            lat: [54.3, 54.4],
            ..a
        };
        assert!(!same_race(&a, &elsewhere));
        let overlapping = Footprint {
            seconds: [50.0, 150.0],
            lat: [39.05, 39.2],
            lon: [-0.25, -0.1],
        };
        assert!(same_race(&a, &overlapping));
    }
}
