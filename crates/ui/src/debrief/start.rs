//! The Start view: each boat at the gun (race time 0) against the start line, closest first,
//! and the line's bias; or, without a start line, the one reason why not.

use egui::Ui;
use race::debrief::{BoatStart, StartReport};

use super::{boat_name, header_row, metres, note, number, wind_line};
use crate::leaderboard::KNOTS_PER_MPS;

/// The line when the race has none: "No start line in this race: the race has no course".
pub fn no_start_line_text(reason: &str) -> String {
    format!("No start line in this race: {reason}")
}

/// The line's bias in words: which end is upwind (favoured), by how many degrees off square to
/// the wind and how many metres further upwind.
pub fn bias_text(r: &StartReport) -> String {
    let end = if r.bias_m > 0.0 { "pin" } else { "committee" };
    if r.bias_deg.abs() < 0.05 {
        format!("Line {:.0} m, square to the wind", r.line_length_m)
    } else {
        format!(
            "Line {:.0} m; {end} end favoured by {:.1}° ({:.0} m upwind)",
            r.line_length_m,
            r.bias_deg.abs(),
            r.bias_m.abs()
        )
    }
}

/// The boats at the gun sorted by distance to the line: over it (negative) first, then the
/// closest behind it.
pub fn by_distance(r: &StartReport) -> Vec<&BoatStart> {
    let mut v: Vec<&BoatStart> = r.boats.iter().collect();
    v.sort_by(|a, b| a.distance_to_line_m.total_cmp(&b.distance_to_line_m));
    v
}

/// The Start view.
pub fn start_ui(ui: &mut Ui, race: &race::Race, debrief: &race::Debrief) {
    let report = match &debrief.start {
        Ok(r) => r,
        Err(reason) => {
            ui.label(no_start_line_text(reason));
            return;
        }
    };
    ui.label(wind_line(debrief.wind.as_ref()));
    ui.label(bias_text(report));
    egui::Grid::new("start-table")
        .num_columns(6)
        .striped(true)
        .spacing([8.0, 4.0])
        .show(ui, |ui| {
            header_row(
                ui,
                &[
                    ("Boat", ""),
                    (
                        "To line",
                        "Metres behind the line at the gun (negative: over it)",
                    ),
                    (
                        "Along",
                        "Where along the line: 0 % the pin, 100 % the committee end",
                    ),
                    ("kn", "Speed at the gun"),
                    ("Late", "Seconds to the line at the gun's speed towards it"),
                    ("Over", "On the course side at the gun"),
                ],
            );
            for b in by_distance(report) {
                boat_name(ui, race, &b.boat);
                ui.label(metres(b.distance_to_line_m));
                ui.label(format!("{} %", number(b.along_line_pct, 0)));
                ui.label(format!("{:.1}", b.speed_mps * KNOTS_PER_MPS));
                ui.label(b.time_to_line_s.map_or("—".into(), |s| format!("{s:.0} s")));
                ui.label(if b.over_early { "OCS" } else { "" });
                ui.end_row();
            }
        });
    note(ui, "At the gun; pin = the left end looking upwind");
}
