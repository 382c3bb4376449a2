//! The CPU side of the water's vertex displacement: the height the mesh draws (to measure
//! its error) and, for the tests, a vertex's displacement in f64.

use glam::DVec2;
use ocean::WaveSet;

use super::ClipMapConfig;
#[cfg(test)]
use {super::LevelPlan, super::mesh::ClipVertex, glam::DVec3};

impl ClipMapConfig {
    /// The height that the unmorphed mesh draws at the world rest point `x0` (linear
    /// interpolation over the triangle of the finest level containing it, each vertex
    /// displaced by the waves `kept[level]`), or `None` outside the map. Used to *measure* the
    /// mesh's height error against the analytic sea; the morph band blends this level's
    /// surface with the next coarser one's, each measured here.
    pub(crate) fn interpolated_height(
        &self,
        sea: &WaveSet,
        kept: &[Vec<usize>],
        eye: DVec2,
        x0: DVec2,
        t: f64,
    ) -> Option<f64> {
        let xl = self.to_lattice(x0);
        let l = (0..self.levels()).find(|&l| {
            (xl - self.centre_lattice(l, eye)).abs().max_element() <= self.half_extent(l)
        })?;
        let s = self.cell(l);
        let (fi, fj) = (xl.x / s, xl.y / s);
        let (i, j) = (fi.floor(), fj.floor());
        let (u, v) = (fi - i, fj - j);
        let height = |di: f64, dj: f64| {
            let p = self
                .to_world(DVec2::new((i + di) * s, (j + dj) * s))
                .to_array();
            kept[l as usize]
                .iter()
                .map(|&k| {
                    let w = &sea.waves[k];
                    w.amplitude() * sea.phase_at(w, p, t).sin()
                })
                .sum::<f64>()
        };
        // Quads are split along the (i, j)–(i+1, j+1) diagonal, as `build` emits them.
        Some(if v >= u {
            // Triangle (i,j), (i,j+1), (i+1,j+1).
            height(0.0, 0.0) * (1.0 - v) + height(0.0, 1.0) * (v - u) + height(1.0, 1.0) * u
        } else {
            // Triangle (i,j), (i+1,j+1), (i+1,j).
            height(0.0, 0.0) * (1.0 - u) + height(1.0, 0.0) * (u - v) + height(1.0, 1.0) * v
        })
    }
}

/// The displacement that the water pass's vertex shader gives vertex `v`, evaluated on the CPU
/// in f64 from the sea at race time `t`: the kept waves of `v.level` at weight 1 where the next
/// level keeps them too, `v.fade` where it does not. Used by the tests.
#[cfg(test)]
pub(crate) fn vertex_displacement(
    sea: &WaveSet,
    plan: &[LevelPlan],
    v: &ClipVertex,
    origin: DVec2,
    t: f64,
) -> DVec3 {
    let l = v.level as usize;
    let rest = origin + DVec2::new(f64::from(v.rest[0]), f64::from(v.rest[1]));
    let mut d = DVec3::new(rest.x, 0.0, rest.y);
    for &i in &plan[l].kept {
        let weight = match plan.get(l + 1) {
            Some(next) if !next.kept.contains(&i) => f64::from(v.fade),
            _ => 1.0,
        };
        let w = &sea.waves[i];
        let theta = sea.phase_at(w, [rest.x, rest.y], t);
        let a = w.amplitude() * weight;
        d += DVec3::new(
            w.direction[0] * a * theta.cos(),
            a * theta.sin(),
            w.direction[1] * a * theta.cos(),
        );
    }
    d
}
