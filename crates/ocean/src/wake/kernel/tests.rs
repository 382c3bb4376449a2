//! The kernel's constants against the source's own quantities in f64, and its closed-form
//! gradient against f64 differences of the physical term.

use super::*;
use crate::wake::gpu::GpuWakeSource;
use crate::wake::{TrackSample, Wake, WakeParams, WakeView};

/// A real frame's sources: a boat turning at 5 m/s for 100 s (young and old sources).
fn frame_sources() -> Vec<GpuWakeSource> {
    let track: Vec<TrackSample> = (0..=200)
        .map(|i| {
            let t = 0.5 * f64::from(i);
            let a = 5.0 * t / 80.0;
            TrackSample {
                t,
                x: 80.0 * a.sin(),
                z: 80.0 * (1.0 - a.cos()),
            }
        })
        .collect();
    let wake = Wake::new(&[&track], WakeParams::default()).unwrap();
    let view = WakeView::around([0.0, 40.0], 120.0);
    wake.gpu_sources(100.0, [0.0, 40.0], &view, 1e-6).sources
}

/// The physical term of a source at offset `d`, f64 (the Kelvin source's formula on the f32
/// fields): −S·(k²/r)·e^{−k²R²/4}·[sin Φ + (k²R² − 3)/Φ cos Φ]·(d̂·ΔX), k = q/r², Φ = q/r.
fn term_f64(s: &GpuWakeSource, d: [f64; 2]) -> f64 {
    let r2 = d[0] * d[0] + d[1] * d[1];
    let (q, r) = (f64::from(s.q), r2.sqrt());
    let k = q / r2;
    let kr2 = k * k * 4.0 * f64::from(s.gauss);
    let phi = q / r;
    let proj = d[0] * f64::from(s.dx[0]) + d[1] * f64::from(s.dx[1]);
    -f64::from(s.strength) * k * k / r
        * (-kr2 / 4.0).exp()
        * (phi.sin() + (kr2 - 3.0) / phi * phi.cos())
        * proj
        / r
}

/// What the kernel's sin Φ and cos Φ from the table (each within `e` absolute) can move its
/// height and gradient at offset `d` (f64, the source's f32 fields): with c = S·k²/r²·e^{−G/4}
/// (G = k²R²), the bracket sin Φ + (G − 3)/Φ cos Φ moves by e·(1 + |G − 3|/Φ), the radial
/// bracket (G − 9)·bracket + G sin Φ − (Φ + 12/Φ) cos Φ by |G − 9| times that plus
/// e·(G + Φ + 12/Φ); the height is c·bracket·(d·ΔX), the gradient c·bracket·ΔX plus
/// c·radial·(d·ΔX)·d/r².
fn table_error(s: &GpuWakeSource, d: [f64; 2], e: f64) -> [f64; 2] {
    let r2 = d[0] * d[0] + d[1] * d[1];
    let (q, r) = (f64::from(s.q), r2.sqrt());
    let k = q / r2;
    let big_g = k * k * 4.0 * f64::from(s.gauss);
    let phi = q / r;
    let len = f64::from(s.dx[0]).hypot(f64::from(s.dx[1]));
    let c = f64::from(s.strength) * k * k / r2 * (-big_g / 4.0).exp();
    let proj = (d[0] * f64::from(s.dx[0]) + d[1] * f64::from(s.dx[1])).abs();
    let bracket = e * (1.0 + (big_g - 3.0).abs() / phi);
    let radial = (big_g - 9.0).abs() * bracket + e * (big_g + phi + 12.0 / phi);
    [
        c * bracket * proj,
        c * bracket * len + c * radial * proj / r,
    ]
}

#[test]
fn the_constants_are_the_sources_own_quantities() {
    let sources = frame_sources();
    assert!(sources.len() > 100, "{}", sources.len());
    let u = 1.0 / 16_777_216.0;
    for s in &sources {
        let k = WakeKernelSource::from(s);
        assert_eq!(
            (k.pos, k.q, k.cull_r2, k.foam, k.neg_q),
            (s.pos, s.q, s.cull_r2, s.foam, -s.q)
        );
        // −strength·ΔX, rounded once.
        for c in 0..2 {
            let want = -f64::from(s.strength) * f64::from(s.dx[c]);
            assert!(
                (f64::from(k.dx[c]) - want).abs() <= u * want.abs(),
                "{c}: {k:?}"
            );
        }
        // q/2π from q in f64, rounded once.
        let turns = f64::from(s.q) / std::f64::consts::TAU;
        assert!((f64::from(k.q_turns) - turns).abs() <= u * turns, "{k:?}");
        // R² from R²/4: exact.
        assert_eq!(f64::from(k.hull_r2), 4.0 * f64::from(s.gauss));
        // The cut-off's radius: just outside it k²R²/4 ≤ 40, just inside more (f64).
        let g_at = |r2: f64| (f64::from(s.q) / r2).powi(2) * f64::from(s.gauss);
        let inner = f64::from(k.inner_r2);
        assert!(inner > f64::from(MIN_R2), "{k:?}");
        assert!(g_at(inner * (1.0 + 1e-6)) <= 40.0 && g_at(inner * (1.0 - 1e-6)) > 40.0);
        // The foam's rate: density foam·e^{−r²/w²}.
        assert!((f64::from(k.foam_rate) * f64::from(s.foam_w2) + 1.0).abs() <= u);
    }
}

#[test]
fn a_zeroed_source_adds_nothing_anywhere() {
    // The buffer's placeholder (a frame without sources): no NaN, even at its own centre.
    let k = WakeKernelSource::from(&GpuWakeSource::default());
    assert_eq!(k.inner_r2, MIN_R2);
    for d in [[0.0f32, 0.0], [1e-4, 0.0], [3.0, -4.0]] {
        let r2 = d[0] * d[0] + d[1] * d[1];
        assert_eq!(k.height(d, r2), 0.0);
        assert_eq!(k.height_grad(d, r2, 0.0), [0.0; 3]);
    }
}

/// The kernel's height and closed-form gradient (not band limited) against the physical term
/// and its central differences in f64, on rays through young and old sources from just
/// outside the cut-off to the cull radius: within 2·10⁻⁴ of the source's peak (f32, a phase
/// of up to hundreds of radians rounded at 2⁻²⁴ of itself) plus what the table's sin and cos
/// can move them there ([`table_error`] of the mirror's `mirror_sin_cos_error`).
#[test]
fn the_kernel_is_the_term_and_its_derivative() {
    let e = crate::wake::mirror_sin_cos_error();
    let sources = frame_sources();
    let (mut checked, mut worst_h, mut worst_g) = (0, 0.0f64, 0.0f64);
    for s in sources.iter().step_by(7) {
        let k = WakeKernelSource::from(s);
        let (inner, cull) = (f64::from(k.inner_r2).sqrt(), f64::from(s.cull_r2).sqrt());
        let mut cases = Vec::new();
        let (mut peak_h, mut peak_g) = (0.0f64, 0.0f64);
        for a in 0..24 {
            let th = 0.37 + f64::from(a) * std::f64::consts::TAU / 24.0;
            for i in 1..300 {
                let r = inner * (cull / inner).powf(f64::from(i) / 300.0);
                let d = [r * th.cos(), r * th.sin()];
                let h = 1e-6 * r;
                let fd = [
                    (term_f64(s, [d[0] + h, d[1]]) - term_f64(s, [d[0] - h, d[1]])) / (2.0 * h),
                    (term_f64(s, [d[0], d[1] + h]) - term_f64(s, [d[0], d[1] - h])) / (2.0 * h),
                ];
                let df = [d[0] as f32, d[1] as f32];
                let got = k.height_grad(df, df[0] * df[0] + df[1] * df[1], 0.0);
                // The f64 term at the f32 offset the kernel saw.
                let at = [f64::from(df[0]), f64::from(df[1])];
                let want = term_f64(s, at);
                peak_h = peak_h.max(want.abs());
                peak_g = peak_g.max(fd[0].hypot(fd[1]));
                cases.push((r, want, fd, got, table_error(s, at, e)));
            }
        }
        for (r, want, fd, got, table) in cases {
            let err = (f64::from(got[1]) - fd[0]).hypot(f64::from(got[2]) - fd[1]);
            worst_h = worst_h.max((f64::from(got[0]) - want).abs() / peak_h);
            worst_g = worst_g.max(err / peak_g);
            assert!(
                (f64::from(got[0]) - want).abs() <= 2e-4 * peak_h + table[0],
                "q {} r {r}: {} vs {want} (peak {peak_h})",
                s.q,
                got[0]
            );
            assert!(
                err <= 2e-4 * peak_g + table[1],
                "q {} r {r}: {got:?} vs {fd:?} (peak {peak_g})",
                s.q
            );
            checked += 1;
        }
    }
    eprintln!(
        "kernel vs f64 term: {checked} points, worst height {worst_h:.1e}, gradient {worst_g:.1e} of the source's peak"
    );
    assert!(checked > 10_000, "{checked}");
}

/// The band-limited kernel (`wake_at`'s, the edges formed once per point) against the f64
/// term and its central differences times the f64 fade (height and gradient are faded alike),
/// at two clip-map spacings, within the unlimited kernel's 2·10⁻⁴ of the source's peak and
/// its table term (the fade's own f32 error is 9u, `BAND_FADE_F32_ERROR`); the edges of a
/// spacing 1 % off miss.
#[test]
fn the_band_limited_kernel_is_the_faded_term_and_derivative() {
    use crate::wake::gpu::band_fade;
    let e = crate::wake::mirror_sin_cos_error();
    let sources = frame_sources();
    let (mut checked, mut faded, mut worst) = (0, 0, 0.0f64);
    for spacing in [0.5f32, 2.0] {
        let (band, off) = (band_edges(spacing), band_edges(spacing * 1.01));
        let mut broken = 0.0f64;
        for s in sources.iter().step_by(13) {
            let k = WakeKernelSource::from(s);
            let (inner, cull) = (f64::from(k.inner_r2).sqrt(), f64::from(s.cull_r2).sqrt());
            let mut cases = Vec::new();
            let mut peak = [0.0f64; 2];
            for a in 0..12 {
                let th = 0.37 + f64::from(a) * std::f64::consts::TAU / 12.0;
                for i in 1..200 {
                    let r = inner * (cull / inner).powf(f64::from(i) / 200.0);
                    let df = [(r * th.cos()) as f32, (r * th.sin()) as f32];
                    let d = [f64::from(df[0]), f64::from(df[1])];
                    let h = 1e-6 * r;
                    let fd = [
                        (term_f64(s, [d[0] + h, d[1]]) - term_f64(s, [d[0] - h, d[1]])) / (2.0 * h),
                        (term_f64(s, [d[0], d[1] + h]) - term_f64(s, [d[0], d[1] - h])) / (2.0 * h),
                    ];
                    let want = term_f64(s, d);
                    peak = [peak[0].max(want.abs()), peak[1].max(fd[0].hypot(fd[1]))];
                    let r2 = df[0] * df[0] + df[1] * df[1];
                    let fade = band_fade(
                        f64::from(s.q) / (d[0] * d[0] + d[1] * d[1]),
                        f64::from(spacing),
                    );
                    faded += usize::from(fade > 0.0 && fade < 1.0);
                    let got = k.height_grad_in_band(df, r2, band);
                    let bad = k.height_grad_in_band(df, r2, off);
                    let table = table_error(s, d, e);
                    cases.push((r, fade, [want, fd[0], fd[1]], got, bad, table));
                }
            }
            for (r, fade, want, got, bad, table) in cases {
                for c in 0..3 {
                    // The height against the height's peak, the gradient against the slope's.
                    let peak = peak[usize::from(c > 0)];
                    let err = (f64::from(got[c]) - fade * want[c]).abs();
                    worst = worst.max(err / peak);
                    assert!(
                        err <= 2e-4 * peak + fade * table[usize::from(c > 0)],
                        "q {} spacing {spacing} r {r} c {c}: {} vs {} (peak {peak})",
                        s.q,
                        got[c],
                        fade * want[c]
                    );
                    broken = broken.max((f64::from(bad[c]) - fade * want[c]).abs() / peak);
                }
                checked += 1;
            }
        }
        assert!(
            broken > 2e-3,
            "spacing {spacing}: edges 1 % off miss by {broken:.1e}"
        );
    }
    eprintln!(
        "band-limited kernel vs f64: {checked} points, {faded} in the fade, worst {worst:.1e} of the source's peak"
    );
    assert!(faded > 500, "{faded}");
}
