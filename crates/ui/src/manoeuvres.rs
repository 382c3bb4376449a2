//! The selected boat's tacks and gybes on the timeline (issue 28): two buttons that move the
//! playhead to the start (`t_entry`) of the previous or next manoeuvre, as `race::debrief`
//! found them (worked out once per loaded race: [`crate::DebriefView`]).

use egui::Ui;

use crate::clock::RaceClock;

/// "⏪ Tack" and "Tack ⏩": jump to the previous / next manoeuvre start of the selected boat
/// (`starts`, sorted race seconds), pausing. Returns true when race time moved.
pub fn manoeuvre_jump_ui(ui: &mut Ui, clock: &mut RaceClock, boat: &str, starts: &[f64]) -> bool {
    let mut moved = false;
    ui.add_enabled_ui(!starts.is_empty(), |ui| {
        if ui
            .button("⏪ Tack")
            .on_hover_text(format!("{boat}: jump to the previous tack or gybe"))
            .clicked()
        {
            clock.pause();
            moved |= clock.jump_to_previous(starts).is_some();
        }
        if ui
            .button("Tack ⏩")
            .on_hover_text(format!("{boat}: jump to the next tack or gybe"))
            .clicked()
        {
            clock.pause();
            moved |= clock.jump_to_next(starts).is_some();
        }
    });
    moved
}
