//! The performance overlay: frames per second, GPU milliseconds and triangles per pass, and the
//! passes the frame planner skipped with its reason. The app fills [`PerfStats`] from the
//! renderer's frame record, so ui does not depend on the renderer.

use std::collections::VecDeque;

use egui::{Color32, RichText, Ui};

/// One pass of one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PassStat {
    pub name: String,
    pub ran: bool,
    /// Why it ran, or why it was skipped.
    pub reason: String,
    pub triangles: u64,
    /// GPU milliseconds, where the adapter has timestamp queries.
    pub gpu_ms: Option<f64>,
}

/// What the overlay shows for one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PerfStats {
    pub fps: f64,
    /// Mean wall milliseconds per frame over the meter's window.
    pub frame_ms: f64,
    pub triangles: u64,
    pub passes: Vec<PassStat>,
    /// The adapter, e.g. "llvmpipe (Vulkan)".
    pub adapter: String,
}

/// Frames per second over the last `window` frames (a moving window, so the number is steady
/// enough to read and still follows a change within a second).
#[derive(Clone, Debug)]
pub struct FpsMeter {
    intervals: VecDeque<f64>,
    window: usize,
    sum: f64,
}

impl FpsMeter {
    pub fn new(window: usize) -> Self {
        Self {
            intervals: VecDeque::with_capacity(window),
            window: window.max(1),
            sum: 0.0,
        }
    }

    /// Records one frame that took `dt` wall seconds.
    pub fn push(&mut self, dt: f64) {
        if !dt.is_finite() || dt <= 0.0 {
            return;
        }
        if self.intervals.len() == self.window
            && let Some(old) = self.intervals.pop_front()
        {
            self.sum -= old;
        }
        self.intervals.push_back(dt);
        self.sum += dt;
    }

    /// Frames per second: frames in the window over their total time (0 before the first).
    pub fn fps(&self) -> f64 {
        if self.sum > 0.0 {
            self.intervals.len() as f64 / self.sum
        } else {
            0.0
        }
    }

    /// Mean milliseconds per frame.
    pub fn frame_ms(&self) -> f64 {
        if self.intervals.is_empty() {
            0.0
        } else {
            1000.0 * self.sum / self.intervals.len() as f64
        }
    }
}

/// Draws the overlay: a headline line, then one line per pass.
pub fn perf_ui(ui: &mut Ui, stats: &PerfStats) {
    ui.label(
        RichText::new(format!(
            "{:.0} fps  {:.1} ms  {} tris",
            stats.fps,
            stats.frame_ms,
            format_count(stats.triangles)
        ))
        .monospace()
        .strong(),
    );
    if !stats.adapter.is_empty() {
        ui.label(RichText::new(&stats.adapter).small().weak());
    }
    ui.set_max_width(420.0);
    egui::Grid::new("perf-passes")
        .num_columns(4)
        .spacing([8.0, 2.0])
        .show(ui, |ui| {
            for p in &stats.passes {
                let color = if p.ran {
                    Color32::from_rgb(90, 200, 110)
                } else {
                    Color32::from_gray(150)
                };
                ui.label(RichText::new(&p.name).monospace().color(color));
                if p.ran {
                    ui.label(
                        RichText::new(
                            p.gpu_ms
                                .map_or("– ms".to_string(), |ms| format!("{ms:.2} ms")),
                        )
                        .monospace(),
                    );
                    ui.label(RichText::new(format_count(p.triangles)).monospace());
                } else {
                    ui.label(RichText::new("skipped").monospace().weak());
                    ui.label("");
                }
                // The planner's reasons can be long: one line each, the whole reason on hover.
                ui.add(egui::Label::new(RichText::new(&p.reason).small()).truncate())
                    .on_hover_text(&p.reason);
                ui.end_row();
            }
        });
}

/// `950`, `12.3k`, `1.25M`.
pub fn format_count(n: u64) -> String {
    match n {
        0..1_000 => n.to_string(),
        1_000..1_000_000 => format!("{:.1}k", n as f64 / 1e3),
        _ => format!("{:.2}M", n as f64 / 1e6),
    }
}
