//! Tile culling: which tiles and cells of each level survive the view frustum and the play
//! area ([`ClipMapConfig::visit_tiles`]), with the per-level stats of a frame.

use glam::{DVec2, DVec3, I64Vec2};

use super::{ClipMapConfig, TILE_CELLS};
use crate::camera::Frustum;

/// What a frame's culling knows.
#[derive(Debug, Clone, Copy, Default)]
pub struct Culling {
    /// View frustum in the mesh's local coordinates (relative to [`ClipMesh::origin`], which
    /// [`ClipMapConfig::origin_for`] gives before building).
    pub frustum: Option<Frustum>,
    /// Play area in world metres: min x, min z, max x, max z.
    pub play_area: Option<[f64; 4]>,
    /// Largest displacement of the sea in any direction, metres (Σ A).
    pub max_displacement: f64,
}

/// Why a tile or cell is not drawn.
pub(super) enum Outside {
    PlayArea,
    Frustum,
}

/// Tiles and triangles of one level in one frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct LevelStats {
    pub tiles_drawn: u32,
    pub tiles_outside_frustum: u32,
    pub tiles_outside_play_area: u32,
    pub triangles: u64,
}

impl ClipMapConfig {
    /// Cells per side of level `l`'s tiles (its cells' bit set has a bit per cell).
    pub(super) fn tile_cells(&self, l: u32) -> i64 {
        i64::from(TILE_CELLS).min(i64::from(self.cells[l as usize]) / 2)
    }

    /// Level `l`'s lowest lattice index (i, j) for its centre index `centre`: its n × n cells
    /// span indices `min` to `min + n`.
    pub(super) fn lattice_min(&self, l: u32, centre: I64Vec2) -> I64Vec2 {
        centre - I64Vec2::splat(i64::from(self.cells[l as usize]) / 2)
    }

    /// Every tile of every level that survives `culling` for an eye at world (x, z) `eye`:
    /// `visit(level, [i0, i1, j0, j1], cells)` in lattice indices, `cells` having bit
    /// (j − j0) t + (i − i0) set for each cell (i, j) to draw (outside the hole, meeting the
    /// view and the play area). Returns each level's stats.
    pub(super) fn visit_tiles(
        &self,
        eye: DVec2,
        culling: &Culling,
        mut visit: impl FnMut(u32, [i64; 4], u64),
    ) -> Vec<LevelStats> {
        let origin = self.centre_lattice(self.levels() - 1, eye);
        let lift = culling.max_displacement;
        // The play area's bounds in the lattice's frame: with the world bounds, the four axes
        // that separate a turned tile from the area when they do not meet.
        let area_lattice = culling.play_area.map(|[ax, az, bx, bz]| {
            let c = [(ax, az), (ax, bz), (bx, az), (bx, bz)]
                .map(|(x, z)| self.to_lattice(DVec2::new(x, z)));
            c.iter()
                .fold((c[0], c[0]), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
        });
        // The frustum's planes in the lattice's frame (a rotation about y): a tile is then
        // an axis-aligned box there.
        let frustum = culling.frustum.map(|f| Frustum {
            planes: f.planes.map(|p| {
                let n = self.to_lattice(DVec2::new(p.x, p.z));
                glam::DVec4::new(n.x, p.y, n.y, p.w)
            }),
        });
        // Why a box [lo, hi] (lattice coordinates, grown by the sea's largest displacement)
        // is not drawn, if it is not. The caller grows the box by its level's morph first.
        let cull = |lo: DVec2, hi: DVec2| -> Option<Outside> {
            if let (Some([ax, az, bx, bz]), Some((la, lb))) = (culling.play_area, area_lattice) {
                // The box's world bounds (the turned box's).
                let c = [lo, hi, DVec2::new(lo.x, hi.y), DVec2::new(hi.x, lo.y)]
                    .map(|c| self.to_world(c));
                let (b_lo, b_hi) = c
                    .iter()
                    .fold((c[0], c[0]), |(a, b), p| (a.min(*p), b.max(*p)));
                let apart = |lo: DVec2, hi: DVec2, a: DVec2, b: DVec2| {
                    hi.x + lift < a.x || lo.x - lift > b.x || hi.y + lift < a.y || lo.y - lift > b.y
                };
                if apart(b_lo, b_hi, DVec2::new(ax, az), DVec2::new(bx, bz))
                    || apart(lo, hi, la, lb)
                {
                    return Some(Outside::PlayArea);
                }
            }
            if let Some(f) = &frustum {
                let (a, b) = (lo - origin, hi - origin);
                let lo = DVec3::new(a.x - lift, -lift, a.y - lift);
                let hi = DVec3::new(b.x + lift, lift, b.y + lift);
                if !f.intersects_box(lo, hi) {
                    return Some(Outside::Frustum);
                }
            }
            None
        };
        // Is the box wholly inside the frustum and the play area (then every cell is drawn)?
        let inside = |lo: DVec2, hi: DVec2| -> bool {
            let in_area = culling.play_area.is_none_or(|[ax, az, bx, bz]| {
                [lo, hi, DVec2::new(lo.x, hi.y), DVec2::new(hi.x, lo.y)]
                    .iter()
                    .map(|c| self.to_world(*c))
                    .all(|p| p.x >= ax && p.x <= bx && p.y >= az && p.y <= bz)
            });
            let in_frustum = frustum.as_ref().is_none_or(|f| {
                let (a, b) = (lo - origin, hi - origin);
                let (lo, hi) = (
                    DVec3::new(a.x - lift, -lift, a.y - lift),
                    DVec3::new(b.x + lift, lift, b.y + lift),
                );
                f.planes.iter().all(|p| {
                    // The box corner least along the plane's normal.
                    let c = DVec3::new(
                        if p.x >= 0.0 { lo.x } else { hi.x },
                        if p.y >= 0.0 { lo.y } else { hi.y },
                        if p.z >= 0.0 { lo.z } else { hi.z },
                    );
                    p.truncate().dot(c) + p.w >= 0.0
                })
            });
            in_area && in_frustum
        };
        let mut levels = Vec::new();
        for l in 0..self.levels() {
            let n = i64::from(self.cells[l as usize]);
            let t = self.tile_cells(l);
            let s = self.cell(l);
            let ci = self.centre_index(l, eye);
            let hole = self.hole(l, eye);
            let in_hole = |i: i64, j: i64| {
                hole.is_some_and(|(x0, x1, z0, z1)| i >= x0 && i < x1 && j >= z0 && j < z1)
            };
            let mut stats = LevelStats::default();
            // A vertex of a morphing level slides towards the nearest point of the coarser
            // lattice, at most half a coarse cell along each lattice axis: a cell's triangles
            // lie within its box grown by that much. Culling the ungrown box dropped cells
            // whose morphed triangles reached into the view (or the play area) while their
            // drawn neighbours' shared edges slid away from it: a hole in the water at the
            // screen's edge, a few pixels wide, where the finer level's morph band meets it.
            let morph = if l + 1 < self.levels() {
                DVec2::splat(0.5 * self.cell(l + 1))
            } else {
                DVec2::ZERO
            };
            let cull = |lo: DVec2, hi: DVec2| cull(lo - morph, hi + morph);
            let lo = self.lattice_min(l, ci);
            let (lo_i, lo_j) = (lo.x, lo.y);
            let mut tj = 0;
            while tj < n {
                let mut ti = 0;
                while ti < n {
                    let (i0, j0) = (lo_i + ti, lo_j + tj);
                    let (i1, j1) = ((i0 + t).min(lo_i + n), (j0 + t).min(lo_j + n));
                    ti += t;
                    // A tile wholly inside the hole belongs to the finer level.
                    if in_hole(i0, j0) && in_hole(i1 - 1, j1 - 1) {
                        continue;
                    }
                    let w_lo = DVec2::new(i0 as f64 * s, j0 as f64 * s);
                    let w_hi = DVec2::new(i1 as f64 * s, j1 as f64 * s);
                    match cull(w_lo, w_hi) {
                        Some(Outside::PlayArea) => {
                            stats.tiles_outside_play_area += 1;
                            continue;
                        }
                        Some(Outside::Frustum) => {
                            stats.tiles_outside_frustum += 1;
                            continue;
                        }
                        None => {}
                    }
                    stats.tiles_drawn += 1;
                    // A tile on the edge of the view or the play area keeps only its cells
                    // that meet them (bit (j − j0) t + (i − i0)).
                    let whole = inside(w_lo, w_hi);
                    let mut cells = 0u64;
                    for j in j0..j1 {
                        for i in i0..i1 {
                            let lo = DVec2::new(i as f64 * s, j as f64 * s);
                            if !in_hole(i, j) && (whole || cull(lo, lo + DVec2::splat(s)).is_none())
                            {
                                cells |= 1 << ((j - j0) * t + (i - i0));
                            }
                        }
                    }
                    stats.triangles += 2 * u64::from(cells.count_ones());
                    visit(l, [i0, i1, j0, j1], cells);
                }
                tj += t;
            }
            levels.push(stats);
        }
        levels
    }
}
