//! The generated sample race (`assets/races/fleet.json`): eight dinghies on a windward-leeward
//! course (start, windward, leeward, windward, finish at the start) in an oscillating breeze
//! from the north, with tacks, gybes, roundings, speed lost in each turn and heel.
//! Deterministic (fixed seed, no platform-dependent maths): `scripts/gen-fleet-race.sh` writes
//! it, and a test checks the committed file is exactly this output.
//!
//! The boats are kinematic: each 0.1 s a boat turns towards its target heading at 20°/s and its
//! speed relaxes (time constant 4 s) towards a simple polar's speed at its true wind angle, so a
//! tack costs a few boat lengths, as on the water. Output is thinned to 1 Hz, 0.1 m.

use std::fmt::Write;

const DT: f64 = 0.1;
const TWD_MEAN: f64 = 0.0;

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        // xorshift64*: plenty for jitter in a demo race.
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

/// Signed angle a - b in (-180, 180].
fn diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    if d > 180.0 { d - 360.0 } else { d }
}

/// Boat speed (m/s) of a dinghy in 4.5 m/s of wind at true wind angle `twa` (degrees, 0–180).
fn polar(twa: f64) -> f64 {
    let pts = [
        (0.0, 0.0),
        (30.0, 0.6),
        (42.0, 2.5),
        (50.0, 2.75),
        (90.0, 3.4),
        (120.0, 3.5),
        (150.0, 3.2),
        (180.0, 2.8),
    ];
    let a = twa.abs().min(180.0);
    for w in pts.windows(2) {
        if a <= w[1].0 {
            let s = (a - w[0].0) / (w[1].0 - w[0].0);
            return w[0].1 + s * (w[1].1 - w[0].1);
        }
    }
    2.8
}

fn bearing(from: [f64; 2], to: [f64; 2]) -> f64 {
    (to[0] - from[0])
        .atan2(-(to[1] - from[1]))
        .to_degrees()
        .rem_euclid(360.0)
}

struct Boat {
    id: &'static str,
    name: &'static str,
    color: &'static str,
    pos: [f64; 2],
    heading: f64,
    speed: f64,
    skill: f64,
    upwind_twa: f64,
    downwind_twa: f64,
    /// +1 starboard tack/gybe (wind over the starboard side), -1 port.
    tack: f64,
    next_mark: usize,
    tack_timer: f64,
    finished_at: Option<f64>,
    track: Vec<[f64; 4]>,
}

/// The sample fleet race as native race JSON (deterministic; the committed
/// `assets/races/fleet.json` is exactly this, see `tests/sample.rs`).
pub fn fleet_race_json() -> String {
    let marks: [(&str, [f64; 2]); 3] = [
        ("Start", [0.0, 400.0]),
        ("W", [0.0, -420.0]),
        ("L", [0.0, 300.0]),
    ];
    let course = [0usize, 1, 2, 1, 0];
    let fleet = [
        ("AUR", "Aurora", "#e6194b"),
        ("BOR", "Boreas", "#ffe119"),
        ("CIR", "Cirrus", "#f58231"),
        ("DOR", "Dorado", "#f032e6"),
        ("EOS", "Eos", "#ffffff"),
        ("FRA", "Fram", "#3cb44b"),
        ("GAL", "Gale", "#911eb4"),
        ("HAL", "Halcyon", "#bcf60c"),
    ];
    let mut rng = Rng(0x5eed_2025_0621);
    let mut boats: Vec<Boat> = fleet
        .iter()
        .enumerate()
        .map(|(i, (id, name, color))| Boat {
            id,
            name,
            color,
            pos: [
                -105.0 + 30.0 * i as f64 + rng.range(-5.0, 5.0),
                445.0 + rng.range(0.0, 10.0),
            ],
            heading: 315.0,
            speed: 0.5,
            skill: rng.range(0.94, 1.03),
            upwind_twa: rng.range(42.0, 46.0),
            downwind_twa: rng.range(145.0, 155.0),
            tack: if i % 2 == 0 { 1.0 } else { -1.0 },
            next_mark: 1,
            tack_timer: rng.range(60.0, 200.0),
            finished_at: None,
            track: Vec::new(),
        })
        .collect();
    let t_start = -45.0;
    let steps = ((2400.0 - t_start) / DT) as usize;
    for k in 0..=steps {
        let t = t_start + k as f64 * DT;
        // An oscillating breeze: ±7° over seven minutes, plus a slower ±4° swing.
        let twd = TWD_MEAN
            + 7.0 * (2.0 * std::f64::consts::PI * t / 420.0).sin()
            + 4.0 * (2.0 * std::f64::consts::PI * t / 1500.0 + 1.0).sin();
        for b in &mut boats {
            if let Some(f) = b.finished_at
                && t > f + 15.0
            {
                continue;
            }
            let target = if b.finished_at.is_some() {
                marks[0].1
            } else {
                marks[course[b.next_mark]].1
            };
            let brg = bearing(b.pos, target);
            let twa_direct = diff(brg, twd).abs();
            let desired = if b.finished_at.is_some() {
                b.heading
            } else if twa_direct < b.upwind_twa + 2.0 {
                // Beat: sail close-hauled, tack at the layline, on the timer, or at the corridor.
                let on = |tack: f64| twd - tack * b.upwind_twa;
                let other_fetches = diff(brg, on(-b.tack)).abs() < 3.0
                    || diff(brg, twd).signum() == -b.tack.signum()
                        && twa_direct > b.upwind_twa - 1.0;
                b.tack_timer -= DT;
                let wide = b.pos[0].abs() > 260.0 && (b.pos[0].signum() == -b.tack);
                if other_fetches || b.tack_timer < 0.0 || wide {
                    b.tack = -b.tack;
                    b.tack_timer = rng.range(70.0, 220.0);
                }
                on(b.tack)
            } else if twa_direct > b.downwind_twa - 2.0 {
                // Run: sail the gybing angle, gybe at the layline, on the timer, or at the corridor.
                let on = |tack: f64| twd + tack * b.downwind_twa;
                let other_fetches = diff(brg, on(-b.tack)).abs() < 3.0
                    || diff(brg, twd + 180.0).signum() == b.tack.signum()
                        && twa_direct < b.downwind_twa + 1.0;
                b.tack_timer -= DT;
                let wide = b.pos[0].abs() > 220.0 && (b.pos[0].signum() == b.tack);
                if other_fetches || b.tack_timer < 0.0 || wide {
                    b.tack = -b.tack;
                    b.tack_timer = rng.range(60.0, 160.0);
                }
                on(b.tack)
            } else {
                brg
            };
            // Before the gun: luff along below the line, slowly.
            let dh = diff(desired, b.heading);
            b.heading = (b.heading + dh.clamp(-20.0 * DT, 20.0 * DT)).rem_euclid(360.0);
            let twa = diff(b.heading, twd);
            let mut target_speed = polar(twa) * b.skill;
            if t < 0.0 {
                target_speed *= 0.25;
            }
            if b.finished_at.is_some() {
                target_speed = 0.6;
            }
            b.speed += (target_speed - b.speed) * (DT / 4.0);
            let h = b.heading.to_radians();
            b.pos[0] += b.speed * h.sin() * DT;
            b.pos[1] -= b.speed * h.cos() * DT;
            if b.finished_at.is_none() && t >= 0.0 {
                let d = ((b.pos[0] - target[0]).powi(2) + (b.pos[1] - target[1]).powi(2)).sqrt();
                if d < 9.0 {
                    b.next_mark += 1;
                    b.tack_timer = rng.range(40.0, 160.0);
                    if b.next_mark == course.len() {
                        b.finished_at = Some(t);
                    }
                }
            }
            if k % 10 == 0 {
                // Heel to leeward, more upwind and in a gust: + to starboard (port tack).
                let heel = -twa.signum() * 14.0 * (1.0 - twa.abs() / 180.0) * b.speed / 3.0;
                b.track.push([t.round(), b.pos[0], b.pos[1], heel]);
            }
        }
    }
    let mut out = String::new();
    out.push_str("{\"name\": \"Table-top fleet race (generated)\",\n");
    out.push_str(" \"origin\": {\"lat\": 39.44, \"lon\": -0.28},\n");
    out.push_str(" \"start_time\": \"2025-06-21T14:00:00Z\",\n");
    let _ = writeln!(
        out,
        " \"wind\": {{\"from_deg\": {TWD_MEAN:.1}, \"speed_mps\": 4.5}},"
    );
    out.push_str(" \"marks\": [");
    for (i, (n, p)) in marks.iter().enumerate() {
        let _ = write!(
            out,
            "{}{{\"name\": \"{n}\", \"position\": [{:.1}, {:.1}]}}",
            if i > 0 { ", " } else { "" },
            p[0],
            p[1]
        );
    }
    out.push_str("],\n \"course\": [");
    let names: Vec<String> = course
        .iter()
        .map(|&c| format!("\"{}\"", marks[c].0))
        .collect();
    out.push_str(&names.join(", "));
    out.push_str("],\n \"boats\": [\n");
    for (i, b) in boats.iter().enumerate() {
        let _ = write!(
            out,
            "  {{\"id\": \"{}\", \"name\": \"{}\", \"color\": \"{}\",\n   \"track\": [",
            b.id, b.name, b.color
        );
        let pts: Vec<String> = b
            .track
            .iter()
            .map(|p| format!("[{:.0},{:.1},{:.1}]", p[0], p[1], p[2]))
            .collect();
        out.push_str(&pts.join(","));
        out.push_str("],\n   \"heel\": [");
        let heel: Vec<String> = b.track.iter().map(|p| format!("{:.1}", p[3])).collect();
        out.push_str(&heel.join(","));
        let _ = writeln!(out, "]}}{}", if i + 1 < boats.len() { "," } else { "" });
    }
    out.push_str(" ]}\n");
    out
}
