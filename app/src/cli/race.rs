//! `regatta race --t T [--race PATH ...]`: boat states and ranks at one race time (docs/command-line.md
//! contract); `regatta race --report`: the import and cleaning report and the debrief
//! (wind, manoeuvres, start, legs). Files of every format
//! of docs/race-files.md; `--keep-going`, `--session N`, `--marks FILE`, `--course A,B,C`.

use std::path::PathBuf;

use clap::Args;
use serde_json::{Value, json};

use crate::error::{AppError, AppResult};
use crate::setup::inputs::load_race_with;

#[derive(Debug, Args)]
pub struct RaceArgs {
    /// Race time in seconds since the start.
    #[arg(long, allow_negative_numbers = true)]
    pub t: Option<f64>,
    /// Race files (native race JSON, maxSail JSON, GPX, CSV logs and exports, Expedition, NMEA
    /// 0183, SailGP / AC race XML, FIT, TCX, KML / KMZ, NMEA 2000 logs: candump, Actisense CSV,
    /// canboat JSON; several combine into one race). Default: the sample.
    #[arg(long, num_args = 1..)]
    pub race: Vec<PathBuf>,
    /// Print the import and cleaning report (and the course and roundings) instead.
    #[arg(long)]
    pub report: bool,
    /// Load boats even when cleaning drops more than half of their samples (with a warning).
    #[arg(long)]
    pub keep_going: bool,
    /// For GPX tracks of several days: the session to race (1-based).
    #[arg(long, allow_negative_numbers = true,
        value_parser = super::inputs::whole_number::<usize>("from 1 (the first session)"))]
    pub session: Option<usize>,
    /// Course marks for tracks that have none: GPX waypoints, a SailGP/AC race XML (its course
    /// in order), JSON, or CSV (name,lat,lon, or columns named by a header).
    #[arg(long)]
    pub marks: Option<PathBuf>,
    /// The course as mark names in order, e.g. S,W,G1a/G1b,F (a gate as two names with /), or a
    /// course file (a race XML) read as --marks.
    #[arg(long, value_delimiter = ',')]
    pub course: Vec<String>,
}

impl RaceArgs {
    /// The load options these flags ask for.
    pub fn load_options(&self) -> AppResult<race::LoadOptions> {
        // `--course FILE`: one value naming a file is a course file (a race XML), read as marks.
        let course_file = match self.course.as_slice() {
            [one] if std::path::Path::new(one).is_file() => Some(PathBuf::from(one)),
            _ => None,
        };
        if course_file.is_some() && self.marks.is_some() {
            return Err(AppError::new(
                "--course names a file and --marks gives marks too; give the course file once",
            ));
        }
        let marks = match self.marks.as_ref().or(course_file.as_ref()) {
            Some(p) => Some((
                p.display().to_string(),
                race::read_file(p).map_err(|e| AppError::new(e.to_string()))?,
            )),
            None => None,
        };
        if self.session == Some(0) {
            return Err(AppError::new("--session counts from 1"));
        }
        Ok(race::LoadOptions {
            keep_going: self.keep_going,
            session: self.session,
            course: (!self.course.is_empty() && course_file.is_none()).then(|| self.course.clone()),
            marks,
        })
    }
}

pub fn run(a: RaceArgs) -> AppResult {
    if !a.report && a.t.is_none() {
        return Err(AppError::new(
            "regatta race needs --t SECONDS (or --report for the import report)",
        ));
    }
    if let Some(t) = a.t {
        super::inputs::check_race_time(t)?;
    }
    let race = load_race_with(&a.race, &a.load_options()?)?;
    let out = if a.report {
        report_json(&race)
    } else {
        states_json(&race, a.t.unwrap_or(0.0))
    };
    crate::terminal::print_stdout("the race JSON", &out)
}

/// The docs/command-line.md JSON of `regatta race --t T`.
pub fn states_json(race: &race::Race, t: f64) -> Value {
    let mut states = Vec::new();
    race.states_at(t, &mut states);
    let mut standings = Vec::new();
    race.standings_into(t, &states, &mut standings);
    let boats: Vec<Value> = standings
        .iter()
        .map(|st| {
            let b = &race.boats[st.boat];
            let s = &states[st.boat];
            let mut o = json!({
                "id": b.id,
                "name": b.name,
                "position": s.position,
                "heading_deg": s.heading_deg,
                "speed_mps": s.speed_mps,
                "rank": st.rank,
                "distance_m": st.distance_m,
                "racing": s.racing,
            });
            if let Some(g) = race.to_geo(s.position) {
                o["lat"] = json!(g.lat);
                o["lon"] = json!(g.lon);
            }
            o
        })
        .collect();
    json!({ "t": t, "rank_basis": rank_basis(race), "boats": boats })
}

/// What `rank` means: "course" (marks passed, then distance to sail) or "no_course" (no
/// marks: listed by metres sailed, which is no rank).
fn rank_basis(race: &race::Race) -> Value {
    json!(race.rank_basis())
}

fn report_json(race: &race::Race) -> Value {
    let (t0, t1) = race.time_span();
    let debrief = race::Debrief::of(race);
    let start = match &debrief.start {
        Ok(s) => json!(s),
        Err(why) => json!({ "none": why }),
    };
    let marks: Vec<&str> = race.course_marks().map(|m| m.name.as_str()).collect();
    let roundings: Vec<Value> = race
        .boats
        .iter()
        .map(|b| json!({ "id": b.id, "times": b.roundings() }))
        .collect();
    json!({
        "name": race.name,
        "time_span": [t0, t1],
        "marks": race.marks,
        "course": marks,
        "leg_lengths_m": race.leg_lengths(),
        "rounding_radius_m": race.rounding_radius_m,
        "wind": debrief.wind,
        "manoeuvres": debrief.manoeuvres,
        "start": start,
        "legs": debrief.legs,
        "rank_basis": rank_basis(race),
        "boundary": race.boundary,
        "series": race
            .series
            .iter()
            .map(|s| json!({"boat": s.boat, "channel": s.channel, "unit": s.unit, "samples": s.t.len()}))
            .collect::<Vec<_>>(),
        "roundings": roundings,
        "import": race.report,
    })
}
