//! The selected boat's tacks and gybes on the timeline (issue 28): from `race::debrief`, worked
//! out once per loaded race, and two buttons that move the playhead to the start (`t_entry`) of
//! the previous or next manoeuvre.

use egui::Ui;

use crate::clock::RaceClock;

/// Each boat's manoeuvre starts (race seconds, sorted), indexed like `race.boats`.
#[derive(Clone, Debug, Default)]
pub struct ManoeuvreStarts {
    /// The race this was worked out for (its name, boat ids and time span's bits): another
    /// race recomputes, even one of the same name.
    key: Option<(String, Vec<String>, [u64; 2])>,
    pub per_boat: Vec<Vec<f64>>,
    /// The whole debrief [`ManoeuvreStarts::update`] worked out (the scene's manoeuvre marks
    /// read it too: one computation per race).
    debrief: Option<race::Debrief>,
}

impl ManoeuvreStarts {
    /// The starts of `debrief`'s manoeuvres per boat.
    pub fn from_debrief(debrief: &race::Debrief, boats: usize) -> Self {
        let mut per_boat = vec![Vec::new(); boats];
        for bm in &debrief.manoeuvres {
            if let Some(starts) = per_boat.get_mut(bm.boat) {
                starts.extend(bm.manoeuvres.iter().map(|m| m.t_entry));
            }
        }
        for starts in &mut per_boat {
            starts.sort_by(f64::total_cmp);
        }
        Self {
            key: None,
            per_boat,
            debrief: None,
        }
    }

    /// Runs the debrief when `race` is not the one last seen (once per loaded race, not per
    /// frame: the debrief samples every track).
    pub fn update(&mut self, race: &race::Race) {
        let (a, b) = race.time_span();
        let ids = race.boats.iter().map(|boat| boat.id.clone()).collect();
        let key = (race.name.clone(), ids, [a.to_bits(), b.to_bits()]);
        if self.key.as_ref() == Some(&key) {
            return;
        }
        let debrief = race::Debrief::of(race);
        *self = Self::from_debrief(&debrief, race.boats.len());
        self.debrief = Some(debrief);
        self.key = Some(key);
    }

    /// The debrief of the race last given to [`ManoeuvreStarts::update`]; `None` before.
    pub fn debrief(&self) -> Option<&race::Debrief> {
        self.debrief.as_ref()
    }

    /// `boat`'s manoeuvre starts; empty for an unknown boat.
    pub fn of(&self, boat: usize) -> &[f64] {
        self.per_boat.get(boat).map_or(&[], Vec::as_slice)
    }
}

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
