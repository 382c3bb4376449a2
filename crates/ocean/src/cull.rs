//! Error-bounded wave culling.
//!
//! Each wave moves a rest point by the vector (D A cos θ, A sin θ), whose length is exactly A.
//! So dropping a set of waves moves every displaced surface point (same rest point, any time)
//! by at most δ = Σ A over the dropped waves: that is the rigorous bound this module returns,
//! and what the renderer's per-vertex displacement error is.
//!
//! At a fixed *world* point the height error also includes the horizontal shift: the kept
//! surface is a graph with slope at most L = S/(1 − S), S = Σ kA of the kept waves
//! (|∇y| ≤ S over rest points, |J⁻¹| ≤ 1/(1 − S)), so |h(X) − h_kept(X)| ≤ δ·sqrt(1 + L²).
//! Slopes are not bounded by δ: each dropped wave changes ∇y by up to kA, so the slope error
//! bound is Σ kA over the dropped waves (reported too; short waves matter for normals).
//!
//! A grid of spacing Δ cannot represent a wave shorter than two cells (Nyquist), so for a
//! clip-map level those waves are dropped whatever ε says, and counted in the bound.

use crate::WaveSet;

/// The waves kept for a tolerance, and the bounds of what was dropped.
#[derive(Debug, Clone, PartialEq)]
pub struct Culled {
    /// The kept waves (same gravity and depth).
    pub sea: WaveSet,
    /// Indices of the kept waves in the original set, in their original order.
    pub kept: Vec<usize>,
    /// Σ A of the dropped waves, metres: bound of |P(x0) − P_kept(x0)| for every rest point
    /// and time (3-D displacement, so also of the height error at a rest point).
    pub displacement_bound: f64,
    /// Bound of |h(X) − h_kept(X)| at every world point and time, metres.
    pub height_bound: f64,
    /// Σ kA of the dropped waves: bound of the error of ∂y/∂x0 and ∂y/∂z0.
    pub slope_bound: f64,
    /// How many waves were dropped because they are shorter than the minimum wavelength.
    pub below_grid: usize,
}

impl WaveSet {
    /// Drop the waves whose summed amplitude stays within `epsilon` metres, smallest first
    /// (that drops the most waves for the budget), after dropping every wave shorter than
    /// `min_wavelength` (use 2 × the grid spacing of a clip-map level, or 0). When the
    /// unrepresentable waves alone exceed `epsilon`, the returned bound says so honestly.
    pub fn cull(&self, epsilon: f64, min_wavelength: f64) -> Culled {
        let mut order: Vec<usize> = (0..self.waves.len()).collect();
        let amp = |i: usize| self.waves[i].amplitude();
        order.sort_by(|&a, &b| amp(a).total_cmp(&amp(b)));
        let mut dropped = vec![false; self.waves.len()];
        let mut delta = 0.0;
        let mut below_grid = 0;
        for (i, w) in self.waves.iter().enumerate() {
            if w.wavelength < min_wavelength {
                dropped[i] = true;
                delta += w.amplitude();
                below_grid += 1;
            }
        }
        for &i in &order {
            if dropped[i] {
                continue;
            }
            if delta + amp(i) > epsilon {
                break;
            }
            dropped[i] = true;
            delta += amp(i);
        }
        self.culled(&dropped, below_grid)
    }

    /// Keep the `max_waves` largest waves (by amplitude; ties keep the earlier wave) and drop
    /// the rest, with the same bounds as [`WaveSet::cull`]: what a renderer that evaluates at
    /// most `max_waves` waves per vertex and frame draws, and how far that is from the sea.
    pub fn keep_largest(&self, max_waves: usize) -> Culled {
        let mut order: Vec<usize> = (0..self.waves.len()).collect();
        // Largest first; a stable sort keeps file order among equal amplitudes.
        order.sort_by(|&a, &b| {
            self.waves[b]
                .amplitude()
                .total_cmp(&self.waves[a].amplitude())
        });
        let mut dropped = vec![false; self.waves.len()];
        for &i in order.iter().skip(max_waves) {
            dropped[i] = true;
        }
        self.culled(&dropped, 0)
    }

    /// The kept waves and the bounds of the `dropped` ones (module docs).
    fn culled(&self, dropped: &[bool], below_grid: usize) -> Culled {
        let kept: Vec<usize> = (0..self.waves.len()).filter(|&i| !dropped[i]).collect();
        let sea = WaveSet {
            gravity: self.gravity,
            depth: self.depth,
            waves: kept.iter().map(|&i| self.waves[i]).collect(),
        };
        let gone = || (0..self.waves.len()).filter(|&i| dropped[i]);
        let delta: f64 = gone().map(|i| self.waves[i].amplitude()).sum();
        let s = sea.total_steepness();
        let lipschitz = s / (1.0 - s);
        Culled {
            height_bound: delta * (1.0 + lipschitz * lipschitz).sqrt(),
            sea,
            kept,
            displacement_bound: delta,
            slope_bound: gone().map(|i| self.waves[i].steepness).sum(),
            below_grid,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_tolerance_keeps_everything_and_huge_drops_everything() {
        let s = WaveSet::default_sea();
        let c = s.cull(0.0, 0.0);
        assert_eq!(c.sea, s);
        assert_eq!(c.displacement_bound, 0.0);
        let all = s.cull(1e9, 0.0);
        assert!(all.sea.waves.is_empty());
        assert!((all.displacement_bound - s.total_amplitude()).abs() < 1e-12);
        assert!((all.slope_bound - s.total_steepness()).abs() < 1e-12);
    }

    /// Keeping the n largest: the kept are exactly the n largest amplitudes, and the bound is
    /// the sum of the rest (computed here independently, in a different order).
    #[test]
    fn keep_largest_keeps_the_largest_and_bounds_the_rest() {
        let s = WaveSet::default_sea();
        let mut amps: Vec<f64> = s.waves.iter().map(|w| w.amplitude()).collect();
        amps.sort_by(f64::total_cmp);
        for n in 0..=s.waves.len() + 1 {
            let c = s.keep_largest(n);
            assert_eq!(c.sea.waves.len(), n.min(s.waves.len()));
            let smallest_kept = c
                .sea
                .waves
                .iter()
                .map(|w| w.amplitude())
                .fold(f64::INFINITY, f64::min);
            let dropped = s.waves.len().saturating_sub(n);
            assert!(amps[..dropped].iter().all(|&a| a <= smallest_kept));
            let rest: f64 = amps[..dropped].iter().rev().sum();
            assert!((c.displacement_bound - rest).abs() < 1e-12, "{n}");
            assert!(c.height_bound >= c.displacement_bound);
        }
        assert_eq!(s.keep_largest(99).sea, s);
    }

    #[test]
    fn short_waves_go_below_the_grid_whatever_epsilon() {
        let s = WaveSet::default_sea();
        // Default sea wavelengths: 60, 31, 18, 11, 6.5, 3.7 m. A 4 m grid keeps λ ≥ 8 m.
        let c = s.cull(0.0, 8.0);
        assert_eq!(c.kept, vec![0, 1, 2, 3]);
        assert_eq!(c.below_grid, 2);
        let expect = s.waves[4].amplitude() + s.waves[5].amplitude();
        assert!((c.displacement_bound - expect).abs() < 1e-12);
    }
}
