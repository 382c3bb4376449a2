//! The camera-following clip-map of source 003 (after Asirvatham & Hoppe), sized from a
//! stated screen-space error target instead of a fixed level count and resolution.
//!
//! **Layout.** Level 0 is an n₀ × n₀ grid of square cells of size s₀ around the camera; level
//! L ≥ 1 is an n_L × n_L grid of cells s_L = 2^L s₀ with a hole where level L − 1 lies. The
//! source uses one n for every level; here each level has its own (a multiple of 4, with
//! n_L ≥ n_{L−1}/2 + 2 so the hole fits), because a far level needs finer angular
//! resolution than a near one for the same error in pixels. Level L's
//! centre c_L is the camera's (x, z) snapped to 2 s_L, so every vertex sits on a fixed world
//! lattice (no swimming) and the hole of level L + 1, which lies on the lattice s_{L+1}, is
//! exactly the outline of level L. The mesh is Lagrangian: vertices are rest points that the
//! vertex shader displaces by the sea, so a vertex keeps sampling the same water.
//!
//! **Morphing** (CDLOD, Strugar 2009). Within the outer `morph_band` of a level, vertices with
//! an odd lattice index slide onto their even neighbour, reaching it on the level's border;
//! there the fine level's vertices are the coarse level's. The waves that the coarser level
//! drops fade out over the same band (`fade`), so on the border both levels evaluate the same
//! waves at the same rest points: no cracks and no pops. `morphed_border_coincides` proves it.
//!
//! **Error target.** For a level whose nearest point is d metres from the eye, a pixel spans
//! d·2 tan(fov/2)/H metres. A kept wave y = A sin(k D·x + θ) interpolated linearly over a
//! triangle errs by at most A k² L²/8, where L is the triangle's extent along D (the error is
//! a Jensen gap of a function of D·x with |second derivative| ≤ A k², at most half of that
//! times the variance of D·x over the vertices, ≤ L²/4): L = s for a wave along a grid axis,
//! √2 s along the diagonal ([`extent_along`]). A dropped wave errs by A (ocean's
//! [`WaveSet::cull`]). The error in pixels of a level is
//! largest at its inner edge, so [`ClipMapConfig::for_view`] builds the map greedily: the
//! coarsest s₀ (on a ladder 2^(e + i/8), the cheapest of the eight) that meets the target at
//! the eye's height, then each level
//! just wide enough that the next, twice as coarse, meets it at its inner edge; levels are
//! added until the map reaches the far edge of the play area or of the view.
//!
//! **Culling.** The mesh is built on the CPU each frame in tiles of [`TILE_CELLS`]² cells;
//! a tile whose box (with the sea's largest displacement) is outside the view frustum or the
//! play area is not emitted. The vertex shader evaluates, per level, only the waves kept by
//! ocean's error-bounded culling for that level's resolution and distance.

use glam::{DVec2, DVec3};
use ocean::WaveSet;

use crate::camera::Frustum;

/// Cells per side of a culling tile.
pub const TILE_CELLS: u32 = 8;
/// Most clip-map levels (the frame uniform's wave masks hold 16).
pub const MAX_LEVELS: u32 = 16;
/// Default outer fraction of a level over which vertices morph.
pub const DEFAULT_MORPH_BAND: f64 = 0.2;
/// Most waves a shader evaluates (the frame uniform's wave array).
pub const MAX_WAVES: usize = 64;

/// How much error on screen the mesh may add, and the screen it is measured on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorTarget {
    /// Largest height error of the mesh against the analytic sea, in pixels.
    pub pixels: f64,
    /// How the allowed error grows with distance: at d metres it is
    /// `pixels · max(1, d / GRADED_FROM)^distance_exponent` ([`ErrorTarget::pixels_at`]); 0 is
    /// a uniform target (the renderer's). The bound is more conservative far away (dropped
    /// waves counted at full amplitude, every wave's worst case added), so a graded target
    /// can meet the same *measured* error with fewer far-field triangles (the mesh bench).
    pub distance_exponent: f64,
    /// Viewport height in pixels.
    pub viewport_height: u32,
    /// Vertical field of view, radians.
    pub fov_y: f64,
}

/// Distance from which a graded [`ErrorTarget`] grows, metres.
pub const GRADED_FROM: f64 = 10.0;

impl ErrorTarget {
    /// A target of `pixels` everywhere on a viewport `viewport_height` pixels high with a
    /// vertical field of view `fov_y` radians.
    pub fn uniform(pixels: f64, viewport_height: u32, fov_y: f64) -> ErrorTarget {
        ErrorTarget {
            pixels,
            distance_exponent: 0.0,
            viewport_height,
            fov_y,
        }
    }

    /// Error allowed at distance `d` metres, pixels.
    pub fn pixels_at(&self, d: f64) -> f64 {
        self.pixels * (d / GRADED_FROM).max(1.0).powf(self.distance_exponent)
    }

    /// Metres that one pixel spans at distance `d`.
    pub fn metres_per_pixel(&self, d: f64) -> f64 {
        d * 2.0 * (self.fov_y / 2.0).tan() / f64::from(self.viewport_height)
    }
}

/// The shape of a clip-map.
#[derive(Debug, Clone, PartialEq)]
pub struct ClipMapConfig {
    /// Cells per side of each level (multiples of 4, ≥ 8, n_L ≥ n_{L−1}/2 + 2); 1 to 16
    /// levels.
    pub cells: Vec<u32>,
    /// Cell size of level 0, metres.
    pub base_cell: f64,
    /// Outer fraction of each level over which vertices morph (0 < band ≤ 0.25).
    pub morph_band: f64,
}

/// What one level draws and the error it is allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelPlan {
    /// Cell size, metres.
    pub cell: f64,
    /// Half the side of the level's square, metres.
    pub half_extent: f64,
    /// Nearest distance from the eye to a point of this level, metres (lower bound).
    pub nearest: f64,
    /// Indices (into the sea's waves) that this level's vertices evaluate.
    pub kept: Vec<usize>,
    /// Bound of the height error from waves the level drops, metres.
    pub dropped_bound: f64,
    /// Bound of the linear-interpolation error of the kept waves, metres.
    pub interpolation_bound: f64,
    /// (dropped + interpolation) in pixels at `nearest`.
    pub error_px: f64,
    /// Error the target allows at `nearest`, pixels.
    pub allowed_px: f64,
}

impl ClipMapConfig {
    /// `levels` levels of `cells` cells each (the source's layout).
    pub fn uniform(levels: u32, cells: u32, base_cell: f64) -> ClipMapConfig {
        ClipMapConfig {
            cells: vec![cells; levels as usize],
            base_cell,
            morph_band: DEFAULT_MORPH_BAND,
        }
    }

    /// Number of levels.
    pub fn levels(&self) -> u32 {
        self.cells.len() as u32
    }

    /// Cell size of level `l`, metres.
    pub fn cell(&self, l: u32) -> f64 {
        self.base_cell * f64::from(1u32 << l)
    }

    /// Half the side of level `l`, metres.
    pub fn half_extent(&self, l: u32) -> f64 {
        self.cell(l) * f64::from(self.cells[l as usize] / 2)
    }

    /// Triangles of the whole map without culling: 2n₀² + Σ 2(n_L² − (n_{L−1}/2)²).
    pub fn full_triangles(&self) -> u64 {
        let mut hole = 0;
        let mut t = 0;
        for &n in &self.cells {
            let n = u64::from(n);
            t += 2 * (n * n - hole * hole);
            hole = n / 2;
        }
        t
    }

    /// Each level's cell size, reach, kept waves and error bound for an eye `eye_height`
    /// metres above the sea, under `target`. Kept sets shrink level by level (a coarser level
    /// evaluates a subset of the finer one's waves: the morph needs it).
    pub fn plan(&self, sea: &WaveSet, target: &ErrorTarget, eye_height: f64) -> Vec<LevelPlan> {
        let lift: f64 = sea.waves.iter().map(|w| w.amplitude()).sum();
        let h = (eye_height.abs() - lift).max(0.5);
        let mut out: Vec<LevelPlan> = Vec::new();
        for l in 0..self.levels() {
            let cell = self.cell(l);
            let nearest = if l == 0 {
                h
            } else {
                // The hole is level l−1's square; the eye is within s_l of its centre.
                let r = (self.half_extent(l - 1) - cell).max(0.0);
                (h * h + r * r).sqrt()
            };
            let allowed_px = target.pixels_at(nearest);
            let budget = allowed_px * target.metres_per_pixel(nearest);
            // A wave shorter than π s errs by half its amplitude or more when interpolated
            // (A k² L²/8 with k s ≥ 2, L ≥ s): the level drops it (ocean counts it in the bound).
            let culled = sea.cull(budget * 0.5, std::f64::consts::PI * cell);
            let mut kept = culled.kept;
            if let Some(prev) = out.last() {
                kept.retain(|i| prev.kept.contains(i));
            }
            let dropped_bound: f64 = (0..sea.waves.len())
                .filter(|i| !kept.contains(i))
                .map(|i| sea.waves[i].amplitude())
                .sum();
            let interpolation_bound: f64 = kept
                .iter()
                .map(|&i| {
                    let w = &sea.waves[i];
                    let l = extent_along(w.direction) * cell;
                    w.amplitude() * w.k() * w.k() * l * l / 8.0
                })
                .sum();
            out.push(LevelPlan {
                cell,
                half_extent: self.half_extent(l),
                nearest,
                kept,
                dropped_bound,
                interpolation_bound,
                error_px: (dropped_bound + interpolation_bound) / target.metres_per_pixel(nearest),
                allowed_px,
            });
        }
        out
    }

    /// The map whose error bound stays within `target` at every level with the fewest cells
    /// (greedy, see the module docs), for an eye `eye_height` metres up that must see water out
    /// to `reach` metres. Where the target cannot be met (16 levels, 1024 cells) the map is the
    /// closest one; its plan says what it reaches.
    ///
    /// Cell sizes double level by level, so the base cell fixes every level's cell. A ladder of
    /// powers of two alone would make the far field, where most triangles are, up to 2× too
    /// fine (4× the triangles), so the base cell is chosen on [`BASE_LADDER_STEPS`] ladders
    /// s₀ = 2^(e + i/steps) and the map with the fewest triangles is kept.
    pub fn for_view(
        sea: &WaveSet,
        target: &ErrorTarget,
        eye_height: f64,
        reach: f64,
    ) -> ClipMapConfig {
        (0..BASE_LADDER_STEPS)
            .map(|i| {
                let scale = 2f64.powf(f64::from(i) / f64::from(BASE_LADDER_STEPS));
                Self::for_view_on_ladder(sea, target, eye_height, reach, scale)
            })
            .min_by_key(ClipMapConfig::full_triangles)
            .expect("at least one ladder")
    }

    /// [`ClipMapConfig::for_view`] with the base cell restricted to `scale` · 2^e metres
    /// (`scale` in [1, 2)).
    pub fn for_view_on_ladder(
        sea: &WaveSet,
        target: &ErrorTarget,
        eye_height: f64,
        reach: f64,
        scale: f64,
    ) -> ClipMapConfig {
        const MAX_CELLS: u32 = 1024;
        let meets = |cfg: &ClipMapConfig| {
            let plan = cfg.plan(sea, target, eye_height);
            plan.last().is_none_or(|p| p.error_px <= p.allowed_px)
        };
        // Coarsest base cell on the ladder meeting the target at level 0.
        let mut cfg = ClipMapConfig {
            cells: vec![8],
            base_cell: scale * 2f64.powi(-8),
            morph_band: DEFAULT_MORPH_BAND,
        };
        for e in (-8..=8).rev() {
            let c = ClipMapConfig {
                base_cell: scale * 2f64.powi(e),
                ..cfg.clone()
            };
            if meets(&c) {
                cfg = c;
                break;
            }
        }
        loop {
            let l = cfg.levels() - 1;
            if l + 1 == MAX_LEVELS && cfg.half_extent(l) < reach {
                // Widen the last level to reach the far edge.
                let need = (2.0 * reach / cfg.cell(l)).ceil() as u32;
                cfg.cells[l as usize] = need.next_multiple_of(4);
                return cfg;
            }
            // Widen level l until a level twice as coarse meets the target beyond it.
            loop {
                if cfg.half_extent(l) >= reach {
                    return cfg;
                }
                let mut next = cfg.clone();
                next.cells
                    .push((cfg.cells[l as usize] / 2 + 2).next_multiple_of(4).max(8));
                if meets(&next) || cfg.cells[l as usize] >= MAX_CELLS {
                    cfg = next;
                    break;
                }
                cfg.cells[l as usize] += 4;
            }
        }
    }
}

/// Ladders of base cell sizes that [`ClipMapConfig::for_view`] tries: s₀ = 2^(e + i/steps).
pub const BASE_LADDER_STEPS: u32 = 8;

/// The largest extent, in cells, of one of the mesh's triangles along the unit direction `d`:
/// the triangles are (0,0),(0,1),(1,1) and (0,0),(1,1),(1,0) in cell units. Between 1 (a wave
/// along an axis) and √2 (along the diagonal).
pub fn extent_along(d: [f64; 2]) -> f64 {
    let range = |a: f64, b: f64, c: f64| a.max(b).max(c) - a.min(b).min(c);
    let diag = d[0] + d[1];
    range(0.0, d[1], diag).max(range(0.0, d[0], diag))
}

/// One vertex of the clip-map mesh (16 bytes), as the water pass reads it.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ClipVertex {
    /// Morphed rest point, local metres (world minus the mesh origin).
    pub rest: [f32; 2],
    /// Weight of the waves the next coarser level drops: 1 − morph.
    pub fade: f32,
    /// Level index.
    pub level: u32,
}

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

/// Tiles and triangles of one level in one frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct LevelStats {
    pub tiles_drawn: u32,
    pub tiles_outside_frustum: u32,
    pub tiles_outside_play_area: u32,
    pub triangles: u64,
}

/// The mesh of one frame.
#[derive(Debug, Clone, Default)]
pub struct ClipMesh {
    /// World (x, z) of the local origin: the coarsest level's snapped centre.
    pub origin: DVec2,
    pub vertices: Vec<ClipVertex>,
    pub indices: Vec<u32>,
    pub levels: Vec<LevelStats>,
}

impl ClipMesh {
    pub fn triangles(&self) -> u64 {
        (self.indices.len() / 3) as u64
    }
}

impl ClipMapConfig {
    /// World (x, z) centre of level `l` for an eye at world (x, z) `eye`: snapped to 2 s_l.
    pub fn centre(&self, l: u32, eye: DVec2) -> DVec2 {
        let snap = 2.0 * self.cell(l);
        (eye / snap).round() * snap
    }

    /// The local origin of the mesh for an eye at world (x, z): the coarsest centre.
    pub fn origin_for(&self, eye: DVec2) -> DVec2 {
        self.centre(self.levels() - 1, eye)
    }

    /// Morph factor in [0, 1] of a rest point at Chebyshev distance `d` from its level's
    /// centre: 0 inside, 1 on the level's border. The coarsest level never morphs.
    pub fn morph(&self, l: u32, d: f64) -> f64 {
        if l + 1 >= self.levels() {
            return 0.0;
        }
        let h = self.half_extent(l);
        if d >= h {
            // Exactly 1 on the border (the formula below may round to 1 − ε).
            return 1.0;
        }
        ((d / h - (1.0 - self.morph_band)) / self.morph_band).clamp(0.0, 1.0)
    }

    /// The morphed world rest point and fade of lattice vertex (i, j) of level `l` (world
    /// position (i s_l, j s_l)) whose level centre is `c`.
    pub fn morphed_vertex(&self, l: u32, i: i64, j: i64, c: DVec2) -> (DVec2, f64) {
        let s = self.cell(l);
        let p = DVec2::new(i as f64 * s, j as f64 * s);
        let d = (p - c).abs().max_element();
        let m = self.morph(l, d);
        // Odd lattice indices slide onto their lower even neighbour.
        let shift = DVec2::new(
            if i.rem_euclid(2) == 1 { s * m } else { 0.0 },
            if j.rem_euclid(2) == 1 { s * m } else { 0.0 },
        );
        (p - shift, 1.0 - m)
    }

    /// Build the mesh for an eye at world (x, z) = `eye`, emitting only the tiles that survive
    /// `culling`.
    pub fn build(&self, eye: DVec2, culling: &Culling) -> ClipMesh {
        let origin = self.origin_for(eye);
        let mut mesh = ClipMesh {
            origin,
            ..Default::default()
        };
        let lift = culling.max_displacement;
        for l in 0..self.levels() {
            let n = i64::from(self.cells[l as usize]);
            let t = i64::from(TILE_CELLS).min(n / 2);
            let s = self.cell(l);
            let c = self.centre(l, eye);
            let ci = (c / s).round().as_i64vec2();
            // Hole: level l−1's square, in level-l lattice indices.
            let hole = (l > 0).then(|| {
                let cp = (self.centre(l - 1, eye) / s).round().as_i64vec2();
                let r = i64::from(self.cells[l as usize - 1]) / 4;
                (cp.x - r, cp.x + r, cp.y - r, cp.y + r)
            });
            let in_hole = |i: i64, j: i64| {
                hole.is_some_and(|(x0, x1, z0, z1)| i >= x0 && i < x1 && j >= z0 && j < z1)
            };
            let mut stats = LevelStats::default();
            let (lo_i, lo_j) = (ci.x - n / 2, ci.y - n / 2);
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
                    if let Some([ax, az, bx, bz]) = culling.play_area
                        && (w_hi.x + lift < ax
                            || w_lo.x - lift > bx
                            || w_hi.y + lift < az
                            || w_lo.y - lift > bz)
                    {
                        stats.tiles_outside_play_area += 1;
                        continue;
                    }
                    if let Some(f) = &culling.frustum {
                        let (a, b) = (w_lo - origin, w_hi - origin);
                        let lo = DVec3::new(a.x - lift, -lift, a.y - lift);
                        let hi = DVec3::new(b.x + lift, lift, b.y + lift);
                        if !f.intersects_box(lo, hi) {
                            stats.tiles_outside_frustum += 1;
                            continue;
                        }
                    }
                    stats.tiles_drawn += 1;
                    let base = mesh.vertices.len() as u32;
                    let wi = (i1 - i0 + 1) as u32;
                    for j in j0..=j1 {
                        for i in i0..=i1 {
                            let (p, fade) = self.morphed_vertex(l, i, j, c);
                            let q = p - origin;
                            mesh.vertices.push(ClipVertex {
                                rest: [q.x as f32, q.y as f32],
                                fade: fade as f32,
                                level: l,
                            });
                        }
                    }
                    for j in j0..j1 {
                        for i in i0..i1 {
                            if in_hole(i, j) {
                                continue;
                            }
                            let a = base + ((j - j0) as u32) * wi + (i - i0) as u32;
                            let (b, d, e) = (a + 1, a + wi, a + wi + 1);
                            // Every quad split along the same diagonal, at every level, so a
                            // fully morphed fine quad matches the coarse triangulation.
                            mesh.indices.extend_from_slice(&[a, d, e, a, e, b]);
                            stats.triangles += 2;
                        }
                    }
                }
                tj += t;
            }
            mesh.levels.push(stats);
        }
        mesh
    }
}

impl ClipMapConfig {
    /// The height that the unmorphed mesh draws at the world rest point `x0` (linear
    /// interpolation over the triangle of the finest level containing it, each vertex
    /// displaced by the waves `kept[level]`), or `None` outside the map. Used to *measure* the
    /// mesh's height error against the analytic sea; the morph band blends this level's
    /// surface with the next coarser one's, each measured here.
    pub fn interpolated_height(
        &self,
        sea: &WaveSet,
        kept: &[Vec<usize>],
        eye: DVec2,
        x0: DVec2,
        t: f64,
    ) -> Option<f64> {
        let l = (0..self.levels())
            .find(|&l| (x0 - self.centre(l, eye)).abs().max_element() <= self.half_extent(l))?;
        let s = self.cell(l);
        let (fi, fj) = (x0.x / s, x0.y / s);
        let (i, j) = (fi.floor(), fj.floor());
        let (u, v) = (fi - i, fj - j);
        let height = |di: f64, dj: f64| {
            let p = [(i + di) * s, (j + dj) * s];
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
/// level keeps them too, `v.fade` where it does not. Used by tests and the mesh bench.
pub fn vertex_displacement(
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

#[cfg(test)]
mod tests {
    use super::*;

    fn config() -> ClipMapConfig {
        ClipMapConfig {
            cells: vec![32, 24, 20, 32],
            base_cell: 0.5,
            morph_band: DEFAULT_MORPH_BAND,
        }
    }

    #[test]
    fn unculled_mesh_has_the_closed_form_triangle_count() {
        let c = config();
        for eye in [
            DVec2::ZERO,
            DVec2::new(3.3, -7.9),
            DVec2::new(-1234.6, 987.2),
        ] {
            let m = c.build(eye, &Culling::default());
            assert_eq!(m.triangles(), c.full_triangles(), "eye {eye}");
        }
    }

    #[test]
    fn levels_tile_the_plane_without_overlap_or_gap() {
        // Every point of the outermost square is covered by exactly one triangle's cell.
        let c = config();
        let m = c.build(DVec2::new(5.7, -2.2), &Culling::default());
        let area: f64 = m
            .indices
            .chunks(3)
            .map(|t| {
                // Unmorphed area: use cell size of the level.
                let s = c.cell(m.vertices[t[0] as usize].level);
                s * s / 2.0
            })
            .sum();
        let side = 2.0 * c.half_extent(c.levels() - 1);
        assert!(
            (area - side * side).abs() < 1e-6,
            "{area} vs {}",
            side * side
        );
    }

    #[test]
    fn morphed_border_coincides() {
        // After morphing, every vertex on the outer border of level L is displaced to exactly
        // where a vertex of level L + 1 is: same rest point, same evaluated waves.
        let sea = WaveSet::default_sea();
        let c = config();
        let target = ErrorTarget::uniform(0.5, 720, 1.0);
        let plan = c.plan(&sea, &target, 8.0);
        assert!(
            plan.windows(2).any(|p| p[1].kept.len() < p[0].kept.len()),
            "the test needs a level that drops waves"
        );
        let eye = DVec2::new(13.2, -4.9);
        let m = c.build(eye, &Culling::default());
        let t = 1234.5;
        let mut checked = 0;
        for l in 0..c.levels() - 1 {
            let centre = c.centre(l, eye);
            let h = c.half_extent(l);
            let coarse: Vec<DVec3> = m
                .vertices
                .iter()
                .filter(|v| v.level == l + 1)
                .map(|v| vertex_displacement(&sea, &plan, v, m.origin, t))
                .collect();
            for v in m.vertices.iter().filter(|v| v.level == l) {
                let p = m.origin + DVec2::new(f64::from(v.rest[0]), f64::from(v.rest[1]));
                if ((p - centre).abs().max_element() - h).abs() > 1e-6 {
                    continue;
                }
                assert_eq!(v.fade, 0.0, "border vertex of level {l} not fully morphed");
                let d = vertex_displacement(&sea, &plan, v, m.origin, t);
                let nearest = coarse
                    .iter()
                    .map(|q| (*q - d).length())
                    .fold(f64::MAX, f64::min);
                assert!(
                    nearest < 1e-9,
                    "level {l} border vertex {p} is {nearest} m off"
                );
                checked += 1;
            }
        }
        assert!(checked > 100, "only {checked} border vertices checked");
    }

    #[test]
    fn unmorphed_fine_border_would_crack() {
        // Without the morph an odd border vertex of level 0 evaluates all of level 0's waves
        // at its own rest point: it lands metres away from any level-1 vertex. So the test
        // above can fail.
        let sea = WaveSet::default_sea();
        let c = config();
        let target = ErrorTarget::uniform(0.5, 720, 1.0);
        let plan = c.plan(&sea, &target, 8.0);
        let (eye, t) = (DVec2::ZERO, 1234.5);
        let m = c.build(eye, &Culling::default());
        let h = c.half_extent(0);
        let raw = ClipVertex {
            rest: [(0.5 - m.origin.x) as f32, (h - m.origin.y) as f32],
            fade: 1.0,
            level: 0,
        };
        let d = vertex_displacement(&sea, &plan, &raw, m.origin, t);
        let nearest = m
            .vertices
            .iter()
            .filter(|v| v.level == 1)
            .map(|v| (vertex_displacement(&sea, &plan, v, m.origin, t) - d).length())
            .fold(f64::MAX, f64::min);
        assert!(nearest > 1e-3, "{nearest}");
        // Interior vertices never move; border ones slide onto their even neighbour.
        assert_eq!(c.morphed_vertex(0, 1, 0, eye).0, DVec2::new(0.5, 0.0));
        assert_eq!(c.morphed_vertex(0, 1, 16, eye).0, DVec2::new(0.0, 8.0));
    }

    #[test]
    fn tiles_outside_play_area_and_frustum_are_culled() {
        use crate::camera::Camera;
        let c = config();
        let eye = DVec2::new(0.0, 0.0);
        let origin = c.origin_for(eye);
        let cam = Camera::look_at(DVec3::new(0.0, 5.0, 0.0), DVec3::new(0.0, 0.0, -40.0), 1e3);
        let f = Frustum::from_matrix(cam.view_proj_local(origin, 1.5));
        let culled = c.build(
            eye,
            &Culling {
                frustum: Some(f),
                play_area: Some([-1e4, -1e4, 1e4, 1e4]),
                max_displacement: 1.0,
            },
        );
        let full = c.full_triangles();
        assert!(
            culled.triangles() < full / 2,
            "{} of {full}",
            culled.triangles()
        );
        assert!(culled.levels.iter().any(|l| l.tiles_outside_frustum > 0));
        // Every triangle behind the eye is gone: none lies wholly at z > 1 + tile.
        let small = c.build(
            eye,
            &Culling {
                frustum: None,
                play_area: Some([-3.0, -3.0, 3.0, 3.0]),
                max_displacement: 0.0,
            },
        );
        assert!(small.levels.iter().any(|l| l.tiles_outside_play_area > 0));
        for v in &small.vertices {
            let p = origin + DVec2::new(f64::from(v.rest[0]), f64::from(v.rest[1]));
            // Tiles touching the area are kept whole: at most one tile beyond it.
            let slack = 3.0 + c.cell(v.level) * f64::from(TILE_CELLS);
            assert!(p.x.abs() <= slack && p.y.abs() <= slack, "{p}");
        }
    }

    #[test]
    fn interpolated_height_is_exact_at_vertices_and_bounded_between() {
        let sea = WaveSet::default_sea();
        let c = config();
        let all: Vec<Vec<usize>> = vec![(0..sea.waves.len()).collect(); c.levels() as usize];
        let (eye, t) = (DVec2::new(0.3, 0.2), 77.0);
        // On a lattice vertex of level 0 the mesh height is the sea's height at that rest point.
        let v = DVec2::new(1.5, -2.0);
        let h = c.interpolated_height(&sea, &all, eye, v, t).unwrap();
        assert!((h - sea.displace([v.x, v.y], t)[1]).abs() < 1e-12);
        // Between vertices the error stays within the stated bound Σ A k² L²/8.
        let s = c.cell(0);
        let bound: f64 = sea
            .waves
            .iter()
            .map(|w| {
                let l = extent_along(w.direction) * s;
                w.amplitude() * w.k() * w.k() * l * l / 8.0
            })
            .sum();
        let mut worst: f64 = 0.0;
        for k in 0..2000 {
            let p = DVec2::new(-3.0 + 0.00317 * f64::from(k), 2.9 - 0.00291 * f64::from(k));
            let h = c.interpolated_height(&sea, &all, eye, p, t).unwrap();
            let e = (h - sea.displace([p.x, p.y], t)[1]).abs();
            assert!(e <= bound, "{p}: {e} > {bound}");
            worst = worst.max(e);
        }
        // And it is not vacuous: the worst error seen is a good part of it.
        assert!(worst > 0.1 * bound, "{worst} vs {bound}");
        // Outside the map there is no mesh.
        let far = DVec2::new(1e4, 0.0);
        assert!(c.interpolated_height(&sea, &all, eye, far, t).is_none());
    }

    #[test]
    fn the_extent_bound_is_sharp_for_one_wave_along_each_axis_and_the_diagonal() {
        assert!((extent_along([1.0, 0.0]) - 1.0).abs() < 1e-15);
        assert!((extent_along([0.0, -1.0]) - 1.0).abs() < 1e-15);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((extent_along([h, h]) - 2f64.sqrt()).abs() < 1e-15);
        // A wave along x sampled at s with a crest midway between vertices: the linear
        // interpolation misses it by exactly A(1 − cos(ks/2)) ≈ A k² s²/8.
        let (a, k, s): (f64, f64, f64) = (0.5, 0.4, 0.25);
        let exact = a * (1.0 - (k * s / 2.0).cos());
        let bound = a * k * k * (extent_along([1.0, 0.0]) * s).powi(2) / 8.0;
        assert!(exact <= bound && exact > 0.99 * bound, "{exact} vs {bound}");
    }

    #[test]
    fn graded_target_allows_more_far_away_and_costs_fewer_cells() {
        let sea = WaveSet::default_sea();
        let uniform = ErrorTarget::uniform(0.5, 720, 55f64.to_radians());
        let graded = ErrorTarget {
            distance_exponent: 0.5,
            ..uniform
        };
        // Closed form: pixels · max(1, d / 10 m)^γ.
        assert_eq!(graded.pixels_at(4.0), 0.5);
        assert!((graded.pixels_at(1000.0) - 5.0).abs() < 1e-12);
        assert_eq!(uniform.pixels_at(1000.0), 0.5);
        let c = ClipMapConfig::for_view(&sea, &graded, 12.0, 1000.0);
        assert!(c.half_extent(c.levels() - 1) >= 1000.0);
        for (l, p) in c.plan(&sea, &graded, 12.0).iter().enumerate() {
            let allowed = 0.5 * (p.nearest / GRADED_FROM).max(1.0).sqrt();
            assert!((p.allowed_px - allowed).abs() < 1e-12, "level {l}");
            assert!(
                p.error_px <= allowed,
                "level {l}: {} > {allowed} px",
                p.error_px
            );
        }
        let u = ClipMapConfig::for_view(&sea, &uniform, 12.0, 1000.0);
        assert!(
            c.full_triangles() < u.full_triangles(),
            "{} vs {}",
            c.full_triangles(),
            u.full_triangles()
        );
    }

    #[test]
    fn finer_base_ladders_are_never_worse_than_powers_of_two() {
        let sea = WaveSet::default_sea();
        for px in [0.5, 1.0, 3.0] {
            let target = ErrorTarget::uniform(px, 720, 55f64.to_radians());
            let best = ClipMapConfig::for_view(&sea, &target, 12.0, 1000.0);
            let pow2 = ClipMapConfig::for_view_on_ladder(&sea, &target, 12.0, 1000.0, 1.0);
            assert!(best.full_triangles() <= pow2.full_triangles(), "{px} px");
            for p in best.plan(&sea, &target, 12.0) {
                assert!(p.error_px <= px, "{px} px: {}", p.error_px);
            }
        }
    }

    #[test]
    fn chosen_config_meets_its_error_target() {
        let sea = WaveSet::default_sea();
        let target = ErrorTarget::uniform(2.0, 720, 55f64.to_radians());
        let c = ClipMapConfig::for_view(&sea, &target, 12.0, 1000.0);
        let plan = c.plan(&sea, &target, 12.0);
        assert!(c.half_extent(c.levels() - 1) >= 1000.0);
        for (l, p) in plan.iter().enumerate() {
            assert!(p.error_px <= 2.0, "level {l}: {} px", p.error_px);
        }
        // Coarser levels evaluate a subset of the finer one's waves.
        for w in plan.windows(2) {
            assert!(w[1].kept.iter().all(|i| w[0].kept.contains(i)));
        }
    }
}
