//! Height at a world point: the inverse of the horizontal Gerstner displacement.
//!
//! A rest point x0 goes to X(x0) = x0 + Σ D A cos θ. This map is the gradient of the strongly
//! convex Φ(x0) = |x0|²/2 + Σ (A/k) sin θ, whose Hessian J = I − Σ kA sin θ D Dᵀ has both
//! eigenvalues in [1 − Σ kA, 1 + Σ kA]. So for a valid sea (Σ kA < 1) every world point has
//! exactly one rest point, and Newton's method on X(x0) = X converges from any start when its
//! step is damped (halved until the residual shrinks). We start at x0 = X.
//!
//! Tolerance: on the horizontal residual |X(x0) − X|. The rest point is then within
//! tol / (1 − Σ kA) of the true one, and the height within tol · Σ kA / (1 − Σ kA).

use std::fmt;

use crate::WaveSet;
use crate::gerstner::{Eval, WaveAt, eval, foam_from_jacobian};

/// Default tolerance on the horizontal residual, metres.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;
/// Newton iterations before giving up.
pub const MAX_ITERATIONS: u32 = 60;

/// The rest point found for a world point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestPoint {
    /// The undisplaced point (x0, z0) that the waves carry to the world point, metres.
    pub rest: [f64; 2],
    /// Newton steps taken (0 when the world point was its own rest point within tolerance).
    /// The work is `iterations + 1` surface evaluations (plus any damping halvings, counted
    /// in `evaluations`).
    pub iterations: u32,
    /// Surface evaluations (each one sin_cos per wave) spent.
    pub evaluations: u32,
    /// The final horizontal residual |X(rest) − X|, metres (≤ the tolerance).
    pub residual: f64,
}

/// The sea at a world point: what `regatta probe` and the boats' float heights need.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSample {
    pub rest: RestPoint,
    /// Height above the rest level, metres.
    pub height: f64,
    /// ∂h/∂X, ∂h/∂Z of the height over the world horizontal point (dimensionless slopes), so a
    /// wake can add its own gradient before the normal is formed.
    pub gradient: [f64; 2],
    /// Unit normal of the wave surface there.
    pub normal: [f64; 3],
    /// Jacobian determinant of the horizontal map at the rest point.
    pub jacobian: f64,
    /// [`foam_from_jacobian`] of it.
    pub foam: f64,
}

/// The inverse did not converge (only possible for a sea with Σ kA ≥ 1, a NaN input, or a
/// tolerance below what f64 can resolve at that coordinate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InverseError {
    pub at: [f64; 2],
    pub t: f64,
    pub tolerance: f64,
    pub iterations: u32,
    pub residual: f64,
}

impl fmt::Display for InverseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the rest point of ({}, {}) at t = {} s did not converge to {:e} m in {} Newton iterations (residual {:e} m)",
            self.at[0], self.at[1], self.t, self.tolerance, self.iterations, self.residual
        )
    }
}

impl std::error::Error for InverseError {}

fn residual(e: &Eval, at: [f64; 2]) -> ([f64; 2], f64) {
    let r = [e.pos[0] - at[0], e.pos[2] - at[1]];
    (r, r[0].hypot(r[1]))
}

/// Newton on frozen waves; returns the rest point and the evaluation there.
fn solve(
    waves: &[WaveAt],
    at: [f64; 2],
    t: f64,
    tol: f64,
) -> Result<(RestPoint, Eval), InverseError> {
    let mut x0 = at;
    let mut e = eval(waves.iter().copied(), x0);
    let (mut r, mut rn) = residual(&e, at);
    let mut evaluations = 1;
    let fail = |iterations, residual| InverseError {
        at,
        t,
        tolerance: tol,
        iterations,
        residual,
    };
    for iterations in 0..=MAX_ITERATIONS {
        if rn <= tol {
            let rest = RestPoint {
                rest: x0,
                iterations,
                evaluations,
                residual: rn,
            };
            return Ok((rest, e));
        }
        if !rn.is_finite() || iterations == MAX_ITERATIONS {
            return Err(fail(iterations, rn));
        }
        // Newton step δ = −J⁻¹ r (J symmetric 2×2).
        let det = e.det();
        let step = [
            -(e.jzz * r[0] - e.jxz * r[1]) / det,
            -(e.jxx * r[1] - e.jxz * r[0]) / det,
        ];
        let mut scale = 1.0;
        loop {
            let cand = [x0[0] + scale * step[0], x0[1] + scale * step[1]];
            let ce = eval(waves.iter().copied(), cand);
            evaluations += 1;
            let (cr, crn) = residual(&ce, at);
            // Accept a step that shrinks the residual; give up halving once the step is
            // below what f64 resolves (the residual is then at its rounding floor).
            if crn < rn || scale < 1e-12 {
                (x0, e, r, rn) = (cand, ce, cr, crn);
                break;
            }
            scale *= 0.5;
        }
    }
    unreachable!("the loop returns at MAX_ITERATIONS")
}

impl WaveSet {
    /// The rest point that the waves carry to the world point `at` = (X, Z) at time `t`, with
    /// the horizontal residual ≤ `tolerance` metres.
    pub fn rest_point(
        &self,
        at: [f64; 2],
        t: f64,
        tolerance: f64,
    ) -> Result<RestPoint, InverseError> {
        let waves: Vec<WaveAt> = self.at_time(t).collect();
        solve(&waves, at, t, tolerance).map(|(r, _)| r)
    }

    /// Height above the rest level at the world point `at`, to [`DEFAULT_TOLERANCE`].
    pub fn height_at(&self, at: [f64; 2], t: f64) -> Result<f64, InverseError> {
        self.sample_at(at, t, DEFAULT_TOLERANCE).map(|s| s.height)
    }

    /// Height, slopes, normal and foam of the wave surface at the world point `at`.
    pub fn sample_at(
        &self,
        at: [f64; 2],
        t: f64,
        tolerance: f64,
    ) -> Result<WorldSample, InverseError> {
        let waves: Vec<WaveAt> = self.at_time(t).collect();
        let (rest, e) = solve(&waves, at, t, tolerance)?;
        let jacobian = e.det();
        Ok(WorldSample {
            rest,
            height: e.pos[1],
            gradient: e.world_gradient(),
            normal: e.normal(),
            jacobian,
            foam: foam_from_jacobian(jacobian),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Wave;

    #[test]
    fn inverse_then_forward_returns_the_world_point() {
        let s = WaveSet::default_sea();
        for &(x, z, t) in &[
            (0.0, 0.0, 0.0),
            (33.0, -71.0, 500.0),
            (-9500.0, 8000.0, 9e6),
        ] {
            let r = s.rest_point([x, z], t, 1e-9).unwrap();
            let p = s.displace(r.rest, t);
            assert!((p[0] - x).hypot(p[2] - z) <= 1e-9, "{p:?}");
            assert!(r.iterations >= 1);
            let h = s.height_at([x, z], t).unwrap();
            assert!((h - p[1]).abs() < 1e-6);
        }
    }

    #[test]
    fn single_wave_inverse_against_bisection() {
        // One wave along x: X = x0 + A cos(k x0 + θt) is strictly increasing in x0 (kA < 1):
        // bisection gives an independent reference.
        let s = WaveSet {
            gravity: 9.81,
            depth: None,
            waves: vec![Wave {
                direction: [1.0, 0.0],
                steepness: 0.95,
                wavelength: 20.0,
                phase: 0.4,
            }],
        };
        let t = 17.0;
        for &x in &[-13.0, 0.0, 2.5, 7.9, 1234.5] {
            let (mut lo, mut hi) = (x - 10.0, x + 10.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if s.displace([mid, 0.0], t)[0] < x {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            let r = s.rest_point([x, 0.0], t, 1e-10).unwrap();
            assert!((r.rest[0] - 0.5 * (lo + hi)).abs() < 1e-8, "{r:?} {lo}");
        }
    }

    #[test]
    fn world_gradient_and_normal_match_finite_differences_of_height() {
        let s = WaveSet::default_sea();
        let (x, z, t) = (21.0, -5.0, 42.0);
        let w = s.sample_at([x, z], t, 1e-12).unwrap();
        let h = |dx: f64, dz: f64| s.sample_at([x + dx, z + dz], t, 1e-12).unwrap().height;
        let d = 1e-4;
        let gx = (h(d, 0.0) - h(-d, 0.0)) / (2.0 * d);
        let gz = (h(0.0, d) - h(0.0, -d)) / (2.0 * d);
        assert!((gx - w.gradient[0]).abs() < 1e-6, "{gx} {:?}", w.gradient);
        assert!((gz - w.gradient[1]).abs() < 1e-6);
        let len = (gx * gx + 1.0 + gz * gz).sqrt();
        let n = [-gx / len, 1.0 / len, -gz / len];
        for (a, b) in n.iter().zip(w.normal) {
            assert!((a - b).abs() < 1e-6);
        }
    }

    #[test]
    fn a_folded_sea_or_nan_reports_non_convergence() {
        // Σ kA = 1.8: the map folds, Newton cannot converge everywhere; never a panic.
        let fold = WaveSet {
            gravity: 9.81,
            depth: None,
            waves: vec![
                Wave {
                    direction: [1.0, 0.0],
                    steepness: 0.9,
                    wavelength: 10.0,
                    phase: 0.0,
                },
                Wave {
                    direction: [1.0, 0.0],
                    steepness: 0.9,
                    wavelength: 10.0,
                    phase: 0.0,
                },
            ],
        };
        let failures = (0..200)
            .filter(|i| fold.rest_point([*i as f64 * 0.05, 0.0], 0.0, 1e-6).is_err())
            .count();
        assert!(failures > 0);
        let e = WaveSet::default_sea()
            .rest_point([f64::NAN, 0.0], 0.0, 1e-6)
            .unwrap_err();
        assert!(e.to_string().contains("did not converge"), "{e}");
    }
}
