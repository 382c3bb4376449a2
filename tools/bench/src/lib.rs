//! `regatta bench`: run time against error. Each section is one module that returns tables
//! (and may draw SVG plots); this crate root runs them, shows progress on stderr and writes
//! `report.json`, `report.md` and the plots into the output folder. A package of its own on the
//! app library (`regatta`), so the Android library carries none of it; `regatta bench ARGS`
//! runs the `regatta-bench` binary (src/main.rs) found beside the `regatta` executable.
//!
//! Timings here are for people and for the README; no test asserts a timing.

use std::path::{Path, PathBuf};
use std::time::Instant;

use plotters::prelude::*;
use serde::Serialize;

use regatta::error::{AppError, AppResult};

pub mod budget;
pub mod budget_accuracy;
pub mod budget_camera;
pub mod budget_model;
pub mod budget_model_run;
pub mod budget_run;
pub mod effects;
pub mod mesh;
pub mod overlays;
pub mod pool;
pub mod race;
pub mod race_fleet;
pub mod race_import;
pub mod shader_cost;
pub mod wakes;
pub mod waves;
pub mod work_clock;

/// What every section gets.
pub struct BenchContext {
    /// Folder the report and plots go into.
    pub out_dir: PathBuf,
    /// Fewer repetitions and smaller grids: for CI smoke runs and impatient people.
    pub quick: bool,
}

/// One table of the report.
#[derive(Debug, Clone, Serialize)]
pub struct Table {
    /// File-safe identifier, e.g. "f32_phase".
    pub name: String,
    pub title: String,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<serde_json::Value>>,
    /// Sentences printed under the table: method, goal, conclusion.
    pub notes: Vec<String>,
    /// SVG files (relative to the output folder) that plot this table.
    pub plots: Vec<String>,
}

impl Table {
    pub fn new(name: &str, title: &str, columns: &[&str]) -> Self {
        Table {
            name: name.into(),
            title: title.into(),
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: Vec::new(),
            notes: Vec::new(),
            plots: Vec::new(),
        }
    }
    pub fn row(&mut self, cells: Vec<serde_json::Value>) {
        self.rows.push(cells);
    }
    pub fn note(&mut self, s: impl Into<String>) {
        self.notes.push(s.into());
    }
}

/// One line of a plot.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// Axis options for [`BenchContext::plot`].
pub struct Axes<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub log_x: bool,
    pub log_y: bool,
}

impl BenchContext {
    /// A progress line for a person watching a long run.
    pub fn progress(&self, msg: impl AsRef<str>) {
        eprintln!("bench: {}", msg.as_ref());
    }

    /// Draw `series` as lines with markers into `<out_dir>/<file>` (SVG). Returns the file name.
    pub fn plot(&self, file: &str, axes: &Axes, series: &[Series]) -> AppResult<String> {
        let path = self.out_dir.join(file);
        draw_plot(&path, axes, series)
            .map_err(|e| AppError::new(format!("could not draw {}: {e}", path.display())))?;
        Ok(file.to_string())
    }
}

fn draw_plot(
    path: &Path,
    axes: &Axes,
    series: &[Series],
) -> Result<(), Box<dyn std::error::Error>> {
    let pts = series.iter().flat_map(|s| s.points.iter().copied());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in pts.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        if (axes.log_x && x <= 0.0) || (axes.log_y && y <= 0.0) {
            continue;
        }
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (1.0, 10.0, 1.0, 10.0);
    }
    // Pad so a single point or a flat line still gets a visible range.
    let pad = |lo: f64, hi: f64, log: bool| {
        if log {
            (lo / 1.5, hi * 1.5)
        } else {
            let d = (hi - lo).abs().max(hi.abs() * 0.05).max(1e-12);
            (lo - 0.05 * d, hi + 0.05 * d)
        }
    };
    let (x0, x1) = pad(x0, x1, axes.log_x);
    let (y0, y1) = pad(y0, y1, axes.log_y);
    let root = SVGBackend::new(path, (800, 500)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut builder = ChartBuilder::on(&root);
    builder
        .caption(axes.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70);
    macro_rules! draw {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(axes.x_label)
                .y_desc(axes.y_label)
                .draw()?;
            for (i, s) in series.iter().enumerate() {
                let color = Palette99::pick(i).to_rgba();
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
                    .filter(|(x, y)| (!axes.log_x || *x > 0.0) && (!axes.log_y || *y > 0.0))
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
                    .label(s.label.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
                chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))?;
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()?;
        }};
    }
    match (axes.log_x, axes.log_y) {
        (false, false) => draw!(builder.build_cartesian_2d(x0..x1, y0..y1)?),
        (true, false) => draw!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1)?),
        (false, true) => draw!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())?),
        (true, true) => {
            draw!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?)
        }
    }
    root.present()?;
    Ok(())
}

/// A section of the report: a name for `--only` and progress, and the function that runs it.
pub type Section = (&'static str, fn(&BenchContext) -> AppResult<Vec<Table>>);

/// Every section, in report order. Add yours here (one line).
pub const SECTIONS: &[Section] = &[
    ("waves", waves::run),
    ("effects", effects::effects_section),
    ("fresnel", effects::fresnel_section),
    ("mesh", mesh::run),
    ("race", race::run),
    ("wakes", wakes::run),
    ("pool", pool::run),
    ("budget", budget_run::run),
    ("budget-model", budget_model_run::run),
    ("overlays", overlays::run),
];

/// A render target of `size` pixels in the offscreen format that the GPU sections draw
/// their timed frames into (never read back).
pub fn offscreen(gpu: &render::Gpu, size: [u32; 2]) -> wgpu::TextureView {
    render::gpu::texture_2d(
        &gpu.device,
        "bench offscreen",
        size,
        render::OFFSCREEN_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    )
    .create_view(&Default::default())
}

/// Run the sections (all, or those named in `only`) and write the report.
pub fn run_all(ctx: &BenchContext, only: &[String]) -> AppResult<Vec<Table>> {
    if let Some(bad) = only.iter().find(|o| !SECTIONS.iter().any(|(n, _)| n == o)) {
        let names: Vec<&str> = SECTIONS.iter().map(|(n, _)| *n).collect();
        return Err(AppError::new(format!(
            "--only names the unknown section {}; the sections are: {}",
            input::quote(bad),
            names.join(", ")
        )));
    }
    std::fs::create_dir_all(&ctx.out_dir).map_err(|e| {
        AppError::new(format!(
            "could not create the bench folder {}: {e}",
            input::show_path(&ctx.out_dir)
        ))
    })?;
    let mut tables = Vec::new();
    let chosen: Vec<&Section> = SECTIONS
        .iter()
        .filter(|(n, _)| only.is_empty() || only.iter().any(|o| o == n))
        .collect();
    for (i, (name, f)) in chosen.iter().enumerate() {
        ctx.progress(format!("[{}/{}] {name} ...", i + 1, chosen.len()));
        let t0 = Instant::now();
        tables.extend(f(ctx)?);
        ctx.progress(format!(
            "[{}/{}] {name} done in {:.1} s",
            i + 1,
            chosen.len(),
            t0.elapsed().as_secs_f64()
        ));
    }
    write_report(ctx, &tables)?;
    Ok(tables)
}

fn write_report(ctx: &BenchContext, tables: &[Table]) -> AppResult {
    let json =
        serde_json::to_string_pretty(&serde_json::json!({ "quick": ctx.quick, "tables": tables }))?;
    // Written whole or not at all, a failure naming the file.
    regatta::setup::output::write_text(&ctx.out_dir.join("report.json"), &json)?;
    regatta::setup::output::write_text(&ctx.out_dir.join("report.md"), &markdown(tables))
}

/// The tables as Markdown, for the README and for people.
pub fn markdown(tables: &[Table]) -> String {
    let mut md = String::from("# Regatta benchmark report\n");
    for t in tables {
        let header: Vec<String> = t.columns.iter().map(|c| escape_pipes(c)).collect();
        md.push_str(&format!(
            "\n## {}\n\n| {} |\n|",
            t.title,
            header.join(" | ")
        ));
        md.push_str(&" --- |".repeat(t.columns.len()));
        md.push('\n');
        for r in &t.rows {
            let cells: Vec<String> = r.iter().map(cell).collect();
            md.push_str(&format!("| {} |\n", cells.join(" | ")));
        }
        for n in &t.notes {
            md.push_str(&format!("\n{n}\n"));
        }
        for p in &t.plots {
            md.push_str(&format!("\n![{}]({p})\n", t.title));
        }
    }
    md
}

/// A `|` inside a Markdown table cell ends the cell unless escaped (e.g. "max |Δy|").
fn escape_pipes(s: &str) -> String {
    s.replace('|', "\\|")
}

fn cell(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::String(s) => escape_pipes(s),
        serde_json::Value::Number(n) => match n.as_f64() {
            Some(f) if n.is_f64() => fmt_sig(f),
            _ => n.to_string(),
        },
        other => other.to_string(),
    }
}

/// Four significant digits, scientific outside [1e-3, 1e6).
pub fn fmt_sig(f: f64) -> String {
    if f == 0.0 {
        "0".into()
    } else if f.abs() >= 1e6 || f.abs() < 1e-3 {
        format!("{f:.3e}")
    } else {
        let digits = (3 - f.abs().log10().floor() as i32).max(0) as usize;
        format!("{f:.digits$}")
    }
}

/// Median of `reps` timed runs of `f`, in nanoseconds per call of `f` divided by `per`.
pub fn time_ns(reps: usize, per: usize, mut f: impl FnMut()) -> f64 {
    let mut v: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_nanos() as f64 / per.max(1) as f64
        })
        .collect();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
