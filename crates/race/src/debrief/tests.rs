//! The debrief on synthetic tracks whose tacks, gybes, losses and wind are known in closed form.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, SQRT_2};

use super::manoeuvres::{ManoeuvreKind, Settings, detect, side_runs};
use super::wind::{WindModel, WindSource, angle_diff, estimate, twa_deg};
use crate::track::{Boat, Fix, Logged};
use crate::{LoadReport, Race};

/// A planned leg of a synthetic boat: hold `heading` (compass degrees) at `speed` for `secs`,
/// or turn from the current heading through `turn` degrees (signed) in `secs` with the speed
/// dipping by `dip` (fraction) at mid-turn: v(s) = V (1 − dip sin(π s / D)).
#[derive(Clone, Copy)]
enum Step {
    Hold {
        secs: f64,
    },
    Turn {
        turn: f64,
        secs: f64,
        dip: f64,
    },
    /// From here on sail at this speed, m/s.
    Speed(f64),
}

/// Integrates the plan in f64 (1 ms steps) and samples it at 1 Hz; returns the fixes and the
/// heading at each sample. `noise` adds a fixed-seed GPS error of that sigma (metres).
fn sail(
    start: [f64; 2],
    heading0: f64,
    speed: f64,
    plan: &[Step],
    noise: f64,
    seed: u64,
) -> Vec<Fix> {
    let dt = 1e-3;
    let mut rng = seed.max(1);
    let mut gauss = || {
        // xorshift + Box–Muller: deterministic, platform-independent enough for a test.
        let mut u = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            ((rng >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let (a, b) = (u(), u());
        (-2.0 * a.ln()).sqrt() * (2.0 * PI * b).cos()
    };
    let (mut x, mut z, mut h, mut t) = (start[0], start[1], heading0, 0.0f64);
    let mut speed = speed;
    let mut out = vec![Fix { t: 0.0, x, z }];
    let mut next = 1.0;
    for step in plan {
        let (secs, rate, dip) = match *step {
            Step::Hold { secs } => (secs, 0.0, 0.0),
            Step::Turn { turn, secs, dip } => (secs, turn / secs, dip),
            Step::Speed(v) => {
                speed = v;
                continue;
            }
        };
        let n = (secs / dt).round() as usize;
        for k in 0..n {
            let s = (k as f64 + 0.5) * dt;
            let v = speed * (1.0 - dip * (PI * s / secs).sin());
            let hh = (h + rate * s).to_radians();
            x += v * hh.sin() * dt;
            z -= v * hh.cos() * dt;
            t += dt;
            if t >= next - 1e-9 {
                out.push(Fix { t: next, x, z });
                next += 1.0;
            }
        }
        h += rate * secs;
    }
    if noise > 0.0 {
        for f in &mut out {
            f.x += noise * gauss();
            f.z += noise * gauss();
        }
    }
    out
}

fn boat(id: &str, fixes: Vec<Fix>) -> Boat {
    let n = fixes.len();
    Boat::build(
        id.into(),
        id.into(),
        "#ff0000".into(),
        fixes,
        vec![false; n],
        vec![
            Logged {
                heading: f32::NAN,
                heel: f32::NAN,
            };
            n
        ],
    )
}

fn race_of(boats: Vec<Boat>) -> Race {
    let report = LoadReport {
        files: vec![],
        origin: None,
        start_time: None,
        start_from: "test".into(),
        boats: vec![],
        file_reports: vec![],
        warnings: vec![],
    };
    Race::new(
        "synthetic".into(),
        None,
        None,
        boats,
        vec![],
        vec![],
        None,
        report,
    )
}

/// Wind from 0° (north); close-hauled at TWA ±45°: starboard heading 315°, port 45°.
fn upwind_plan(tacks: usize, leg_s: f64, tack_s: f64, dip: f64) -> Vec<Step> {
    let mut plan = vec![Step::Hold { secs: leg_s }];
    for k in 0..tacks {
        // From starboard (315°) turn right +90° to 45°, from port turn left −90°.
        let turn = if k % 2 == 0 { 90.0 } else { -90.0 };
        plan.push(Step::Turn {
            turn,
            secs: tack_s,
            dip,
        });
        plan.push(Step::Hold { secs: leg_s });
    }
    plan
}

/// The loss of one modelled tack in closed form: V D √2 (1/2 − 2/π + 4 dip / (3π)) (the
/// integral of V cos 45° − v(s) cos(45° − 90° s / D) over the turn; docs in the test).
fn tack_loss_closed_form(v: f64, d: f64, dip: f64) -> f64 {
    v * d * SQRT_2 * (0.5 - 2.0 / PI + 4.0 * dip / (3.0 * PI))
}

#[test]
fn closed_form_tack_loss_matches_a_direct_quadrature() {
    // The reference itself, against a midpoint sum of the VMG deficit.
    let (v, d, dip) = (5.0, 8.0, 0.6);
    let n = 200_000;
    let sum: f64 = (0..n)
        .map(|k| {
            let s = (k as f64 + 0.5) / n as f64 * d;
            let speed = v * (1.0 - dip * (PI * s / d).sin());
            v * FRAC_PI_4.cos() - speed * (FRAC_PI_4 - FRAC_PI_2 * s / d).cos()
        })
        .sum::<f64>()
        * d
        / n as f64;
    assert!(
        (sum - tack_loss_closed_form(v, d, dip)).abs() < 1e-6,
        "{sum}"
    );
}

#[test]
fn synthetic_tacks_are_found_at_their_times_with_their_closed_form_loss() {
    let (v, d, dip) = (5.0, 8.0, 0.6);
    let plan = upwind_plan(6, 60.0, d, dip);
    let b = boat("A", sail([0.0, 0.0], 315.0, v, &plan, 0.0, 1));
    let wind = WindModel::constant(WindSource::Data, "test", 0.0, 0.0);
    let (t0, t1) = b.time_span();
    let ms = detect(&b, &wind, t0, t1, &Settings::default());
    assert_eq!(ms.len(), 6, "{ms:#?}");
    let truth = tack_loss_closed_form(v, d, dip);
    for (k, m) in ms.iter().enumerate() {
        assert_eq!(m.kind, ManoeuvreKind::Tack);
        // Head to wind at mid-turn: 60 s + k (8 + 60) s + 4 s.
        let t_truth = 60.0 + k as f64 * 68.0 + 4.0;
        assert!(
            (m.t - t_truth).abs() < 1.0,
            "tack {k} at {} vs {t_truth}",
            m.t
        );
        assert!(
            (m.loss_m - truth).abs() < 0.5,
            "tack {k}: loss {} vs closed form {truth}",
            m.loss_m
        );
        assert!((m.entry_speed_mps - v).abs() < 1e-3);
        assert!((m.entry_vmg_mps - v * FRAC_PI_4.cos()).abs() < 1e-3);
        assert!(m.min_speed_mps < v * (1.0 - 0.8 * dip));
        assert_eq!(m.from_side, if k % 2 == 0 { "starboard" } else { "port" });
    }
}

#[test]
fn gps_noise_of_two_metres_neither_adds_nor_hides_a_tack_and_the_error_covers_the_loss() {
    let (v, d, dip) = (3.0, 6.0, 0.6);
    let plan = upwind_plan(8, 45.0, d, dip);
    let truth = tack_loss_closed_form(v, d, dip);
    let wind = WindModel::constant(WindSource::Data, "test", 0.0, 0.0);
    let mut within = 0;
    let mut total = 0;
    for seed in [3u64, 17, 99] {
        let b = boat("A", sail([0.0, 0.0], 315.0, v, &plan, 2.0, seed));
        let (t0, t1) = b.time_span();
        let ms = detect(&b, &wind, t0, t1, &Settings::default());
        assert_eq!(ms.len(), 8, "seed {seed}: {ms:#?}");
        for (k, m) in ms.iter().enumerate() {
            let t_truth = 45.0 + k as f64 * 51.0 + 3.0;
            assert!((m.t - t_truth).abs() < 3.0, "seed {seed} tack {k}: {}", m.t);
            total += 1;
            if (m.loss_m - truth).abs() <= 2.0 * m.loss_sigma_m {
                within += 1;
            }
        }
    }
    // A 2-sigma band holds about 95 %; at least 80 % of 24 here.
    assert!(within * 10 >= total * 8, "{within}/{total} within 2 sigma");
}

#[test]
fn a_gybe_is_a_gybe_and_a_bear_away_at_a_mark_is_no_manoeuvre() {
    // Upwind on starboard (315°), bear away at the mark to starboard run at TWA 140° (heading
    // 220°: the turn passes 270°, never head to wind nor dead downwind), run, gybe to port
    // (TWA −140°, heading 140°, through 180°), run, head up at the leeward mark to port
    // close-hauled (heading 45°).
    let plan = [
        Step::Hold { secs: 60.0 },
        Step::Turn {
            turn: -95.0,
            secs: 8.0,
            dip: 0.2,
        },
        Step::Hold { secs: 60.0 },
        Step::Turn {
            turn: -80.0,
            secs: 6.0,
            dip: 0.3,
        },
        Step::Hold { secs: 60.0 },
        Step::Turn {
            turn: -95.0,
            secs: 8.0,
            dip: 0.3,
        },
        Step::Hold { secs: 60.0 },
    ];
    let b = boat("A", sail([0.0, 0.0], 315.0, 4.0, &plan, 0.5, 5));
    let wind = WindModel::constant(WindSource::Data, "test", 0.0, 0.0);
    let (t0, t1) = b.time_span();
    let ms = detect(&b, &wind, t0, t1, &Settings::default());
    assert_eq!(ms.len(), 1, "{ms:#?}");
    assert_eq!(ms[0].kind, ManoeuvreKind::Gybe);
    // Dead downwind when the heading passes 180°: 40° into an 80° turn of 6 s from 128 s.
    assert!((ms[0].t - 131.0).abs() < 1.0, "{}", ms[0].t);
    assert_eq!(ms[0].from_side, "starboard");
}

#[test]
fn short_wobbles_across_the_wind_are_not_manoeuvres() {
    // Sides alternating faster than the hold time, then a real change.
    let times: Vec<f64> = (0..100).map(|k| k as f64).collect();
    let mut sides = vec![1i8; 100];
    for k in (30..40).step_by(3) {
        sides[k] = -1;
    }
    for s in &mut sides[60..] {
        *s = -1;
    }
    let runs = side_runs(&times, &sides, 8.0);
    assert_eq!(runs.len(), 2, "{runs:?}");
    assert_eq!((runs[0].side, runs[1].side), (1, -1));
    assert_eq!((runs[0].last, runs[1].first), (59, 60));
}

#[test]
fn the_fleet_estimate_finds_a_known_wind_within_its_uncertainty() {
    // Four boats beating and running in a wind from 20°: close-hauled at ±42° (headings 338°
    // and 62°), running at ±150° (headings 230° and 170°), with GPS noise.
    let wind_from = 20.0;
    let mut boats = Vec::new();
    for (i, seed) in [11u64, 12, 13, 14].iter().enumerate() {
        let stb_up = (wind_from - 42.0f64).rem_euclid(360.0);
        let plan = vec![
            Step::Hold {
                secs: 50.0 + 10.0 * i as f64,
            },
            Step::Turn {
                turn: 84.0,
                secs: 6.0,
                dip: 0.5,
            },
            Step::Hold { secs: 70.0 },
            Step::Turn {
                turn: -84.0,
                secs: 6.0,
                dip: 0.5,
            },
            Step::Hold { secs: 60.0 },
            Step::Turn {
                turn: 84.0,
                secs: 6.0,
                dip: 0.5,
            },
            Step::Hold { secs: 80.0 },
            // Bear away to the run on port gybe (TWA −150°: heading 170°), faster downwind.
            Step::Speed(5.0),
            Step::Turn {
                turn: 108.0,
                secs: 8.0,
                dip: 0.2,
            },
            Step::Hold { secs: 90.0 },
            // Gybe to starboard (TWA 150°: heading 230°).
            Step::Turn {
                turn: 60.0,
                secs: 6.0,
                dip: 0.3,
            },
            Step::Hold { secs: 90.0 },
        ];
        boats.push(boat(
            &format!("B{i}"),
            sail([i as f64 * 30.0, 0.0], stb_up, 4.0, &plan, 1.5, *seed),
        ));
    }
    let race = race_of(boats);
    let w = estimate(&race).expect("an estimate");
    assert_eq!(w.source, WindSource::Estimated);
    let err = angle_diff(w.from_deg, wind_from);
    assert!(err.abs() < 2.0, "{} vs {wind_from}", w.from_deg);
    assert!(
        err.abs() <= 3.0 * w.uncertainty_deg,
        "error {err} vs sigma {}",
        w.uncertainty_deg
    );
    // And the detector, on the estimate, finds each boat's 3 tacks and 1 gybe.
    let d = super::Debrief::of(&race);
    for b in &d.manoeuvres {
        assert_eq!((b.tacks, b.gybes), (3, 1), "{}: {:#?}", b.id, b.manoeuvres);
    }
}

#[test]
fn twa_sign_is_starboard_positive() {
    // Wind from the north, heading north-west: the wind comes over the starboard bow.
    assert_eq!(twa_deg(315.0, 0.0), 45.0);
    assert_eq!(twa_deg(45.0, 0.0), -45.0);
    assert_eq!(twa_deg(180.0, 0.0), 180.0);
}

#[test]
fn the_sample_race_wind_estimate_is_near_its_generated_breeze_from_the_north() {
    // The generated fleet (`synth.rs`): a breeze from 0° oscillating by a few degrees.
    let race = Race::sample();
    let w = estimate(&race).expect("an estimate");
    assert!(angle_diff(w.from_deg, 0.0).abs() < 5.0, "{w:?}");
}
