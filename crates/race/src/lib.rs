//! Races: boats' tracks and course marks in time.
//!
//! Import native race JSON, GPX and CSV boat logs (several files and kinds at once), project
//! latitude/longitude onto a local tangent plane in f64, clean the samples (spikes, frozen
//! fixes, duplicates, order, gaps) with a report, and answer "where is every boat at race time
//! t" in O(log n) per boat without allocating. Units: metres, seconds; x east, z south; race
//! time in seconds since the start. Knows nothing of wgpu, egui or Android.
//!
//! ```
//! let race = race::Race::sample();
//! let (t0, t1) = race.time_span();
//! let mut states = Vec::new();
//! race.states_at(0.5 * (t0 + t1), &mut states);
//! assert_eq!(states.len(), race.boats.len());
//! ```

use std::path::PathBuf;

use serde::{Deserialize, Serialize};
use time::OffsetDateTime;

pub mod clean;
pub mod course;
pub mod debrief;
pub mod error;
pub mod events;
pub mod geo;
mod import;
pub mod synth;
pub mod synth_formats;
pub mod synth_logs;
pub mod text;
pub mod track;

pub use clean::{BoatReport, Spike};
pub use course::{Mark, MarkKind, Standing};
pub use debrief::Debrief;
pub use error::{RaceError, RaceResult};
pub use events::{EventKind, RaceEvent, race_events};
pub use geo::{GeoPoint, LocalFrame};
pub use import::{
    DEFAULT_MAX_SPEED_KN, FileReport, Format, LoadOptions, MAX_FILE_BYTES, MAX_SAILING_SPEED_KN,
    Series,
};
pub use track::{Boat, BoatState, Fix};

/// The wind a file states (for the sea and the UI; nothing in the race depends on it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Wind {
    /// Compass direction the wind blows from, degrees.
    pub from_deg: f64,
    pub speed_mps: f64,
}

/// What importing did: files, origin, how the start was chosen, cleaning per boat, warnings.
/// `regatta race --report` prints it as JSON.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct LoadReport {
    pub files: Vec<String>,
    pub origin: Option<GeoPoint>,
    /// RFC 3339, where the files give absolute times.
    pub start_time: Option<String>,
    /// A phrase saying where the start came from.
    pub start_from: String,
    pub boats: Vec<BoatReport>,
    /// Per file: format, records read, fixes, channels, date source, rules that dropped data.
    pub file_reports: Vec<FileReport>,
    pub warnings: Vec<String>,
}

/// What a race's ranks mean.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RankBasis {
    /// Marks passed, then course distance still to sail.
    Course,
    /// No marks: no course rank exists; boats are listed by metres sailed.
    NoCourse,
}

/// One boat passing one course mark.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoundingEvent {
    /// Race seconds.
    pub t: f64,
    /// Index into `Race::boats`.
    pub boat: usize,
    /// Position in `Race::course` (0 = the start).
    pub course_index: usize,
    pub mark: String,
}

/// A race: boats, marks, course, and the clock they share.
#[derive(Debug, Clone)]
pub struct Race {
    pub name: String,
    /// The geographic point at race metres (0, 0), where the files are geographic.
    pub origin: Option<GeoPoint>,
    /// The wall-clock time of race time 0, where the files have one.
    pub start_time: Option<OffsetDateTime>,
    pub boats: Vec<Boat>,
    /// Every mark, in file order.
    pub marks: Vec<Mark>,
    /// Indices into `marks` in rounding order; `course[0]` is the start.
    pub course: Vec<usize>,
    pub wind: Option<Wind>,
    /// Radius (m) inside which a boat's closest approach to a mark counts as its rounding.
    pub rounding_radius_m: f64,
    pub report: LoadReport,
    /// Logged channels over time (wind, boat speed, heading, heel), race seconds.
    pub series: Vec<Series>,
    /// The course boundary polygon in race metres, where a file states one.
    pub boundary: Vec<[f64; 2]>,
    frame: Option<LocalFrame>,
    tail: Vec<f64>,
    /// The debrief's wind, worked out on first use ([`Race::wind_model`]).
    wind_model: std::sync::OnceLock<Option<debrief::WindModel>>,
}

/// The embedded default race: a generated eight-boat windward-leeward race
/// (`scripts/gen-fleet-race.sh`, see `assets/races/README.md`).
const SAMPLE: &[(&str, &[u8])] = &[(
    "assets/races/fleet.json",
    include_bytes!("../../../assets/races/fleet.json"),
)];

/// The real race shipped beside it (MIT, `assets/races/valencia/LICENSE`): two dinghies,
/// Valencia 2025-06-21, race P01, with the maxSail marks.
const VALENCIA: &[(&str, &[u8])] = &[
    (
        "assets/races/valencia/2025-06-21-ESP29375-P01.gpx",
        include_bytes!("../../../assets/races/valencia/2025-06-21-ESP29375-P01.gpx"),
    ),
    (
        "assets/races/valencia/2025-06-21-ESP30782-P01.gpx",
        include_bytes!("../../../assets/races/valencia/2025-06-21-ESP30782-P01.gpx"),
    ),
    (
        "assets/races/valencia/2025-06-21-ESP30782-P01-meta-data.json",
        include_bytes!("../../../assets/races/valencia/2025-06-21-ESP30782-P01-meta-data.json"),
    ),
];

impl Race {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        name: String,
        origin: Option<GeoPoint>,
        start_time: Option<OffsetDateTime>,
        mut boats: Vec<Boat>,
        marks: Vec<Mark>,
        course: Vec<usize>,
        wind: Option<Wind>,
        report: LoadReport,
    ) -> Race {
        let rounding_radius_m =
            course::rounding_radius(&marks, &course, course::typical_step(&boats));
        for b in &mut boats {
            b.roundings = course::detect_roundings(b, &marks, &course, rounding_radius_m);
        }
        let tail = course::tail_lengths(&marks, &course);
        Race {
            name,
            origin,
            start_time,
            boats,
            marks,
            course,
            wind,
            rounding_radius_m,
            report,
            series: Vec::new(),
            boundary: Vec::new(),
            frame: origin.map(LocalFrame::new),
            tail,
            wind_model: std::sync::OnceLock::new(),
        }
    }

    /// The embedded default race (the generated fleet).
    pub fn sample() -> Race {
        Race::from_files(SAMPLE).expect("the embedded sample race is valid (tested)")
    }

    /// The embedded real race: Valencia 2025-06-21 P01, two dinghies, marks S1 and B1.
    pub fn valencia() -> Race {
        Race::from_files(VALENCIA).expect("the embedded Valencia race is valid (tested)")
    }

    /// Read and combine race files (every format of [`Format`], detected by content).
    pub fn load(paths: &[PathBuf]) -> RaceResult<Race> {
        Race::load_with(paths, &LoadOptions::default())
    }

    /// [`Race::load`] with options (`--keep-going`, `--session`, `--course`).
    pub fn load_with(paths: &[PathBuf], opts: &LoadOptions) -> RaceResult<Race> {
        let mut files = Vec::with_capacity(paths.len());
        for p in paths {
            files.push((p.display().to_string(), read_file(p)?));
        }
        let refs: Vec<(&str, &[u8])> = files
            .iter()
            .map(|(n, b)| (n.as_str(), b.as_slice()))
            .collect();
        Race::from_files_with(&refs, opts)
    }

    /// Combine files given as (name, contents); the content says the kind.
    pub fn from_files(files: &[(&str, &[u8])]) -> RaceResult<Race> {
        Race::from_files_with(files, &LoadOptions::default())
    }

    /// [`Race::from_files`] with options.
    pub fn from_files_with(files: &[(&str, &[u8])], opts: &LoadOptions) -> RaceResult<Race> {
        let mut sources = Vec::with_capacity(files.len());
        for (name, bytes) in files {
            sources.push(import::parse(&text::escape(name), bytes, opts)?);
        }
        if let Some((name, bytes)) = &opts.marks {
            sources.push(import::marks::parse(&text::escape(name), bytes)?);
        }
        import::assemble(sources, opts)
    }

    /// What the ranks of [`Race::standings`] mean.
    pub fn rank_basis(&self) -> RankBasis {
        if self.course.len() >= 2 {
            RankBasis::Course
        } else {
            RankBasis::NoCourse
        }
    }

    /// First and last fix of any boat, race seconds.
    pub fn time_span(&self) -> (f64, f64) {
        let mut span = (f64::INFINITY, f64::NEG_INFINITY);
        for b in self.boats.iter().filter(|b| !b.fixes().is_empty()) {
            let (a, z) = b.time_span();
            span = (span.0.min(a), span.1.max(z));
        }
        if span.0 > span.1 { (0.0, 0.0) } else { span }
    }

    /// Every boat's state at race time t, in `boats` order, into `out` (cleared first; no
    /// allocation once it has room for every boat).
    pub fn states_at(&self, t: f64, out: &mut Vec<BoatState>) {
        out.clear();
        out.extend(self.boats.iter().map(|b| b.state_at(t)));
    }

    /// The leaderboard at time t (see [`course`]) from `states` (= `states_at(t)`), into `out`.
    pub fn standings_into(&self, t: f64, states: &[BoatState], out: &mut Vec<Standing>) {
        course::standings_into(
            t,
            &self.boats,
            states,
            &self.marks,
            &self.course,
            &self.tail,
            out,
        );
    }

    /// The leaderboard at time t, sorted by rank (allocates; see [`Race::standings_into`]).
    pub fn standings(&self, t: f64) -> Vec<Standing> {
        let mut states = Vec::new();
        self.states_at(t, &mut states);
        let mut out = Vec::new();
        self.standings_into(t, &states, &mut out);
        out
    }

    /// Every buoy to draw, once: single marks and the two ends of gates and lines.
    pub fn buoys(&self) -> Vec<[f64; 2]> {
        let mut out: Vec<[f64; 2]> = Vec::new();
        for p in self.marks.iter().flat_map(Mark::buoys) {
            if !out.iter().any(|q| (q[0] - p[0]).hypot(q[1] - p[1]) < 0.01) {
                out.push(p);
            }
        }
        out
    }

    /// The marks of the course in rounding order.
    pub fn course_marks(&self) -> impl Iterator<Item = &Mark> {
        self.course.iter().map(|&i| &self.marks[i])
    }

    /// Length of each leg (`course[k - 1]` → `course[k]`), metres.
    pub fn leg_lengths(&self) -> Vec<f64> {
        self.course
            .windows(2)
            .map(|w| {
                let (a, b) = (self.marks[w[0]].position, self.marks[w[1]].position);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
            .collect()
    }

    /// Latitude/longitude of race metres, where the race has an origin.
    pub fn to_geo(&self, xz: [f64; 2]) -> Option<GeoPoint> {
        self.frame.map(|f| f.to_geo(xz))
    }

    /// The box `[[x_min, z_min], [x_max, z_max]]` (race metres) around every fix and mark: what
    /// a table scene must fit. `None` for a race with nothing in it.
    pub fn bounds(&self) -> Option<[[f64; 2]; 2]> {
        let pts = self
            .boats
            .iter()
            .flat_map(|b| b.fixes().iter().map(|f| f.pos()))
            .chain(self.marks.iter().map(|m| m.position));
        let mut bb: Option<[[f64; 2]; 2]> = None;
        for p in pts {
            let b = bb.get_or_insert([p, p]);
            b[0] = [b[0][0].min(p[0]), b[0][1].min(p[1])];
            b[1] = [b[1][0].max(p[0]), b[1][1].max(p[1])];
        }
        bb
    }

    /// Every rounding of every boat, sorted by time: the timeline's jump targets.
    pub fn rounding_events(&self) -> Vec<RoundingEvent> {
        let mut v: Vec<RoundingEvent> = self
            .boats
            .iter()
            .enumerate()
            .flat_map(|(b, boat)| {
                boat.roundings()
                    .iter()
                    .enumerate()
                    .filter_map(move |(k, r)| r.map(|t| (b, k, t)))
            })
            .map(|(boat, leg, t)| RoundingEvent {
                t,
                boat,
                course_index: leg,
                mark: self.marks[self.course[leg]].name.clone(),
            })
            .collect();
        v.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.boat.cmp(&b.boat)));
        v
    }

    /// The race's wind over time: the files' where they bring one, else estimated from the
    /// fleet ([`debrief::wind`]); worked out once, on first use (the estimate samples every
    /// boat every 2 s, milliseconds for a race). `None` where neither exists.
    pub fn wind_model(&self) -> Option<&debrief::WindModel> {
        self.wind_model
            .get_or_init(|| debrief::race_wind(self))
            .as_ref()
    }

    /// The index of the boat with this id.
    pub fn boat_index(&self, id: &str) -> Option<usize> {
        self.boats.iter().position(|b| b.id == id)
    }
}

/// A race file's bytes: a regular file of at most [`MAX_FILE_BYTES`], checked before reading
/// to the end (a device such as `/dev/zero` never ends).
pub fn read_file(p: &std::path::Path) -> RaceResult<Vec<u8>> {
    use std::io::Read;
    let name = text::escape(&p.display().to_string());
    let open = |e: std::io::Error| RaceError::in_file(&name, format!("could not be read ({e})"));
    let meta = std::fs::metadata(p).map_err(open)?;
    if !meta.is_file() {
        return Err(RaceError::in_file(
            &name,
            "is not a regular file (a folder or a device); a race file is a file",
        ));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(RaceError::in_file(
            &name,
            format!(
                "is {} MB, over the {} MB a race file may have",
                meta.len() / 1_000_000,
                MAX_FILE_BYTES / 1_000_000
            ),
        ));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(p)
        .map_err(open)?
        .take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(open)?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(RaceError::in_file(
            &name,
            format!(
                "grew past the {} MB a race file may have while it was read",
                MAX_FILE_BYTES / 1_000_000
            ),
        ));
    }
    Ok(bytes)
}
