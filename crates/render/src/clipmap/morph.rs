//! Level centres on the world-fixed lattice and the CDLOD morph towards the coarser level
//! (see the module doc of `clipmap`).

use glam::{DVec2, I64Vec2};

use super::ClipMapConfig;

impl ClipMapConfig {
    /// Level `l`'s centre in its own lattice indices for an eye at world (x, z) `eye`: the eye
    /// snapped to [`ClipMapConfig::snap`].
    pub(crate) fn centre_index(&self, l: u32, eye: DVec2) -> I64Vec2 {
        (self.to_lattice(eye) / self.snap(l)).round().as_i64vec2() * i64::from(self.ratio.p)
    }

    /// Lattice coordinates of level `l`'s centre for an eye at world (x, z) `eye`.
    pub(crate) fn centre_lattice(&self, l: u32, eye: DVec2) -> DVec2 {
        self.centre_index(l, eye).as_dvec2() * self.cell(l)
    }

    /// World (x, z) centre of level `l` for an eye at world (x, z) `eye`.
    pub fn centre(&self, l: u32, eye: DVec2) -> DVec2 {
        self.to_world(self.centre_lattice(l, eye))
    }

    /// The local origin of the mesh for an eye at world (x, z): the coarsest centre.
    pub(crate) fn origin_for(&self, eye: DVec2) -> DVec2 {
        self.centre(self.levels() - 1, eye)
    }

    /// Level `l − 1`'s square (the hole of level `l`) in level `l`'s lattice indices:
    /// (min i, max i, min j, max j), exclusive of the max.
    pub(super) fn hole(&self, l: u32, eye: DVec2) -> Option<(i64, i64, i64, i64)> {
        if l == 0 {
            return None;
        }
        let (p, q) = (i64::from(self.ratio.p), i64::from(self.ratio.q));
        // Level l−1's centre index k p becomes k q; its half side n/2 cells becomes n q / 2p.
        let c = self.centre_index(l - 1, eye) / p * q;
        let r = i64::from(self.cells[l as usize - 1]) / 2 / p * q;
        Some((c.x - r, c.x + r, c.y - r, c.y + r))
    }

    /// Morph factor in [0, 1] of a lattice vertex of level `l` at Chebyshev distance `d`
    /// *cells* from its level's centre: 0 inside, 1 on the level's border. Integer distances
    /// make the border exactly 1. The coarsest level never morphs.
    pub fn morph(&self, l: u32, d: i64) -> f64 {
        if l + 1 >= self.levels() {
            return 0.0;
        }
        let h = i64::from(self.cells[l as usize] / 2);
        if d >= h {
            return 1.0;
        }
        ((d as f64 / h as f64 - (1.0 - self.morph_band)) / self.morph_band).clamp(0.0, 1.0)
    }

    /// The morphed rest point (lattice coordinates) and fade of lattice vertex (i, j) of level
    /// `l` (at (i s_l, j s_l)) whose level centre has index `c`: it slides towards the
    /// coarser level's lattice point ([`LevelRatio::coarse_index`]) and reaches it on the
    /// border, where the position is the coarse vertex's own, bit for bit.
    pub(crate) fn morphed_vertex(&self, l: u32, i: i64, j: i64, c: I64Vec2) -> (DVec2, f64) {
        let s = self.cell(l);
        let p = DVec2::new(i as f64 * s, j as f64 * s);
        let m = self.morph(l, (i - c.x).abs().max((j - c.y).abs()));
        if m == 0.0 {
            return (p, 1.0);
        }
        let sc = self.cell(l + 1);
        let target = DVec2::new(
            self.ratio.coarse_index(i) as f64 * sc,
            self.ratio.coarse_index(j) as f64 * sc,
        );
        (p * (1.0 - m) + target * m, 1.0 - m)
    }
}
