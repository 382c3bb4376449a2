//! The Boats panel's debrief views (issue 28) read back through egui_kittest: every figure the
//! Manoeuvres, Start and Legs views show is parsed from the rendered labels and compared with
//! `race::Debrief`'s own figure for the embedded sample race, to the precision shown. Clicks on
//! a manoeuvre move race time to its start; a race without a start line says why; every wind
//! line names its source.

use egui::Vec2;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{By, NodeT, Queryable};
use ui::debrief::legs::legs_ui;
use ui::debrief::manoeuvre_table::manoeuvre_table_ui;
use ui::debrief::parse_signed;
use ui::debrief::start::start_ui;
use ui::{BoatsView, RaceClock, RegattaUi, UiFrame, wind_line};

mod common;
use common::sample_with_a_start_line;

/// Every text node (label or button) on screen: its text and centre, top to bottom then left
/// to right.
fn texts<S>(h: &Harness<'_, S>) -> Vec<(String, egui::Pos2)> {
    let mut v: Vec<(String, egui::Pos2)> = h
        .query_all(By::new().predicate(|n| {
            matches!(n.role(), Role::Label | Role::Button)
                && (n.label().is_some() || n.value().is_some())
        }))
        .map(|n| {
            let a = n.accesskit_node();
            (a.label().or(a.value()).unwrap(), n.rect().center())
        })
        .collect();
    v.sort_by(|a, b| a.1.y.total_cmp(&b.1.y).then(a.1.x.total_cmp(&b.1.x)));
    v
}

/// The cells on the same row as the first text equal to `first` at or below `below` (points),
/// left to right, `first` included; and that row's y.
fn row_of(all: &[(String, egui::Pos2)], first: &str, below: f32) -> (Vec<String>, f32) {
    let (_, p) = all
        .iter()
        .find(|(s, p)| s == first && p.y >= below)
        .unwrap_or_else(|| panic!("no row \"{first}\" below {below}: {all:?}"));
    let mut row: Vec<&(String, egui::Pos2)> = all
        .iter()
        .filter(|(_, q)| (q.y - p.y).abs() < 3.0 && q.x >= p.x)
        .collect();
    row.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));
    (row.into_iter().map(|(s, _)| s.clone()).collect(), p.y)
}

/// "12 m" → 12.
fn metres(s: &str) -> f64 {
    parse_signed(
        s.strip_suffix(" m")
            .unwrap_or_else(|| panic!("{s:?} is no metres")),
    )
    .unwrap_or_else(|| panic!("{s:?}"))
}

/// "12:04" or "1:02:03" → seconds.
fn clock_time(s: &str) -> f64 {
    s.split(':')
        .map(|p| p.parse::<f64>().unwrap_or_else(|_| panic!("{s:?}")))
        .fold(0.0, |acc, v| acc * 60.0 + v)
}

/// A shown whole number (rounded) matches the truth.
fn near(shown: f64, truth: f64, half_step: f64, what: &str) {
    assert!(
        (shown - truth).abs() <= half_step + 1e-9,
        "{what}: shown {shown}, debrief {truth}"
    );
}

/// A shown race-clock time (whole seconds, floored) matches the truth.
fn same_second(shown: &str, truth: f64, what: &str) {
    let s = clock_time(shown);
    assert!(
        (0.0..1.0).contains(&(truth - s)),
        "{what}: shown {shown}, debrief {truth}"
    );
}

struct Table {
    clock: RaceClock,
    selected: Option<usize>,
}

fn manoeuvre_harness<'a>(
    race: &'a race::Race,
    debrief: &'a race::Debrief,
    selected: Option<usize>,
) -> Harness<'a, Table> {
    let span = race.time_span();
    let mut clock = RaceClock::new(span);
    clock.scrub_to(span.0);
    Harness::builder()
        .with_size(Vec2::new(420.0, 1400.0))
        .build_ui_state(
            move |ui, s: &mut Table| {
                manoeuvre_table_ui(ui, race, debrief, s.selected, &mut s.clock);
            },
            Table { clock, selected },
        )
}

#[test]
fn the_manoeuvre_table_shows_the_debriefs_figures() {
    // The generated sample (8 boats) and the embedded real race (Valencia 2025-06-21 P01, two
    // dinghies, a wind the metadata state).
    for race in [race::Race::sample(), race::Race::valencia()] {
        manoeuvre_table_matches(&race);
    }
}

fn manoeuvre_table_matches(race: &race::Race) {
    let debrief = race::Debrief::of(race);
    let bm = debrief
        .manoeuvres
        .iter()
        .max_by_key(|b| b.manoeuvres.len())
        .unwrap();
    assert!(bm.manoeuvres.len() >= 2, "{}: its boats tack", race.name);
    let mut h = manoeuvre_harness(race, &debrief, Some(bm.boat));
    h.run();
    let all = texts(&h);
    // The wind it depends on, and its source (the sample's file states it).
    let w = debrief.wind.as_ref().unwrap();
    assert_eq!(
        all[0].0,
        format!("wind {:.0}°: from the race's data", w.from_deg)
    );
    let (_, header_y) = row_of(&all, "Boat", 0.0);
    for b in &debrief.manoeuvres {
        let (row, _) = row_of(&all, &b.id, header_y);
        assert_eq!(row.len(), 5, "{row:?}");
        assert_eq!(row[1].parse::<usize>().unwrap(), b.tacks, "{row:?}");
        assert_eq!(row[2].parse::<usize>().unwrap(), b.gybes, "{row:?}");
        match (b.median_loss_m, b.worst_loss_m) {
            (Some(median), Some(worst)) => {
                near(metres(&row[3]), median, 0.5, &format!("{} median", b.id));
                let (loss, when) = row[4].split_once(" at ").unwrap();
                near(metres(loss), worst, 0.5, &format!("{} worst", b.id));
                let w = b.manoeuvres.iter().find(|m| m.loss_m == worst).unwrap();
                same_second(when, w.t_entry, &format!("{} worst's time", b.id));
            }
            _ => assert_eq!((row[3].as_str(), row[4].as_str()), ("—", "—")),
        }
    }
    // The selected boat's list: one row per manoeuvre in order, its figures.
    let (_, list_y) = row_of(&all, "When", header_y);
    let mut below = list_y;
    for m in &bm.manoeuvres {
        let t = ui::format_race_time(m.t_entry);
        let (row, y) = row_of(&all, &t, below + 1.0);
        below = y;
        let kind = match m.kind {
            race::debrief::ManoeuvreKind::Tack => "tack",
            race::debrief::ManoeuvreKind::Gybe => "gybe",
        };
        assert_eq!(row[1], kind);
        near(
            row[2].strip_suffix(" s").unwrap().parse().unwrap(),
            m.duration_s,
            0.5,
            "duration",
        );
        let (a, b) = row[3].split_once('/').unwrap();
        let kn = ui::leaderboard::KNOTS_PER_MPS;
        near(a.parse().unwrap(), m.entry_speed_mps * kn, 0.05, "entry kn");
        near(b.parse().unwrap(), m.exit_speed_mps * kn, 0.05, "exit kn");
        near(metres(&row[4]), m.loss_m, 0.5, "loss");
    }
}

#[test]
fn clicking_a_manoeuvre_moves_race_time_to_its_start() {
    let race = race::Race::sample();
    let debrief = race::Debrief::of(&race);
    let bm = debrief
        .manoeuvres
        .iter()
        .max_by_key(|b| b.manoeuvres.len())
        .unwrap();
    let mut h = manoeuvre_harness(&race, &debrief, Some(bm.boat));
    h.run();
    // The list's second manoeuvre.
    let m = &bm.manoeuvres[1];
    h.get_by_label(&ui::format_race_time(m.t_entry)).click();
    h.run();
    assert_eq!(h.state().clock.time(), m.t_entry);
    assert!(!h.state().clock.is_playing());
    // The worst of another boat, from the fleet table.
    let other = debrief
        .manoeuvres
        .iter()
        .find(|b| b.boat != bm.boat && !b.manoeuvres.is_empty())
        .unwrap();
    let worst = ui::debrief::manoeuvre_table::worst_manoeuvre(other).unwrap();
    assert_eq!(Some(worst.loss_m), other.worst_loss_m);
    h.get_by_label(&ui::debrief::manoeuvre_table::format_worst(worst))
        .click();
    h.run();
    assert_eq!(h.state().clock.time(), worst.t_entry);
}

fn view_harness<'a>(size: Vec2, app: impl FnMut(&mut egui::Ui) + 'a) -> Harness<'a> {
    Harness::builder().with_size(size).build_ui(app)
}

#[test]
fn the_start_view_shows_the_debriefs_start() {
    let race = sample_with_a_start_line();
    let debrief = race::Debrief::of(&race);
    let report = debrief
        .start
        .as_ref()
        .expect("the sample race has a start line");
    // The line was made 5° off square with its west end (the pin, looking upwind into a wind
    // from the north) upwind: 120 m · sin 5° = 10.46 m.
    assert!((report.bias_deg - 5.0).abs() < 1e-9, "{}", report.bias_deg);
    assert!((report.bias_m - 120.0 * 5f64.to_radians().sin()).abs() < 1e-9);
    let mut h = view_harness(Vec2::new(420.0, 800.0), |ui| start_ui(ui, &race, &debrief));
    h.run();
    let all = texts(&h);
    let bias = all
        .iter()
        .find(|(s, _)| s.starts_with("Line "))
        .expect("the bias line");
    let favoured = if report.bias_m > 0.0 {
        "pin"
    } else {
        "committee"
    };
    assert!(
        bias.0.contains(&format!("{favoured} end favoured")),
        "{}",
        bias.0
    );
    let deg: f64 = bias
        .0
        .split(" by ")
        .nth(1)
        .unwrap()
        .split('°')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    near(deg, report.bias_deg.abs(), 0.05, "bias °");
    let m: f64 = bias
        .0
        .split(" (")
        .nth(1)
        .unwrap()
        .split(" m")
        .next()
        .unwrap()
        .parse()
        .unwrap();
    near(m, report.bias_m.abs(), 0.5, "bias m");
    let (_, header_y) = row_of(&all, "Boat", 0.0);
    let mut last_distance = f64::NEG_INFINITY;
    for b in &report.boats {
        let (row, _) = row_of(&all, &b.boat, header_y);
        near(
            metres(&row[1]),
            b.distance_to_line_m,
            0.5,
            "distance to line",
        );
        near(
            parse_signed(&row[2]).unwrap(),
            b.along_line_pct,
            0.5,
            "along",
        );
        near(
            row[3].parse().unwrap(),
            b.speed_mps * ui::leaderboard::KNOTS_PER_MPS,
            0.05,
            "kn",
        );
        match b.time_to_line_s {
            Some(s) => near(
                row[4].strip_suffix(" s").unwrap().parse().unwrap(),
                s,
                0.5,
                "late",
            ),
            None => assert_eq!(row[4], "—"),
        }
        assert_eq!(
            row.get(5).is_some_and(|s| s == "OCS"),
            b.over_early,
            "{row:?}"
        );
    }
    // Sorted by distance to the line, top to bottom.
    let mut rows: Vec<(f32, f64)> = report
        .boats
        .iter()
        .map(|b| (row_of(&all, &b.boat, header_y).1, b.distance_to_line_m))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, d) in rows {
        assert!(d >= last_distance, "not sorted by distance");
        last_distance = d;
    }
}

#[test]
fn a_race_without_a_start_line_says_why() {
    // The sample's course starts at a mark, not a line.
    let race = race::Race::sample();
    let debrief = race::Debrief::of(&race);
    let reason = debrief.start.clone().unwrap_err();
    let mut h = view_harness(Vec2::new(420.0, 200.0), |ui| start_ui(ui, &race, &debrief));
    h.run();
    h.get_by_label(&format!("No start line in this race: {reason}"));
    assert_eq!(texts(&h).len(), 1, "one calm line");
}

#[test]
fn the_legs_view_shows_the_debriefs_legs() {
    let race = race::Race::sample();
    let debrief = race::Debrief::of(&race);
    assert!(!debrief.legs.is_empty());
    let mut h = view_harness(Vec2::new(420.0, 4000.0), |ui| {
        legs_ui(ui, &race, &debrief.legs)
    });
    h.run();
    let all = texts(&h);
    for r in &debrief.legs {
        let heading = ui::debrief::legs::leg_heading(r);
        let (_, y0) = row_of(&all, &heading, 0.0);
        let (row, _) = row_of(&all, &r.boat, y0);
        same_second(&row[1], r.elapsed_s, "elapsed");
        assert_eq!(row[2].parse::<usize>().unwrap(), r.rank);
        match r.places_gained {
            Some(p) => assert_eq!(parse_signed(&row[3]).unwrap(), p as f64),
            None => assert_eq!(row[3], "—"),
        }
        near(
            parse_signed(&row[4]).unwrap(),
            r.seconds_gained,
            0.5,
            "seconds gained",
        );
        near(metres(&row[5]), r.sailed_m, 0.5, "sailed");
    }
}

#[test]
fn every_wind_line_names_its_source() {
    let race = race::Race::sample();
    let data = race::Debrief::of(&race);
    assert!(wind_line(data.wind.as_ref()).contains("from the race's data"));
    assert!(ui::plots::vmg_wind_note(&race).contains("from the race's data"));
    let mut estimated = race::Race::sample();
    estimated.wind = None;
    let e = race::Debrief::of(&estimated);
    let w = e.wind.as_ref().unwrap();
    assert_eq!(w.source, race::debrief::WindSource::Estimated);
    assert_eq!(
        wind_line(e.wind.as_ref()),
        format!(
            "wind {:.0}°: estimated from the fleet ±{:.1}°",
            w.from_deg, w.uncertainty_deg
        )
    );
    assert!(ui::plots::vmg_wind_note(&estimated).contains("No wind in the race's data"));
    // Rendered: the Manoeuvres view of the estimated race says so.
    let mut h = manoeuvre_harness(&estimated, &e, None);
    h.run();
    assert!(texts(&h)[0].0.contains("estimated from the fleet ±"));
}

/// The whole desktop layout with the Boats panel on `view` (Eos selected, race time 10:00),
/// for looking at.
fn snapshot_desktop(view: BoatsView) {
    let race = sample_with_a_start_line();
    let (t0, t1) = race.time_span();
    let rows = ui::leaderboard_rows(&race, 600.0);
    let mut clock = RaceClock::new((t0, t1));
    clock.scrub_to(600.0);
    let mut app = RegattaUi::new(clock, Vec::new());
    app.show_boats = true;
    app.boats_view = view;
    let name = format!("desktop_{}", view.label().to_lowercase());
    common::snapshot(&name, Vec2::new(1280.0, 800.0), move |ui| {
        ui.painter()
            .rect_filled(ui.max_rect(), 0.0, egui::Color32::from_rgb(150, 110, 70));
        app.show(
            ui,
            &UiFrame {
                rows: &rows,
                title: &race.name,
                race: Some(&race),
                selection: &[4],
                ..Default::default()
            },
        );
    });
}

#[test]
fn snapshot_desktop_manoeuvres() {
    snapshot_desktop(BoatsView::Manoeuvres);
}

#[test]
fn snapshot_desktop_start() {
    snapshot_desktop(BoatsView::Start);
}

#[test]
fn snapshot_desktop_legs() {
    snapshot_desktop(BoatsView::Legs);
}
