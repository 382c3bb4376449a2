//! Flow-map texture distortion with the UV jump (source 000 § 3.1, after Vlachos, "Water Flow
//! in Portal 2", 2010, and Flick's flow tutorial), used for the tidal current around marks.
//! f64 reference of `shaders/flowmap.wgsl`.
//!
//! A detail texture is advected along the flow for one period, then restarts. Two copies (A and
//! B) run half a period apart and are blended with triangle weights that are 0 at each copy's
//! restart, so the restart is never seen; at each restart the copy's UV also *jumps* by a fixed
//! offset, so successive periods do not show the same pattern (000's "UV jump").
//!
//! Race time is reduced here in f64 (progress in [0, 1), the jump offset modulo one texture
//! tile) so the shader never sees a large time.
//!
//! The current around a mark is the closed-form potential flow past a cylinder: uniform far
//! away, no flow through the mark, twice as fast at its sides, still at its front and back.

use glam::DVec2;

/// One of the two advected copies at one moment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlowPhase {
    /// Time since this copy's last restart, in periods, in [0, 1).
    pub progress: f64,
    /// Blend weight 1 − |1 − 2·progress|: 0 at a restart, 1 half-way.
    pub weight: f64,
    /// UV offset of this copy: its half-tile phase shift plus the accumulated jumps, modulo 1.
    pub offset: DVec2,
}

/// The two copies A and B at race time `t` (seconds) for a restart period `period` (seconds)
/// and a UV `jump` per restart. Their weights always sum to 1.
pub fn flow_phases(t: f64, period: f64, jump: DVec2) -> [FlowPhase; 2] {
    let tau = t / period;
    [0.0, 0.5].map(|shift| {
        let cycles = (tau + shift).floor();
        let progress = tau + shift - cycles;
        // Reduce the accumulated jump in f64: cycles × jump can be large after hours of race.
        let offset = (DVec2::splat(shift) + cycles * jump).map(|c| c.rem_euclid(1.0));
        FlowPhase {
            progress,
            weight: 1.0 - (1.0 - 2.0 * progress).abs(),
            offset,
        }
    })
}

/// The texture UV one copy samples at `uv`: moved back along `flow` (UV units per period) by
/// its progress, plus its offset.
pub fn flow_uv(uv: DVec2, flow: DVec2, phase: &FlowPhase) -> DVec2 {
    uv - flow * phase.progress + phase.offset
}

/// Jump that Flick found to give a long, unrepeating sequence: 25 restarts before a repeat
/// in u, 24 in v.
pub const DEFAULT_JUMP: DVec2 = DVec2::new(0.24, 0.208_333_333_333_333_34);

/// A course mark standing in the current.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarkObstacle {
    /// Centre (x, z), metres.
    pub centre: DVec2,
    /// Radius, metres, > 0.
    pub radius: f64,
}

/// The current velocity (m/s, in the (x, z) plane) at `p` for a uniform current `current` far
/// away and the `marks` in it: potential flow past each mark as a cylinder, superposed (exact for
/// one mark; for several, accurate while they are many radii apart). Zero inside a mark.
///
/// For one mark at the origin and the current U along x: v = U (1 − a² (x² − z²)/r⁴,
/// −2 a² x z / r⁴).
pub fn current_at(p: DVec2, current: DVec2, marks: &[MarkObstacle]) -> DVec2 {
    let speed = current.length();
    if speed == 0.0 {
        return DVec2::ZERO;
    }
    let along = current / speed;
    let mut v = current;
    for m in marks {
        let d = p - m.centre;
        // Into the frame where the current runs along +x.
        let (x, z) = (d.dot(along), d.dot(along.perp()));
        let r2 = x * x + z * z;
        let a2 = m.radius * m.radius;
        if r2 <= a2 {
            return DVec2::ZERO;
        }
        let r4 = r2 * r2;
        let pert = DVec2::new(-a2 * (x * x - z * z) / r4, -2.0 * a2 * x * z / r4) * speed;
        // Back to world axes.
        v += along * pert.x + along.perp() * pert.y;
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_weights_sum_to_one_and_hide_each_restart() {
        let jump = DEFAULT_JUMP;
        for i in 0..2000 {
            let t = i as f64 * 0.0137 + 3.0;
            let [a, b] = flow_phases(t, 2.0, jump);
            assert!((a.weight + b.weight - 1.0).abs() < 1e-12, "t = {t}");
            assert!((0.0..1.0).contains(&a.progress) && (0.0..1.0).contains(&b.progress));
            assert!(((b.progress - a.progress).rem_euclid(1.0) - 0.5).abs() < 1e-9);
        }
        // At A's restart its weight is 0 and B carries everything.
        let [a, b] = flow_phases(10.0, 2.0, jump);
        assert!(a.progress.abs() < 1e-12 && a.weight.abs() < 1e-12);
        assert!((b.weight - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_uv_jumps_by_the_jump_vector_at_each_restart() {
        let jump = DEFAULT_JUMP;
        let period = 2.0;
        let before = flow_phases(10.0 - 1e-9, period, jump)[0];
        let after = flow_phases(10.0 + 1e-9, period, jump)[0];
        let step = (after.offset - before.offset).map(|c| c.rem_euclid(1.0));
        assert!((step - jump).length() < 1e-9, "{step}");
        // Within a period the offset stays put.
        let mid = flow_phases(10.9, period, jump)[0];
        assert_eq!(mid.offset, after.offset);
        // B starts half a tile away from A and jumps half a period later.
        let b0 = flow_phases(0.0, period, jump)[1];
        assert!((b0.offset - DVec2::splat(0.5)).length() < 1e-12);
        // Flick's jump repeats only after 25 restarts.
        let o = |k: f64| flow_phases(k * period + 0.1, period, jump)[0].offset;
        for k in 1..25 {
            assert!((o(k as f64) - o(0.0)).length() > 1e-6, "repeats after {k}");
        }
        assert!((o(25.0).x - o(0.0).x).abs() < 1e-9);
    }

    #[test]
    fn the_blended_texture_moves_continuously_through_restarts() {
        // Sample a smooth tiling texture through both copies; the blend must not pop.
        let tex = |uv: DVec2| {
            (std::f64::consts::TAU * uv.x).sin() * (std::f64::consts::TAU * 2.0 * uv.y).cos()
        };
        let flow = DVec2::new(0.3, -0.1);
        let uv = DVec2::new(0.37, 0.61);
        let blend = |t: f64| {
            flow_phases(t, 1.5, DEFAULT_JUMP)
                .iter()
                .map(|p| p.weight * tex(flow_uv(uv, flow, p)))
                .sum::<f64>()
        };
        let dt = 1e-4;
        let mut worst = 0.0f64;
        for i in 0..30000 {
            let t = i as f64 * dt;
            worst = worst.max((blend(t + dt) - blend(t)).abs());
        }
        // Largest slope: weights change at 2/period, the texture at 2π·|flow|/period per
        // second; both bounded, so steps stay of order dt.
        assert!(worst < 50.0 * dt, "a pop of {worst}");
    }

    #[test]
    fn long_races_reduce_time_on_the_cpu() {
        // Ten hours in, the phases are as exact as in the first minute.
        let period = 1.7;
        let n = 21176.0; // whole periods, about 10 h
        let early = flow_phases(0.4, period, DVec2::new(0.25, 0.5));
        let late = flow_phases(n * period + 0.4, period, DVec2::new(0.25, 0.5));
        for (e, l) in early.iter().zip(&late) {
            assert!((e.progress - l.progress).abs() < 1e-9);
            assert!((0.0..1.0).contains(&l.offset.x) && (0.0..1.0).contains(&l.offset.y));
        }
        // 21176 × (0.25, 0.5) is whole tiles: the offsets agree too.
        assert!((early[0].offset - late[0].offset).length() < 1e-9);
    }

    #[test]
    fn current_flows_around_a_mark_not_through_it() {
        let u = DVec2::new(0.4, 0.3); // 0.5 m/s towards east-south-east
        let mark = MarkObstacle {
            centre: DVec2::new(2.0, -1.0),
            radius: 1.5,
        };
        let along = u.normalize();
        // Far away: the free current.
        let far = current_at(mark.centre + along.perp() * 200.0, u, &[mark]);
        assert!((far - u).length() < 1e-4 * u.length());
        // On the mark's rim the flow is tangential (no flow into the mark).
        for i in 0..36 {
            let a = i as f64 * 10f64.to_radians();
            let n = DVec2::new(a.cos(), a.sin());
            let v = current_at(mark.centre + n * mark.radius * (1.0 + 1e-12), u, &[mark]);
            assert!(v.dot(n).abs() < 1e-9, "radial flow {} at {i}0°", v.dot(n));
        }
        // Twice as fast at the sides, still at the front and the back.
        let side = current_at(
            mark.centre + along.perp() * mark.radius * 1.000001,
            u,
            &[mark],
        );
        assert!((side.length() - 2.0 * u.length()).abs() < 1e-5 && side.dot(u) > 0.0);
        let front = current_at(mark.centre - along * mark.radius * 1.000001, u, &[mark]);
        assert!(front.length() < 1e-5);
        assert_eq!(current_at(mark.centre, u, &[mark]), DVec2::ZERO);
        // Incompressible and irrotational: zero divergence and curl (central differences).
        let p = mark.centre + DVec2::new(1.1, 2.3);
        let h = 1e-5;
        let v = |q: DVec2| current_at(q, u, &[mark]);
        let dvx = (v(p + DVec2::X * h) - v(p - DVec2::X * h)) / (2.0 * h);
        let dvz = (v(p + DVec2::Y * h) - v(p - DVec2::Y * h)) / (2.0 * h);
        assert!((dvx.x + dvz.y).abs() < 1e-6, "divergence");
        assert!((dvx.y - dvz.x).abs() < 1e-6, "curl");
        // No current, no flow.
        assert_eq!(current_at(p, DVec2::ZERO, &[mark]), DVec2::ZERO);
    }
}
