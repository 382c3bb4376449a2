//! The boats panel's plots (egui_plot): speed (and VMG where the wind is known) of the selected
//! boats over race time, and "compare": the gap between two selected boats over time, in
//! metres and seconds. A vertical line marks the timeline's race time; a click on a plot
//! scrubs there.

use egui::{Color32, RichText, Ui};
use egui_plot::{Legend, Line, Plot, PlotPoints, VLine};

use crate::clock::format_race_time;
use crate::leaderboard::parse_hex_color;
use crate::series::{BoatSeries, GapSample, boat_series, gap_near, gap_series};

/// Height of one plot, points.
pub const PLOT_HEIGHT: f32 = 130.0;

/// The series of the current selection, computed when it changes (a race's worth of samples
/// costs milliseconds, too much for every frame).
#[derive(Clone, Debug, Default)]
pub struct PlotCache {
    key: Option<Vec<usize>>,
    pub speed: Vec<BoatSeries>,
    /// The gap from the first selected boat back to the second (two selected).
    pub gaps: Vec<GapSample>,
}

impl PlotCache {
    /// Recomputes the series when `selection` differs from the last one.
    pub fn update(&mut self, race: &race::Race, selection: &[usize]) {
        let sel: Vec<usize> = selection
            .iter()
            .copied()
            .filter(|&b| b < race.boats.len())
            .collect();
        if self.key.as_ref() == Some(&sel) {
            return;
        }
        self.speed = sel.iter().map(|&b| boat_series(race, b)).collect();
        self.gaps = match sel.as_slice() {
            [a, b] => gap_series(race, *a, *b),
            _ => Vec::new(),
        };
        self.key = Some(sel);
    }

    /// Forget the series (a new race was opened).
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

fn boat_color(race: &race::Race, b: usize) -> Color32 {
    parse_hex_color(&race.boats[b].color).unwrap_or(Color32::GRAY)
}

fn time_axis(plot: Plot<'_>) -> Plot<'_> {
    plot.height(PLOT_HEIGHT)
        .allow_zoom(false)
        .allow_drag(false)
        .allow_scroll(false)
        .allow_boxed_zoom(false)
        .allow_double_click_reset(false)
        .x_axis_formatter(|m, _| format_race_time(m.value))
        // Race clocks read in minutes: ticks every 1, 5 and 10 minutes (longer races: 10, 30,
        // 60), never egui_plot's decimal 1000 s.
        .x_grid_spacer(egui_plot::uniform_grid_spacer(|g| {
            if g.bounds.1 - g.bounds.0 > 3.0 * 3600.0 {
                [600.0, 1800.0, 3600.0]
            } else {
                [60.0, 300.0, 600.0]
            }
        }))
        .legend(Legend::default().background_alpha(0.5))
}

/// Speed (knots) of each selected boat over race time, VMG dashed where the race states its
/// wind. Returns the race time clicked, if any.
pub fn speed_plot_ui(ui: &mut Ui, race: &race::Race, cache: &PlotCache, t: f64) -> Option<f64> {
    if cache.speed.is_empty() {
        ui.label(RichText::new("Select a boat (click its row) to plot its speed").weak());
        return None;
    }
    ui.label(RichText::new(vmg_wind_note(race)).weak());
    let plot = time_axis(Plot::new("speed-plot")).y_axis_label("kn");
    let r = plot.show(ui, |p| {
        for s in &cache.speed {
            let colour = boat_color(race, s.boat);
            let id = &race.boats[s.boat].id;
            p.line(
                Line::new(format!("{id} speed"), PlotPoints::from(s.speed_kn.clone()))
                    .color(colour)
                    .width(1.5),
            );
            if let Some(v) = &s.vmg_kn {
                p.line(
                    Line::new(format!("{id} VMG"), PlotPoints::from(v.clone()))
                        .color(colour.gamma_multiply(0.6))
                        .style(egui_plot::LineStyle::dashed_loose()),
                );
            }
        }
        p.vline(VLine::new("", t).color(Color32::WHITE));
        clicked_time(p)
    });
    r.inner
}

/// Where the speed plot's VMG comes from: the wind the race's files state (never the fleet's
/// estimate, whose direction error would show as a VMG error), or that there is none.
pub fn vmg_wind_note(race: &race::Race) -> String {
    match race.wind {
        Some(w) => format!(
            "VMG (dashed): wind {:.0}° {}",
            w.from_deg,
            crate::debrief::wind_source_text(race::debrief::WindSource::Data, 0.0)
        ),
        None => "No wind in the race's data: speed only, no VMG".to_string(),
    }
}

fn clicked_time(p: &egui_plot::PlotUi<'_>) -> Option<f64> {
    if p.response().clicked() {
        p.pointer_coordinate().map(|c| c.x)
    } else {
        None
    }
}

/// The two selected boats' gap now (one line) and over time (metres and seconds). Returns the
/// race time clicked, if any.
pub fn compare_ui(
    ui: &mut Ui,
    race: &race::Race,
    cache: &PlotCache,
    selection: &[usize],
    t: f64,
) -> Option<f64> {
    let [a, b] = selection else {
        ui.label(RichText::new("Select two boats to compare them").weak());
        return None;
    };
    let (na, nb) = (&race.boats[*a].id, &race.boats[*b].id);
    if cache.gaps.is_empty() {
        ui.label(RichText::new("No course: no gap between boats to compare").weak());
        return None;
    }
    let tolerance = (race.time_span().1 - race.time_span().0) / 200.0;
    ui.label(RichText::new(gap_sentence(na, nb, gap_near(&cache.gaps, t, tolerance))).strong());
    let metres: Vec<[f64; 2]> = cache.gaps.iter().map(|g| [g.t, g.metres]).collect();
    let seconds: Vec<[f64; 2]> = cache
        .gaps
        .iter()
        .filter_map(|g| g.seconds.map(|s| [g.t, s]))
        .collect();
    let plot = time_axis(Plot::new("gap-plot")).y_axis_label(format!("{nb} behind {na}"));
    let r = plot.show(ui, |p| {
        p.line(
            Line::new("metres", PlotPoints::from(metres))
                .color(boat_color(race, *b))
                .width(1.5),
        );
        p.line(
            Line::new("seconds", PlotPoints::from(seconds))
                .color(Color32::LIGHT_GRAY)
                .style(egui_plot::LineStyle::dashed_loose()),
        );
        p.vline(VLine::new("", t).color(Color32::WHITE));
        clicked_time(p)
    });
    r.inner
}

/// "GBR 35 m (8 s) behind NZL", from the gap from `a` back to `b`.
pub fn gap_sentence(a: &str, b: &str, gap: Option<GapSample>) -> String {
    let Some(g) = gap else {
        return format!("{a} – {b}: not both on the course now");
    };
    let (ahead, behind) = if g.metres >= 0.0 { (a, b) } else { (b, a) };
    let secs = g
        .seconds
        .map_or(String::new(), |s| format!(" ({:.0} s)", s.abs()));
    format!("{behind} {:.0} m{secs} behind {ahead}", g.metres.abs())
}
