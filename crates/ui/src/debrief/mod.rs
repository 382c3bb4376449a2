//! The race's debrief in the Boats panel (issue 28): `race::Debrief` worked out once per loaded
//! race ([`DebriefView`]) and shown as three views beside the speed plot: every boat's tacks
//! and gybes with the metres they cost ([`manoeuvre_table`]), the start at the gun
//! ([`start`]) and the legs ([`legs`]). Each view says where its wind comes from: measured in
//! the race's data, or estimated from the fleet with its uncertainty.

pub mod legs;
pub mod manoeuvre_table;
pub mod start;

use egui::{RichText, Ui};
use race::debrief::{WindModel, WindSource};

/// The whole debrief of the race last shown, worked out once per race (the debrief samples
/// every track: never per frame), and each boat's manoeuvre starts for the timeline's jumps.
#[derive(Clone, Debug, Default)]
pub struct DebriefView {
    /// The race this was worked out for (its name, boat ids and time span's bits): another
    /// race recomputes, even one of the same name.
    key: Option<(String, Vec<String>, [u64; 2])>,
    debrief: Option<race::Debrief>,
    /// Each boat's manoeuvre starts (`t_entry`, race seconds, sorted), indexed like
    /// `race.boats`.
    starts: Vec<Vec<f64>>,
}

impl DebriefView {
    /// The view of an already computed debrief of a race of `boats` boats.
    pub fn from_debrief(debrief: race::Debrief, boats: usize) -> Self {
        let mut starts = vec![Vec::new(); boats];
        for bm in &debrief.manoeuvres {
            if let Some(s) = starts.get_mut(bm.boat) {
                s.extend(bm.manoeuvres.iter().map(|m| m.t_entry));
            }
        }
        for s in &mut starts {
            s.sort_by(f64::total_cmp);
        }
        Self {
            key: None,
            debrief: Some(debrief),
            starts,
        }
    }

    /// Runs the debrief when `race` is not the one last seen. Called every frame (the timeline
    /// and the trails' marks): the check compares in place and copies the key only for a new
    /// race.
    pub fn update(&mut self, race: &race::Race) {
        let (a, b) = race.time_span();
        let span = [a.to_bits(), b.to_bits()];
        let same = self.key.as_ref().is_some_and(|(name, ids, s)| {
            *name == race.name
                && *s == span
                && ids.len() == race.boats.len()
                && ids.iter().zip(&race.boats).all(|(id, boat)| *id == boat.id)
        });
        if same {
            return;
        }
        *self = Self::from_debrief(race::Debrief::of(race), race.boats.len());
        let ids = race.boats.iter().map(|boat| boat.id.clone()).collect();
        self.key = Some((race.name.clone(), ids, span));
    }

    /// The debrief; `None` before the first [`DebriefView::update`].
    pub fn debrief(&self) -> Option<&race::Debrief> {
        self.debrief.as_ref()
    }

    /// `boat`'s manoeuvre starts (race seconds, sorted); empty for an unknown boat.
    pub fn starts_of(&self, boat: usize) -> &[f64] {
        self.starts.get(boat).map_or(&[], Vec::as_slice)
    }
}

/// Where a wind figure comes from, in the words every display of it uses: "from the race's
/// data" or "estimated from the fleet ±2.0°" (one sigma of the direction).
pub fn wind_source_text(source: WindSource, uncertainty_deg: f64) -> String {
    match source {
        WindSource::Data => "from the race's data".to_string(),
        WindSource::Estimated => format!("estimated from the fleet ±{uncertainty_deg:.1}°"),
    }
}

/// The line above each debrief view: "wind 59° estimated from the fleet ±2.0°", or that there
/// is none (then no manoeuvre can be told).
pub fn wind_line(wind: Option<&WindModel>) -> String {
    match wind {
        Some(w) => format!(
            "wind {:.0}°: {}",
            w.from_deg,
            wind_source_text(w.source, w.uncertainty_deg)
        ),
        None => "wind: none in the race's data and too little sailing to estimate it".to_string(),
    }
}

/// The Boats panel's views, one at a time (a phone shows one screenful).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BoatsView {
    /// The speed plot and the comparison of two boats.
    #[default]
    Speed,
    Manoeuvres,
    Start,
    Legs,
}

impl BoatsView {
    pub const ALL: [BoatsView; 4] = [
        BoatsView::Speed,
        BoatsView::Manoeuvres,
        BoatsView::Start,
        BoatsView::Legs,
    ];

    /// The tab's label.
    pub fn label(self) -> &'static str {
        match self {
            BoatsView::Speed => "Speed",
            BoatsView::Manoeuvres => "Manoeuvres",
            BoatsView::Start => "Start",
            BoatsView::Legs => "Legs",
        }
    }
}

/// The row of view tabs.
pub fn boats_view_tabs(ui: &mut Ui, view: &mut BoatsView) {
    ui.horizontal_wrapped(|ui| {
        for v in BoatsView::ALL {
            ui.selectable_value(view, v, v.label());
        }
    });
}

/// A weak one-line note.
fn note(ui: &mut Ui, text: impl Into<String>) {
    ui.label(RichText::new(text.into()).weak());
}

/// A table's header row: each column's name in bold, with its hover text where there is one.
fn header_row(ui: &mut Ui, columns: &[(&str, &str)]) {
    for &(name, hover) in columns {
        let r = ui.label(RichText::new(name).strong());
        if !hover.is_empty() {
            r.on_hover_text(hover);
        }
    }
    ui.end_row();
}

/// A boat's id in bold, in its team's colour (grey for a boat the race does not know).
fn boat_name(ui: &mut Ui, race: &race::Race, id: &str) {
    let colour = race
        .boat_index(id)
        .and_then(|i| crate::leaderboard::parse_hex_color(&race.boats[i].color))
        .unwrap_or(egui::Color32::GRAY);
    ui.label(RichText::new(id).color(colour).strong());
}

/// `+3`, `−2`, `0`: a signed count or figure (a minus sign, not a hyphen).
pub fn signed(v: f64, decimals: usize) -> String {
    let s = format!("{:.*}", decimals, v.abs());
    if s.chars().all(|c| c == '0' || c == '.') {
        s
    } else if v < 0.0 {
        format!("−{s}")
    } else {
        format!("+{s}")
    }
}

/// A figure with a minus sign where negative and no sign otherwise ("−35", "0", "12"; never
/// "-0").
pub fn number(v: f64, decimals: usize) -> String {
    signed(v, decimals).trim_start_matches('+').to_string()
}

/// Whole metres: "12 m", "−35 m".
pub fn metres(m: f64) -> String {
    format!("{} m", number(m, 0))
}

/// Parses what [`signed`], [`number`] or [`metres`] wrote (for the tests and anyone reading the labels back).
pub fn parse_signed(s: &str) -> Option<f64> {
    let s = s.trim().trim_end_matches(" m").trim_end_matches(" %");
    if let Some(r) = s.strip_prefix('−') {
        r.parse::<f64>().ok().map(|v| -v)
    } else {
        s.trim_start_matches('+').parse().ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same race keeps its debrief; another race of the same name (a boat renamed, or one
    /// boat fewer) runs it again.
    #[test]
    fn a_debrief_is_run_again_only_for_another_race() {
        let mut race = race::Race::sample();
        let mut view = DebriefView::default();
        view.update(&race);
        let key = view.key.clone();
        view.starts.clear();
        view.update(&race);
        assert!(
            view.starts.is_empty(),
            "the same race ran the debrief again"
        );
        race.boats[0].id.push('x');
        view.update(&race);
        assert_ne!(view.key, key);
        assert_eq!(view.starts.len(), race.boats.len());
        let key = view.key.clone();
        race.boats.pop();
        view.update(&race);
        assert_ne!(view.key, key, "a fleet of one boat fewer is another race");
        assert_eq!(view.starts.len(), race.boats.len());
    }

    /// Signs as a sailor reads them: a real minus sign, no "-0", a plus only where asked; and
    /// every form parses back.
    #[test]
    fn figures_are_signed_and_parse_back() {
        assert_eq!(signed(3.0, 0), "+3");
        assert_eq!(signed(-2.4, 0), "−2");
        assert_eq!(signed(-0.3, 0), "0");
        assert_eq!(number(-35.2, 0), "−35");
        assert_eq!(number(12.0, 0), "12");
        assert_eq!(metres(-0.4), "0 m");
        for v in [-35.0, -1.0, 0.0, 7.0, 1234.0] {
            assert_eq!(parse_signed(&signed(v, 0)), Some(v));
            assert_eq!(parse_signed(&metres(v)), Some(v));
            assert_eq!(parse_signed(&format!("{} %", number(v, 0))), Some(v));
        }
    }
}
