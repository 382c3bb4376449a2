//! Bench section `waves`: the analytic sea's run time against its error.
//!
//! - f32 with absolute time and coordinates vs f32 with phases reduced in f64 on the CPU
//!   (`WaveSet::gpu_waves`) vs the f64 reference, over t = 1e2 … 1e7 s;
//! - culling tolerance ε → waves kept, stated bounds, measured errors, cost;
//! - inverse (height at a world point) tolerance → Newton iterations and cost relative to one
//!   forward evaluation, for Σ kA = 0.3, 0.6, 0.9.

use std::hint::black_box;

use ocean::spectrum::{SeaState, SpectralOptions};
use ocean::{WaveSet, displace_f32, f32_error_bound};
use serde_json::json;

use crate::{Axes, BenchContext, Series, Table, time_ns};
use regatta::error::AppResult;

/// A patch of the course: `n`×`n` points over `size` metres centred at `centre`.
fn grid(centre: [f64; 2], size: f64, n: usize) -> Vec<[f64; 2]> {
    let step = size / (n - 1) as f64;
    (0..n * n)
        .map(|i| {
            let (ix, iz) = (i % n, i / n);
            [
                centre[0] - 0.5 * size + ix as f64 * step,
                centre[1] - 0.5 * size + iz as f64 * step,
            ]
        })
        .collect()
}

/// Median of time(a) / time(b) over chunks of 64 points, the two timed back to back (in
/// alternating order) on each chunk, `reps` times: robust against a machine whose load changes
/// during the run (a shared CI box), where whole-run timings drift by tens of per cent.
fn interleaved_ratio(
    reps: usize,
    pts: &[[f64; 2]],
    a: impl Fn(&[[f64; 2]]),
    b: impl Fn(&[[f64; 2]]),
) -> f64 {
    let mut ratios = Vec::new();
    for rep in 0..reps.max(1) {
        for (i, chunk) in pts.chunks(64).enumerate() {
            let (ta, tb) = if (i + rep) % 2 == 0 {
                let tb = time_ns(1, 1, || b(chunk));
                (time_ns(1, 1, || a(chunk)), tb)
            } else {
                let ta = time_ns(1, 1, || a(chunk));
                (ta, time_ns(1, 1, || b(chunk)))
            };
            ratios.push(ta / tb);
        }
    }
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

/// The naive f32 path a shader would run if handed absolute time and coordinates.
fn displace_f32_absolute(sea: &WaveSet, x: [f32; 2], t: f32) -> [f32; 3] {
    let mut d = [0.0f32; 3];
    for w in &sea.waves {
        let (k, a) = (w.k() as f32, w.amplitude() as f32);
        let omega = w.omega(sea.gravity, sea.depth) as f32;
        let dir = [w.direction[0] as f32, w.direction[1] as f32];
        let theta = k * (dir[0] * x[0] + dir[1] * x[1]) - omega * t + w.phase as f32;
        let (s, c) = theta.sin_cos();
        d[0] += dir[0] * a * c;
        d[1] += a * s;
        d[2] += dir[1] * a * c;
    }
    d
}

/// A sea of the default one's shape with its total steepness scaled to `total`.
fn scaled_sea(total: f64) -> WaveSet {
    let mut s = WaveSet::default_sea();
    let f = total / s.total_steepness();
    for w in &mut s.waves {
        w.steepness *= f;
    }
    s
}

fn f32_table(ctx: &BenchContext) -> AppResult<Table> {
    let sea = WaveSet::default_sea();
    // A 400 m patch 2.5 km from the course origin: realistic for a camera over a course.
    let centre = [2000.0, -1500.0];
    let pts = grid(centre, 400.0, if ctx.quick { 60 } else { 200 });
    let reps = if ctx.quick { 3 } else { 9 };
    let mut t = Table::new(
        "waves_f32_time",
        "Waves in f32: absolute time vs phases reduced in f64, against the f64 reference",
        &[
            "t (s)",
            "f32 absolute: max |Δy| (m)",
            "f32 reduced: max |Δy| (m)",
            "f32 reduced: max |Δ| any axis (m)",
            "stated bound (m)",
            "f32 absolute ns/pt",
            "f32 reduced ns/pt",
            "f64 ns/pt",
        ],
    );
    let (mut abs_s, mut red_s, mut bound_s) = (Vec::new(), Vec::new(), Vec::new());
    for e in 2..=7 {
        let time = 10f64.powi(e);
        ctx.progress(format!("waves: f32 at t = 1e{e} s"));
        let g = sea.gpu_waves(time, centre);
        let local: Vec<[f32; 2]> = pts
            .iter()
            .map(|p| [(p[0] - centre[0]) as f32, (p[1] - centre[1]) as f32])
            .collect();
        let (mut e_abs, mut e_red, mut e_red_all) = (0.0f64, 0.0f64, 0.0f64);
        let mut radius: f64 = 0.0;
        for (p, l) in pts.iter().zip(&local) {
            let x0 = [centre[0] + l[0] as f64, centre[1] + l[1] as f64];
            let r = sea.displace(x0, time);
            let d = displace_f32(&g, *l);
            e_red = e_red.max((d[1] as f64 - r[1]).abs());
            e_red_all = e_red_all
                .max((d[0] as f64 - (r[0] - x0[0])).abs())
                .max((d[1] as f64 - r[1]).abs())
                .max((d[2] as f64 - (r[2] - x0[1])).abs());
            let ra = sea.displace(*p, time);
            let da = displace_f32_absolute(&sea, [p[0] as f32, p[1] as f32], time as f32);
            e_abs = e_abs.max((da[1] as f64 - ra[1]).abs());
            radius = radius.max((l[0] as f64).hypot(l[1] as f64));
        }
        let bound = f32_error_bound(&g, radius);
        let ns_abs = time_ns(reps, pts.len(), || {
            for p in &pts {
                black_box(displace_f32_absolute(
                    &sea,
                    [p[0] as f32, p[1] as f32],
                    black_box(time as f32),
                ));
            }
        });
        let ns_red = time_ns(reps, pts.len(), || {
            let g = sea.gpu_waves(black_box(time), centre);
            for l in &local {
                black_box(displace_f32(&g, *l));
            }
        });
        let ns_f64 = time_ns(reps, pts.len(), || {
            for p in &pts {
                black_box(sea.displace(*p, black_box(time)));
            }
        });
        t.row(vec![
            json!(time),
            json!(e_abs),
            json!(e_red),
            json!(e_red_all),
            json!(bound),
            json!(ns_abs),
            json!(ns_red),
            json!(ns_f64),
        ]);
        abs_s.push((time, e_abs));
        red_s.push((time, e_red.max(1e-12)));
        bound_s.push((time, bound));
    }
    t.note(format!(
        "Default sea (6 waves, Σ A = {:.2} m), {} points on a 400 m patch centred at (2000, −1500) m. \
         Reduced: `gpu_waves(t, centre)` then `displace_f32` at local coordinates (what the shader does); \
         the reference is `WaveSet::displace` in f64. The stated bound is `ocean::f32_error_bound` \
         (u Σ A (8 k |p| + 6π + 4 + n), u = 2⁻²⁴): independent of t. The ns/pt of the reduced path \
         include the per-frame `gpu_waves` call.",
        sea.total_amplitude(),
        pts.len()
    ));
    t.plots.push(ctx.plot(
        "waves_f32_time.svg",
        &Axes {
            title: "f32 height error against race time",
            x_label: "race time t (s)",
            y_label: "max |Δy| vs f64 (m)",
            log_x: true,
            log_y: true,
        },
        &[
            Series {
                label: "f32, absolute time".into(),
                points: abs_s,
            },
            Series {
                label: "f32, phases reduced in f64".into(),
                points: red_s,
            },
            Series {
                label: "stated bound (reduced)".into(),
                points: bound_s,
            },
        ],
    )?);
    Ok(t)
}

fn cull_table(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let state = SeaState {
        hs: 2.0,
        tp: 8.0,
        gamma: 3.3,
        direction: [1.0, 0.3],
        spreading: 8.0,
    };
    let spectral = state.to_sea(64, &SpectralOptions::default());
    let sea = spectral.sea;
    let n = if ctx.quick { 30 } else { 80 };
    let pts = grid([300.0, 200.0], 300.0, n);
    let times = [0.0, 37.0, 3600.0, 5.0e5];
    let reps = if ctx.quick { 3 } else { 7 };
    let mut t = Table::new(
        "waves_cull",
        "Error-bounded culling: tolerance ε against waves kept, bound and measured error",
        &[
            "ε (m)",
            "waves kept",
            "Σ A dropped = displacement bound (m)",
            "measured max |ΔP| (m)",
            "world height bound (m)",
            "measured max |Δh(X)| (m)",
            "ns/pt (displace)",
            "cost vs all waves (interleaved)",
        ],
    );
    let all = |chunk: &[[f64; 2]]| {
        for p in chunk {
            black_box(sea.displace(*p, black_box(37.0)));
        }
    };
    let (mut kept_s, mut bound_s, mut meas_s) = (Vec::new(), Vec::new(), Vec::new());
    for &eps in &[0.0, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3] {
        ctx.progress(format!("waves: culling at ε = {eps} m"));
        let c = sea.cull(eps, 0.0);
        let (mut dp, mut dh) = (0.0f64, 0.0f64);
        for &time in &times {
            for (i, p) in pts.iter().enumerate() {
                let (a, b) = (sea.displace(*p, time), c.sea.displace(*p, time));
                let d =
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                dp = dp.max(d);
                // World-point heights on every 7th point: each needs two Newton solves.
                if i % 7 == 0 {
                    let h = sea.sample_at(*p, time, 1e-9);
                    let hk = c.sea.sample_at(*p, time, 1e-9);
                    if let (Ok(h), Ok(hk)) = (h, hk) {
                        dh = dh.max((h.height - hk.height).abs());
                    }
                }
            }
        }
        let ns = time_ns(reps, pts.len(), || {
            for p in &pts {
                black_box(c.sea.displace(*p, black_box(37.0)));
            }
        });
        let kept = |chunk: &[[f64; 2]]| {
            for p in chunk {
                black_box(c.sea.displace(*p, black_box(37.0)));
            }
        };
        let cost = interleaved_ratio(reps, &pts, kept, all);
        t.row(vec![
            json!(eps),
            json!(c.sea.waves.len()),
            json!(c.displacement_bound),
            json!(dp),
            json!(c.height_bound),
            json!(dh),
            json!(ns),
            json!(cost),
        ]);
        if eps > 0.0 {
            kept_s.push((eps, c.sea.waves.len() as f64));
            bound_s.push((eps, c.displacement_bound.max(1e-9)));
            meas_s.push((eps, dp.max(1e-9)));
        }
    }
    t.note(format!(
        "JONSWAP sea Hs = 2 m, Tp = 8 s, γ = 3.3, s = 8, 64 waves (seed 1; amplitude scale {:.3} to keep Σ kA ≤ 0.8), \
         {} points × {} times. Waves are dropped smallest amplitude first while Σ A of the dropped ≤ ε; \
         that sum bounds the 3-D displacement of every rest point at every time. The world height bound \
         multiplies it by sqrt(1 + L²), L = S/(1 − S), S = Σ kA kept.",
        spectral.amplitude_scale,
        pts.len(),
        times.len()
    ));
    t.plots.push(ctx.plot(
        "waves_cull_error.svg",
        &Axes {
            title: "Culling: bound and measured displacement error",
            x_label: "tolerance ε (m)",
            y_label: "error (m)",
            log_x: true,
            log_y: true,
        },
        &[
            Series {
                label: "bound Σ A dropped".into(),
                points: bound_s,
            },
            Series {
                label: "measured max |ΔP|".into(),
                points: meas_s,
            },
        ],
    )?);
    t.plots.push(ctx.plot(
        "waves_cull_kept.svg",
        &Axes {
            title: "Culling: waves kept",
            x_label: "tolerance ε (m)",
            y_label: "waves kept (of 64)",
            log_x: true,
            log_y: false,
        },
        &[Series {
            label: "kept".into(),
            points: kept_s,
        }],
    )?);

    // Per clip-map level: a grid of spacing Δ cannot carry waves shorter than 2Δ.
    let mut lod = Table::new(
        "waves_cull_lod",
        "Culling per clip-map level (ε = 1 cm plus waves shorter than two grid cells)",
        &[
            "grid spacing (m)",
            "min wavelength (m)",
            "waves kept",
            "below grid",
            "displacement bound (m)",
            "slope bound (Σ kA dropped)",
        ],
    );
    for &spacing in &[0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0] {
        let c = sea.cull(0.01, 2.0 * spacing);
        lod.row(vec![
            json!(spacing),
            json!(2.0 * spacing),
            json!(c.sea.waves.len()),
            json!(c.below_grid),
            json!(c.displacement_bound),
            json!(c.slope_bound),
        ]);
    }
    lod.note(
        "Same sea. Waves below the grid's Nyquist wavelength are dropped whatever ε says, and their \
         amplitudes are part of the stated bound, so a coarse level reports its true error.",
    );
    Ok(vec![t, lod])
}

fn inverse_table(ctx: &BenchContext) -> AppResult<Table> {
    let pts = grid([-700.0, 1200.0], 200.0, if ctx.quick { 40 } else { 120 });
    let reps = if ctx.quick { 3 } else { 7 };
    let time = 4321.0;
    let mut t = Table::new(
        "waves_inverse",
        "Height at a world point: Newton inverse, tolerance against iterations and cost",
        &[
            "Σ kA",
            "tolerance (m)",
            "mean iterations",
            "max iterations",
            "mean evaluations",
            "inverse ns/pt",
            "forward ns/pt",
            "cost / forward",
        ],
    );
    let mut series = Vec::new();
    for &total in &[0.3, 0.6, 0.9] {
        let sea = scaled_sea(total);
        let forward = || {
            for p in &pts {
                black_box(sea.displace(*p, black_box(time)));
            }
        };
        let fwd = time_ns(reps, pts.len(), forward);
        let mut line = Vec::new();
        for &tol in &[1e-2, 1e-3, 1e-4, 1e-6, 1e-9] {
            ctx.progress(format!("waves: inverse Σ kA = {total}, tol = {tol:e} m"));
            let (mut it, mut ev, mut max_it) = (0u64, 0u64, 0u32);
            for p in &pts {
                let r = sea
                    .rest_point(*p, time, tol)
                    .map_err(|e| regatta::error::AppError::new(format!("bench waves: {e}")))?;
                it += r.iterations as u64;
                ev += r.evaluations as u64;
                max_it = max_it.max(r.iterations);
            }
            let inverse = |chunk: &[[f64; 2]]| {
                for p in chunk {
                    if tol == ocean::DEFAULT_TOLERANCE {
                        black_box(sea.height_at(*p, black_box(time)).ok());
                    } else {
                        black_box(sea.rest_point(*p, black_box(time), tol).ok());
                    }
                }
            };
            let forward_chunk = |chunk: &[[f64; 2]]| {
                for p in chunk {
                    black_box(sea.displace(*p, black_box(time)));
                }
            };
            let inv = time_ns(reps, pts.len(), || inverse(&pts));
            let ratio = interleaved_ratio(reps, &pts, inverse, forward_chunk);
            let n = pts.len() as f64;
            t.row(vec![
                json!(total),
                json!(tol),
                json!(it as f64 / n),
                json!(max_it),
                json!(ev as f64 / n),
                json!(inv),
                json!(fwd),
                json!(ratio),
            ]);
            line.push((tol, ratio));
        }
        series.push(Series {
            label: format!("Σ kA = {total}"),
            points: line,
        });
    }
    t.note(format!(
        "Default sea's 6 waves with Σ kA scaled, {} world points, t = {time} s. Newton on the 2×2 \
         horizontal map from x0 = X, damped by halving when the residual does not shrink; the tolerance \
         is on the horizontal residual |X(x0) − X|. One evaluation = one sin_cos per wave with the \
         Jacobian. Goal: ≤ 4× one forward `displace` at 1e-6 m for Σ kA ≤ 0.9 (the 1e-6 rows time \
         `height_at`, the others `rest_point`). The cost column is the median over repetitions of \
         inverse time / forward time over chunks of 64 points timed back to back.",
        pts.len()
    ));
    t.plots.push(ctx.plot(
        "waves_inverse.svg",
        &Axes {
            title: "Inverse cost relative to one forward evaluation",
            x_label: "tolerance (m)",
            y_label: "inverse ns / forward ns",
            log_x: true,
            log_y: false,
        },
        &series,
    )?);
    Ok(t)
}

/// The `waves` section.
pub fn run(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let mut tables = vec![f32_table(ctx)?];
    tables.extend(cull_table(ctx)?);
    tables.push(inverse_table(ctx)?);
    Ok(tables)
}
