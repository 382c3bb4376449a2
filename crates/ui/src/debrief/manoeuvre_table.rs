//! The manoeuvre table: per boat the tacks and gybes `race::debrief` found, their median and
//! worst loss (metres against sailing on at the entry VMG) and when the worst was; below, the
//! selected boat's manoeuvres one by one. A click on the worst, or on a manoeuvre's time,
//! pauses and moves race time to that manoeuvre's start (`t_entry`), as the timeline's Tack
//! buttons do.

use egui::{RichText, Ui};
use race::debrief::{BoatManoeuvres, Manoeuvre, ManoeuvreKind};

use super::{boat_name, header_row, note, wind_line};
use crate::clock::{RaceClock, format_race_time};
use crate::leaderboard::KNOTS_PER_MPS;

/// A loss as the table shows it: whole metres (negative: the boat gained on sailing on).
pub fn format_loss(m: f64) -> String {
    super::metres(m)
}

/// The worst cell: "31 m at 12:04".
pub fn format_worst(m: &Manoeuvre) -> String {
    format!(
        "{} at {}",
        format_loss(m.loss_m),
        format_race_time(m.t_entry)
    )
}

/// The manoeuvre that cost the most (the first of equals).
pub fn worst_manoeuvre(bm: &BoatManoeuvres) -> Option<&Manoeuvre> {
    bm.manoeuvres
        .iter()
        .reduce(|a, b| if b.loss_m > a.loss_m { b } else { a })
}

fn kind_word(k: ManoeuvreKind) -> &'static str {
    match k {
        ManoeuvreKind::Tack => "tack",
        ManoeuvreKind::Gybe => "gybe",
    }
}

fn go_to(clock: &mut RaceClock, t: f64) {
    clock.pause();
    clock.scrub_to(t);
}

/// The table and the selected boat's list (`selected`: index into `race.boats`). Returns true
/// when a click moved race time.
pub fn manoeuvre_table_ui(
    ui: &mut Ui,
    race: &race::Race,
    debrief: &race::Debrief,
    selected: Option<usize>,
    clock: &mut RaceClock,
) -> bool {
    ui.label(wind_line(debrief.wind.as_ref()));
    if debrief.manoeuvres.is_empty() {
        note(
            ui,
            "No manoeuvres: without a wind tacks and gybes cannot be told",
        );
        return false;
    }
    let mut moved = false;
    egui::Grid::new("manoeuvre-table")
        .num_columns(5)
        .striped(true)
        .spacing([8.0, 4.0])
        .show(ui, |ui| {
            header_row(
                ui,
                &[
                    ("Boat", ""),
                    ("Tacks", ""),
                    ("Gybes", ""),
                    ("Median", ""),
                    ("Worst", ""),
                ],
            );
            for bm in &debrief.manoeuvres {
                boat_name(ui, race, &bm.id);
                ui.label(bm.tacks.to_string());
                ui.label(bm.gybes.to_string());
                ui.label(bm.median_loss_m.map_or("—".into(), format_loss));
                match worst_manoeuvre(bm) {
                    Some(w) => {
                        if ui
                            .small_button(format_worst(w))
                            .on_hover_text(format!(
                                "{}: go to its costliest {}",
                                bm.id,
                                kind_word(w.kind)
                            ))
                            .clicked()
                        {
                            go_to(clock, w.t_entry);
                            moved = true;
                        }
                    }
                    None => {
                        ui.label("—");
                    }
                }
                ui.end_row();
            }
        });
    note(ui, "Loss: metres short of sailing on at the entry VMG");
    let Some(bm) = selected.and_then(|b| debrief.manoeuvres.iter().find(|m| m.boat == b)) else {
        note(ui, "Select a boat to list its manoeuvres one by one");
        return moved;
    };
    ui.separator();
    ui.label(RichText::new(format!("{}: each manoeuvre", bm.id)).strong());
    if bm.manoeuvres.is_empty() {
        note(ui, "no tack or gybe found");
        return moved;
    }
    moved |= manoeuvre_list(ui, bm, clock);
    moved
}

/// One row per manoeuvre: its start (a button), kind, duration, speed in and out, loss.
fn manoeuvre_list(ui: &mut Ui, bm: &BoatManoeuvres, clock: &mut RaceClock) -> bool {
    let mut moved = false;
    egui::Grid::new("manoeuvre-list")
        .num_columns(5)
        .striped(true)
        .spacing([8.0, 4.0])
        .show(ui, |ui| {
            header_row(
                ui,
                &[
                    ("When", ""),
                    ("Kind", ""),
                    ("Turn", ""),
                    ("kn in/out", ""),
                    ("Lost", ""),
                ],
            );
            for m in &bm.manoeuvres {
                let here = (clock.time() - m.t_entry).abs() < 1e-3;
                if ui
                    .selectable_label(here, format_race_time(m.t_entry))
                    .on_hover_text("Go to this manoeuvre's start")
                    .clicked()
                {
                    go_to(clock, m.t_entry);
                    moved = true;
                }
                ui.label(kind_word(m.kind));
                ui.label(format!("{:.0} s", m.duration_s));
                ui.label(format!(
                    "{:.1}/{:.1}",
                    m.entry_speed_mps * KNOTS_PER_MPS,
                    m.exit_speed_mps * KNOTS_PER_MPS
                ));
                ui.label(format_loss(m.loss_m));
                ui.end_row();
            }
        });
    moved
}
