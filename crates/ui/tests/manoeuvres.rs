//! The timeline's tack/gybe jumps (issue 28): a click moves the playhead to the start of the
//! selected boat's next or previous manoeuvre as `race::debrief` detects it on the sample race.

use egui::Vec2;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use ui::{DebriefView, RaceClock, manoeuvre_jump_ui};

#[test]
fn tack_buttons_move_the_playhead_to_the_debriefs_manoeuvre_starts() {
    let race = race::Race::sample();
    let debrief = race::Debrief::of(&race);
    // The independent truth: the debrief's own manoeuvre starts of the boat with the most.
    let bm = debrief
        .manoeuvres
        .iter()
        .max_by_key(|b| b.manoeuvres.len())
        .expect("the sample race has boats");
    let mut truth: Vec<f64> = bm.manoeuvres.iter().map(|m| m.t_entry).collect();
    truth.sort_by(f64::total_cmp);
    assert!(truth.len() >= 2, "the sample race's boats tack: {truth:?}");
    let boat = bm.boat;
    let name = race.boats[boat].name.clone();
    let mut starts = DebriefView::default();
    starts.update(&race);
    let span = race.time_span();
    let mut clock = RaceClock::new(span);
    clock.scrub_to(span.0);
    let mut h = Harness::builder()
        .with_size(Vec2::new(400.0, 60.0))
        .build_ui_state(
            |ui, clock: &mut RaceClock| {
                ui.horizontal(|ui| manoeuvre_jump_ui(ui, clock, &name, starts.starts_of(boat)));
            },
            clock,
        );
    h.get_by_label("Tack ⏩").click();
    h.run();
    assert_eq!(h.state().time(), truth[0]);
    h.get_by_label("Tack ⏩").click();
    h.run();
    assert_eq!(h.state().time(), truth[1]);
    h.get_by_label("⏪ Tack").click();
    h.run();
    assert_eq!(h.state().time(), truth[0]);
    assert!(!h.state().is_playing());
}
