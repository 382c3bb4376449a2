//! The leaderboard: rank, boat, speed, heading and distance behind the leader at race time t.

use egui::{Color32, RichText, Ui};
use race::{BoatState, Race, Standing};

/// Metres per second to knots.
pub const KNOTS_PER_MPS: f64 = 3600.0 / 1852.0;

/// One line of the leaderboard.
#[derive(Clone, Debug, PartialEq)]
pub struct LeaderboardRow {
    /// Index into `Race::boats`.
    pub boat: usize,
    pub rank: usize,
    pub name: String,
    pub color: Color32,
    pub speed_kn: f64,
    /// Compass degrees.
    pub heading_deg: f64,
    /// Course metres behind the leader.
    pub behind_m: f64,
    /// Marks passed / marks in the course.
    pub legs: (usize, usize),
    pub racing: bool,
    pub finished: bool,
}

/// The leaderboard rows at race time `t`, sorted by rank.
pub fn leaderboard_rows(race: &Race, t: f64) -> Vec<LeaderboardRow> {
    let mut states: Vec<BoatState> = Vec::new();
    race.states_at(t, &mut states);
    let mut standings: Vec<Standing> = Vec::new();
    race.standings_into(t, &states, &mut standings);
    standings.sort_by_key(|s| s.rank);
    standings
        .iter()
        .map(|s| {
            let boat = &race.boats[s.boat];
            let st = &states[s.boat];
            LeaderboardRow {
                boat: s.boat,
                rank: s.rank,
                name: if boat.name.is_empty() {
                    boat.id.clone()
                } else {
                    boat.name.clone()
                },
                color: parse_hex_color(&boat.color).unwrap_or(Color32::GRAY),
                speed_kn: st.speed_mps * KNOTS_PER_MPS,
                heading_deg: st.heading_deg,
                behind_m: s.distance_m,
                legs: (s.legs_completed, race.course.len()),
                racing: s.racing,
                finished: s.finished,
            }
        })
        .collect()
}

/// `#rrggbb` to a colour.
pub fn parse_hex_color(s: &str) -> Option<Color32> {
    let h = s.strip_prefix('#')?;
    if h.len() != 6 {
        return None;
    }
    let v = u32::from_str_radix(h, 16).ok()?;
    Some(Color32::from_rgb((v >> 16) as u8, (v >> 8) as u8, v as u8))
}

/// The line under the grid when the race has no course (fewer than two marks): the order is
/// by metres sailed, which is no rank.
pub const NO_COURSE_NOTE: &str = "No course: listed by metres sailed, not ranked";

/// Whether the rows come from a race without a course (see [`race::RankBasis`]).
pub fn has_no_course(rows: &[LeaderboardRow]) -> bool {
    rows.first().is_some_and(|r| r.legs.1 < 2)
}

/// Draws the rows as a striped grid (and says so when there is no course to rank on); the
/// boats in `selection` are highlighted. Returns the boat whose name was clicked (to select it).
pub fn leaderboard_ui(ui: &mut Ui, rows: &[LeaderboardRow], selection: &[usize]) -> Option<usize> {
    let clicked = leaderboard_grid(ui, rows, selection);
    if has_no_course(rows) {
        ui.label(RichText::new(NO_COURSE_NOTE).weak());
    }
    clicked
}

fn leaderboard_grid(ui: &mut Ui, rows: &[LeaderboardRow], selection: &[usize]) -> Option<usize> {
    let mut clicked = None;
    egui::Grid::new("leaderboard")
        .num_columns(6)
        .striped(true)
        .spacing([10.0, 4.0])
        .show(ui, |ui| {
            for h in ["#", "Boat", "kn", "Hdg", "Behind", "Marks"] {
                ui.label(RichText::new(h).strong());
            }
            ui.end_row();
            for r in rows {
                ui.label(RichText::new(r.rank.to_string()).strong());
                ui.horizontal(|ui| {
                    let (rect, _) =
                        ui.allocate_exact_size(egui::vec2(10.0, 10.0), egui::Sense::hover());
                    ui.painter().rect_filled(rect, 2.0, r.color);
                    let mut name = RichText::new(&r.name);
                    if !r.racing && !r.finished {
                        name = name.weak();
                    }
                    if ui
                        .selectable_label(selection.contains(&r.boat), name)
                        .on_hover_text("Select (two to compare)")
                        .clicked()
                    {
                        clicked = Some(r.boat);
                    }
                });
                ui.label(format!("{:.1}", r.speed_kn));
                ui.label(format!("{:03.0}°", r.heading_deg));
                ui.label(if r.rank == 1 {
                    "—".to_string()
                } else {
                    format_distance(r.behind_m)
                });
                ui.label(if r.finished {
                    "fin".to_string()
                } else {
                    format!("{}/{}", r.legs.0, r.legs.1)
                });
                ui.end_row();
            }
        });
    clicked
}

/// `35 m`, `1.24 km`.
pub fn format_distance(m: f64) -> String {
    if m.abs() < 1000.0 {
        format!("{m:.0} m")
    } else {
        format!("{:.2} km", m / 1000.0)
    }
}
