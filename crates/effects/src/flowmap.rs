//! Flow-map texture distortion with the UV jump (as the Sailing+ AR water thesis, TU Delft
//! 2022, report 000 in docs/sources.md, does it in its § 3.1; after Vlachos, "Water Flow in
//! Portal 2", 2010, and Flick's flow tutorial), used for the tidal current around marks.
//! f64 reference of `shaders/effects/flowmap.wgsl`.
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
//!
//! The advected detail is a height field's slopes ([`crate::flow_detail`]), so it tilts the
//! water as one: its slopes ([`flow_slope`]) add to the sea's and the wakes', and the normal is
//! that of the summed surface ([`normal_of_slopes`]), normalised once. (Before the thirteenth
//! session the detail was added to the sea's unit normal and normalised again: that is the
//! normal of the slopes ∇h + L·s with L = |(∂h/∂x, 1, ∂h/∂z)|, the detail exaggerated by L on
//! sloped water; on flat water, L = 1, the two agree.)

use glam::{DVec2, DVec3};

use crate::flow_detail::detail_slope;

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

/// The flow-advected detail's slopes (∂/∂x, ∂/∂z; dimensionless) at local point `p` (m) where
/// the water runs at `current` (m/s), for a detail tile of `tile` metres per flow period (the
/// period folded into the tile: the flow moves `current / tile` tiles per period) and the two
/// copies `phases` ([`flow_phases`]): the copies' weighted [`detail_slope`]s, scaled by
/// k = clamp(4·|current / tile|, 0, 1) so still water shows no pattern. `flow_slope` of
/// `shaders/effects/flowmap.wgsl`.
pub fn flow_slope(p: DVec2, current: DVec2, tile: f64, phases: &[FlowPhase; 2]) -> DVec2 {
    let flow = current / tile;
    let uv = p / tile;
    let s: DVec2 = phases
        .iter()
        .map(|phase| detail_slope(flow_uv(uv, flow, phase)) * phase.weight)
        .sum();
    s * (flow.length() * 4.0).clamp(0.0, 1.0)
}

/// The unit normal of a surface y = h(x, z) whose slopes are `slope` = (∂h/∂x, ∂h/∂z):
/// (−∂h/∂x, 1, −∂h/∂z) normalised. The AR water's normal is this of the sea's, the wakes' and
/// [`flow_slope`]'s slopes summed (`fs_ar` in `shaders/effects/ar_water.wgsl`).
pub fn normal_of_slopes(slope: DVec2) -> DVec3 {
    DVec3::new(-slope.x, 1.0, -slope.y).normalize()
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

/// Bound on the error of the current interpolated linearly across a triangle `tri` of the
/// water mesh (vertices in metres), m/s, against [`current_at`]: the AR water evaluates the
/// current per vertex and the rasteriser interpolates it (`shaders/ar_water.wgsl`, `vs_ar`).
/// `None` when the triangle may reach into a mark (there the field drops to zero inside the
/// mark, which the mark itself covers, and the blend across the rim is up to 2|U| off).
///
/// In complex numbers ζ = x + iz the conjugate velocity past a mark of radius a is analytic,
/// w(ζ) = Ū − a² U / ζ², so every second directional derivative of the field has magnitude
/// |w''| = 6 a² |U| / r⁴ (summed over the marks, r the distance to each centre). Linear
/// interpolation on a triangle errs by at most half the squared radius of its smallest
/// enclosing circle times that (Waldron, "The error in linear interpolation at the vertices of
/// a simplex", SIAM J. Numer. Anal. 35, 1998); the circle's radius is at most h/√3 for a
/// longest edge h, and every point of the triangle is within h of each vertex.
pub fn current_interpolation_error(
    current: DVec2,
    marks: &[MarkObstacle],
    tri: [DVec2; 3],
) -> Option<f64> {
    let [a, b, c] = tri;
    let h = (b - a).length().max((c - b).length()).max((a - c).length());
    let mut second = 0.0;
    for m in marks {
        let nearest = tri
            .iter()
            .map(|p| (*p - m.centre).length())
            .fold(f64::INFINITY, f64::min);
        let r = nearest - h;
        if r <= m.radius {
            return None;
        }
        second += 6.0 * m.radius * m.radius * current.length() / r.powi(4);
    }
    Some(0.5 * h * h / 3.0 * second)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_current_interpolated_from_vertices_stays_within_its_bound() {
        // Triangles of 5 cm to 4 m, acute and obtuse, all around two marks in a current; the
        // linear blend of the vertices' f64 currents against the field at points inside.
        let u = DVec2::new(0.6, 0.2);
        let marks = [
            MarkObstacle {
                centre: DVec2::new(0.0, 0.0),
                radius: 4.0,
            },
            MarkObstacle {
                centre: DVec2::new(40.0, 10.0),
                radius: 4.0,
            },
        ];
        let mut rnd = render::golden::fixed_seed_uniform(7);
        let (mut worst_ratio, mut checked) = (0.0f64, 0);
        for _ in 0..4000 {
            let h = 0.05 * (80.0f64).powf(rnd());
            let o = DVec2::new(rnd() * 60.0 - 15.0, rnd() * 40.0 - 15.0);
            let tri = [
                o,
                o + DVec2::from_angle(rnd() * 6.3) * h,
                o + DVec2::from_angle(rnd() * 6.3) * h * (0.2 + 0.8 * rnd()),
            ];
            let Some(bound) = current_interpolation_error(u, &marks, tri) else {
                continue;
            };
            let v = tri.map(|p| current_at(p, u, &marks));
            for _ in 0..12 {
                let (s, t) = (rnd(), rnd());
                let (s, t) = if s + t > 1.0 {
                    (1.0 - s, 1.0 - t)
                } else {
                    (s, t)
                };
                let p = tri[0] + (tri[1] - tri[0]) * s + (tri[2] - tri[0]) * t;
                let blend = v[0] + (v[1] - v[0]) * s + (v[2] - v[0]) * t;
                let err = (blend - current_at(p, u, &marks)).length();
                assert!(
                    err <= bound * (1.0 + 1e-9) + 1e-15,
                    "{err} > {bound} for {tri:?}"
                );
                worst_ratio = worst_ratio.max(err / bound);
                checked += 1;
            }
        }
        // The bound holds everywhere and is not vacuous.
        assert!(checked > 20_000, "{checked}");
        assert!(
            worst_ratio > 0.05,
            "the bound is loose: worst error / bound {worst_ratio}"
        );
        // A number to quote: a 0.5 m cell 1 m outside a 4 m mark's rim in a 0.63 m/s current.
        let near = current_interpolation_error(
            u,
            &marks[..1],
            [
                DVec2::new(5.5, 0.0),
                DVec2::new(6.0, 0.0),
                DVec2::new(5.5, 0.5),
            ],
        )
        .expect("outside the mark");
        eprintln!(
            "current interpolation: worst error / bound {worst_ratio:.3} over {checked} points; \
             0.5 m cell 1 m off the rim: bound {near:.4} m/s"
        );
        assert!(near < 0.05 * u.length(), "{near}");
    }

    #[test]
    fn the_detail_tilts_the_water_as_slopes_of_one_height_field() {
        // A sea y = h(x, z) and a detail with slopes s: the normal of the summed surface is the
        // cross product of its tangents along z and x, (0, ∂/∂z, 1) × (1, ∂/∂x, 0), with the
        // sea's slopes by central differences of the closed-form height.
        let h = |q: DVec2| 0.3 * (0.7 * q.x).sin() * (0.4 * q.y).cos() + 0.05 * q.y;
        let d = 1e-5;
        let phases = flow_phases(7.3, 2.0, DEFAULT_JUMP);
        let current = DVec2::new(0.5, -0.2);
        for (i, p) in [
            DVec2::new(1.0, 2.0),
            DVec2::new(-3.5, 0.7),
            DVec2::new(8.0, -6.0),
        ]
        .into_iter()
        .enumerate()
        {
            let sea = DVec2::new(
                (h(p + DVec2::X * d) - h(p - DVec2::X * d)) / (2.0 * d),
                (h(p + DVec2::Y * d) - h(p - DVec2::Y * d)) / (2.0 * d),
            );
            let s = flow_slope(p, current, 12.0, &phases);
            assert!(s.length() > 1e-3, "no detail at point {i}: {s}");
            let g = sea + s;
            let want = DVec3::new(0.0, g.y, 1.0)
                .cross(DVec3::new(1.0, g.x, 0.0))
                .normalize();
            let got = normal_of_slopes(g);
            assert!((got - want).length() < 1e-12, "{got} against {want}");
            // The old definition (the detail added to the sea's unit normal, normalised
            // again) is the normal of the slopes ∇h + L·s, L = |(∂h/∂x, 1, ∂h/∂z)| > 1 here:
            // it tilted the sloped sea further than the detail's own slopes do.
            let up = normal_of_slopes(sea);
            let old = (up + DVec3::new(-s.x, 0.0, -s.y)).normalize();
            let l = DVec3::new(sea.x, 1.0, sea.y).length();
            assert!(l > 1.001, "point {i} is flat");
            assert!((old - normal_of_slopes(sea + s * l)).length() < 1e-12);
            assert!((old - up).length() > (got - up).length(), "point {i}");
        }
        // On flat water the two definitions agree.
        let s = flow_slope(DVec2::new(2.0, 3.0), current, 12.0, &phases);
        let old = (DVec3::Y + DVec3::new(-s.x, 0.0, -s.y)).normalize();
        assert!((normal_of_slopes(s) - old).length() < 1e-15);
    }

    #[test]
    fn a_triangle_interpolates_the_sample_points_as_it_interpolates_point_and_current() {
        // The AR water forms each copy's sample point at the vertices (`flow_sample_points` in
        // vs_ar) and the rasteriser blends them with the same barycentric weights as the
        // point and the current: the blend of the vertices' sample points is the sample point
        // of the blended point and current (flow_uv is affine in both).
        let phases = flow_phases(5.7, 2.0, DEFAULT_JUMP);
        let tile = 12.0;
        let mut rnd = render::golden::fixed_seed_uniform(11);
        for _ in 0..500 {
            let mut corner = || {
                (
                    DVec2::new(rnd() * 80.0 - 40.0, rnd() * 80.0 - 40.0),
                    DVec2::new(rnd() * 2.0 - 1.0, rnd() * 2.0 - 1.0),
                )
            };
            let tri = [corner(), corner(), corner()];
            let (s, t) = (rnd() * 0.5, rnd() * 0.5);
            let w = [1.0 - s - t, s, t];
            let blend = |f: &dyn Fn(DVec2, DVec2) -> DVec2| {
                tri.iter()
                    .zip(w)
                    .map(|(&(p, c), w)| f(p, c) * w)
                    .sum::<DVec2>()
            };
            let (p, c) = (blend(&|p, _| p), blend(&|_, c| c));
            for phase in &phases {
                let interpolated = blend(&|p, c| flow_uv(p / tile, c / tile, phase));
                let formed = flow_uv(p / tile, c / tile, phase);
                assert!(
                    (interpolated - formed).length() < 1e-13,
                    "{interpolated} {formed}"
                );
            }
        }
        // Not so for the strength k, which the pixel forms from the interpolated current: at
        // the middle of an edge from still water to 6 m/s the vertices' k (0 and 1) blend to
        // 0.5, the middle's current gives k = 1.
        let k = |c: DVec2| (c.length() / tile * 4.0).clamp(0.0, 1.0);
        let (c0, c1) = (DVec2::ZERO, DVec2::new(6.0, 0.0));
        assert_eq!((k(c0) + k(c1)) / 2.0, 0.5);
        assert_eq!(k((c0 + c1) / 2.0), 1.0);
    }

    #[test]
    fn the_flow_detail_fades_out_in_still_water_and_saturates_in_a_current() {
        let phases = flow_phases(3.1, 2.0, DEFAULT_JUMP);
        let p = DVec2::new(4.0, -1.5);
        assert_eq!(flow_slope(p, DVec2::ZERO, 12.0, &phases), DVec2::ZERO);
        // k = 4·|current|/tile: a quarter of it at 0.75 m/s in a 12 m tile...
        let slow = DVec2::new(0.75, 0.0);
        let fast = DVec2::new(3.0, 0.0);
        let full = |c: DVec2| -> DVec2 {
            let flow = c / 12.0;
            phases
                .iter()
                .map(|ph| detail_slope(p / 12.0 - flow * ph.progress + ph.offset) * ph.weight)
                .sum()
        };
        assert!((flow_slope(p, slow, 12.0, &phases) - full(slow) * 0.25).length() < 1e-15);
        // ... and all of it from 3 m/s (k = 1) on.
        assert!((flow_slope(p, fast, 12.0, &phases) - full(fast)).length() < 1e-15);
        assert!((flow_slope(p, fast * 2.0, 12.0, &phases) - full(fast * 2.0)).length() < 1e-15);
    }

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
