//! The Legs view: per leg (course mark to mark) each boat's elapsed time, rank at the leg's
//! end, places and seconds gained on the leg, and the metres it sailed against the leg's
//! length.

use egui::{RichText, Ui};
use race::debrief::LegResult;

use super::{boat_name, header_row, metres, note, signed};
use crate::clock::format_race_time;

/// "Leg 2 to L1 (1.24 km)".
pub fn leg_heading(r: &LegResult) -> String {
    format!(
        "Leg {} to {} ({})",
        r.leg,
        r.to_mark,
        crate::leaderboard::format_distance(r.leg_length_m)
    )
}

/// The Legs view.
pub fn legs_ui(ui: &mut Ui, race: &race::Race, legs: &[LegResult]) {
    if legs.is_empty() {
        note(
            ui,
            "No legs: the race has no course, or no boat rounded a mark",
        );
        return;
    }
    let mut k = 0;
    while k < legs.len() {
        let leg = legs[k].leg;
        let n = legs[k..].iter().take_while(|r| r.leg == leg).count();
        let rows = &legs[k..k + n];
        k += n;
        ui.label(RichText::new(leg_heading(&rows[0])).strong());
        egui::Grid::new(("legs-table", leg))
            .num_columns(6)
            .striped(true)
            .spacing([8.0, 4.0])
            .show(ui, |ui| {
                header_row(
                    ui,
                    &[
                        ("Boat", ""),
                        ("Time", "Elapsed on the leg"),
                        ("Rank", "Order rounding the leg's end"),
                        ("Places", "Places gained on the leg"),
                        ("Secs", "Seconds gained on the leader of each mark"),
                        ("Sailed", "Metres sailed on the leg"),
                    ],
                );
                for r in rows {
                    boat_name(ui, race, &r.boat);
                    ui.label(format_race_time(r.elapsed_s));
                    ui.label(r.rank.to_string());
                    ui.label(r.places_gained.map_or("—".into(), |p| signed(p as f64, 0)));
                    ui.label(signed(r.seconds_gained, 0));
                    ui.label(metres(r.sailed_m));
                    ui.end_row();
                }
            });
    }
    note(
        ui,
        "Sailed: metres along the track; the heading gives the leg's length",
    );
}
