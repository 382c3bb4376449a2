//! The camera-following clip-map of source 003 (after Asirvatham & Hoppe), sized from a
//! stated screen-space error target instead of a fixed level count and resolution.
//!
//! **Layout.** Level 0 is an n₀ × n₀ grid of square cells of size s₀ around the camera; level
//! L ≥ 1 is an n_L × n_L grid of cells s_L = (p/q)^L s₀ with a hole where level L − 1 lies.
//! The source uses one n for every level and doubles the cell (p/q = 2); here each level has
//! its own n (a far level needs finer angular resolution than a near one for the same error
//! in pixels) and the ratio is one of [`LEVEL_RATIOS`] (2, 3/2, 4/3, 5/4): a level's cell is
//! fixed while the error it may make grows with distance, so a ratio r leaves a level up to r²
//! too fine at its outer edge, and a smaller r wastes less. Level L's centre c_L is the eye
//! snapped to p s_L = q s_{L+1}, the shortest length on both lattices, and n_L is a multiple
//! of 2p, so level L's border lies on level L + 1's lattice and the hole of L + 1 is exactly
//! level L's outline; every vertex sits on a lattice fixed in the world (no swimming). The
//! lattice is turned by [`ClipMapConfig::angle`] ([`lattice_angle`]): cells are split along
//! one diagonal, and a wave along it errs twice as much as one across it, so the lattice
//! turns that diagonal across the sea's short waves (for the default sea, by 53°, this cuts
//! the interpolation bound Σ A k² L²/8 by 43 %). The mesh is Lagrangian: vertices
//! are rest points that the vertex shader displaces by the sea, so a vertex keeps sampling the
//! same water.
//!
//! **Morphing** (CDLOD, Strugar 2009). Within the outer `morph_band` of a level, every vertex
//! slides towards the nearest point of the coarser lattice ([`LevelRatio::coarse_index`]:
//! monotone and onto), reaching it on the level's border; there the fine level's vertices are
//! the coarse level's, bit for bit, and every coarse border vertex is met (no T-junction). The
//! waves that the coarser level drops fade out over the same band (`fade`), so on the border
//! both levels evaluate the same waves at the same rest points: no cracks and no pops. Level
//! L's square, at the largest centre offset, stays inside level L + 1's unmorphed part
//! ([`ClipMapConfig::nests`]). `morphed_border_coincides` proves it for every ratio.
//!
//! **Error target.** For a level whose nearest point is d metres from the eye, a pixel spans
//! d·2 tan(fov/2)/H metres. A kept wave y = A sin(k D·x + θ) interpolated linearly over a
//! triangle errs by at most A k² L²/8, where L is the triangle's extent along D (the error is
//! a Jensen gap of a function of D·x with |second derivative| ≤ A k², at most half of that
//! times the variance of D·x over the vertices, ≤ L²/4): L = s/√2 across the split diagonal,
//! s along a lattice axis, √2 s along the diagonal ([`extent_along`]). A dropped wave errs by A
//! (ocean's [`WaveSet::cull`]). The error in pixels of a level is largest where its lattice
//! first shows: where the finer level starts to morph into it. [`ClipMapConfig::for_view`]
//! builds the map greedily: the coarsest s₀ (on a ladder 2^(e + i/8)) that meets the target at
//! the eye's height, then each level just wide enough that the next, p/q times coarser, meets
//! it there; levels are added until the map covers the play area or the view (a turned square
//! needs a half side (|cos| + |sin|) times the world-axis reach). Of every ratio and ladder it
//! keeps the map with the fewest triangles.
//!
//! **Culling.** The mesh is built on the CPU each frame in tiles of [`TILE_CELLS`]² cells;
//! a tile whose box (with the sea's largest displacement) is outside the view frustum or the
//! play area is not emitted, and a tile on their edge emits only its cells that meet them.
//! The vertex shader evaluates, per level, only the waves kept by ocean's error-bounded
//! culling for that level's resolution and distance.

use glam::{DVec2, DVec3, I64Vec2};
use ocean::WaveSet;

use crate::camera::Frustum;

/// Cells per side of a culling tile.
pub(crate) const TILE_CELLS: u32 = 8;
/// Most clip-map levels (the frame uniform's wave masks hold 16).
pub(crate) const MAX_LEVELS: u32 = 16;
/// Default outer fraction of a level over which vertices morph.
pub(crate) const DEFAULT_MORPH_BAND: f64 = 0.2;
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
    pub(crate) fn pixels_at(&self, d: f64) -> f64 {
        self.pixels * (d / GRADED_FROM).max(1.0).powf(self.distance_exponent)
    }

    /// Metres that one pixel spans at distance `d`.
    pub(crate) fn metres_per_pixel(&self, d: f64) -> f64 {
        d * 2.0 * (self.fov_y / 2.0).tan() / f64::from(self.viewport_height)
    }
}

/// The ratio p/q (in lowest terms, 1 < p/q ≤ 2) of the cell sizes of consecutive levels:
/// s_{L+1} = (p/q) s_L. Doubling (2/1) is the classic clip-map; a smaller ratio lets each
/// level's cell follow the error target more closely (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LevelRatio {
    pub p: u32,
    pub q: u32,
}

impl LevelRatio {
    /// The classic clip-map's doubling.
    pub(crate) const DOUBLING: LevelRatio = LevelRatio { p: 2, q: 1 };

    /// p/q.
    pub fn value(self) -> f64 {
        f64::from(self.p) / f64::from(self.q)
    }

    /// The index on the coarser level's lattice that fine lattice index `i` morphs onto: the
    /// nearest (fine point i s lies at i q/p coarse cells), ties to the lower one. Monotone
    /// and onto (a coarse cell is p/q ≥ 1 fine cells wide), exact on the shared lattice
    /// (i a multiple of p maps to i q/p).
    pub(crate) fn coarse_index(self, i: i64) -> i64 {
        let (p, q) = (i64::from(self.p), i64::from(self.q));
        (2 * i * q + p - 1).div_euclid(2 * p)
    }
}

/// The level ratios [`ClipMapConfig::for_view`] tries.
pub const LEVEL_RATIOS: [LevelRatio; 4] = [
    LevelRatio::DOUBLING,
    LevelRatio { p: 3, q: 2 },
    LevelRatio { p: 4, q: 3 },
    LevelRatio { p: 5, q: 4 },
];

/// The shape of a clip-map.
#[derive(Debug, Clone, PartialEq)]
pub struct ClipMapConfig {
    /// Cells per side of each level (multiples of 2p, ≥ 8; level L's square, with the largest
    /// snapping offset, lies inside level L + 1's unmorphed part); 1 to 16 levels.
    pub cells: Vec<u32>,
    /// Cell size of level 0, metres.
    pub base_cell: f64,
    /// Cell-size ratio of consecutive levels.
    pub ratio: LevelRatio,
    /// Orientation of the lattice: its i axis lies `angle` radians from world x towards z
    /// (fixed per sea, so the lattice stays fixed in the world). Cells are split along the
    /// lattice's (i, j)–(i+1, j+1) diagonal.
    pub angle: f64,
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
    /// Nearest distance from the eye to a point where this level's lattice shows (its own
    /// square or the finer level's morph band), metres (lower bound).
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
    /// `levels` levels of `cells` cells each, doubling (the source's layout).
    pub fn uniform(levels: u32, cells: u32, base_cell: f64) -> ClipMapConfig {
        ClipMapConfig {
            cells: vec![cells; levels as usize],
            base_cell,
            ratio: LevelRatio::DOUBLING,
            angle: 0.0,
            morph_band: DEFAULT_MORPH_BAND,
        }
    }

    /// World (x, z) `w` in lattice coordinates (rotated by −angle).
    pub(crate) fn to_lattice(&self, w: DVec2) -> DVec2 {
        let (s, c) = self.angle.sin_cos();
        DVec2::new(c * w.x + s * w.y, c * w.y - s * w.x)
    }

    /// Lattice coordinates `a` in world (x, z) (rotated by angle).
    pub(crate) fn to_world(&self, a: DVec2) -> DVec2 {
        let (s, c) = self.angle.sin_cos();
        DVec2::new(c * a.x - s * a.y, s * a.x + c * a.y)
    }

    /// Number of levels.
    pub fn levels(&self) -> u32 {
        self.cells.len() as u32
    }

    /// Cell size of level `l`, metres: s₀ (p/q)^l.
    pub fn cell(&self, l: u32) -> f64 {
        let l = l as i32;
        self.base_cell * f64::from(self.ratio.p).powi(l) / f64::from(self.ratio.q).powi(l)
    }

    /// Half the side of level `l`, metres.
    pub fn half_extent(&self, l: u32) -> f64 {
        self.cell(l) * f64::from(self.cells[l as usize] / 2)
    }

    /// Grid to which level `l`'s centre snaps, metres: p s_l, the smallest length on both
    /// level l's lattice and level l + 1's (q s_{l+1}), so the level's border (its half side
    /// is a multiple of it) lies on the coarser lattice.
    pub(crate) fn snap(&self, l: u32) -> f64 {
        f64::from(self.ratio.p) * self.cell(l)
    }

    /// Largest offset, per axis, between the centres of levels `l` and `l + 1`, metres: each
    /// lies within half its snapping grid of the eye.
    fn max_centre_offset(&self, l: u32) -> f64 {
        0.5 * (self.snap(l) + self.snap(l + 1))
    }

    /// Triangles of the whole map without culling: 2n₀² + Σ 2(n_L² − (n_{L−1} q/p)²).
    pub(crate) fn full_triangles(&self) -> u64 {
        let (p, q) = (u64::from(self.ratio.p), u64::from(self.ratio.q));
        let mut hole = 0;
        let mut t = 0;
        for &n in &self.cells {
            let n = u64::from(n);
            t += 2 * (n * n - hole * hole);
            hole = n * q / p;
        }
        t
    }

    /// Does level `l`'s square, wherever the eye puts the centres, lie inside level `l + 1`
    /// (inside its unmorphed part unless `l + 1` is the last level, which does not morph)?
    /// This keeps the coarse vertices that the finer border meets at rest (no cracks).
    pub(crate) fn nests(&self, l: u32) -> bool {
        let inner = self.half_extent(l) + self.max_centre_offset(l);
        let outer = self.half_extent(l + 1);
        if l + 2 >= self.levels() {
            inner <= outer
        } else {
            inner <= (1.0 - self.morph_band) * outer
        }
    }

    /// Each level's cell size, reach, kept waves and error bound for an eye `eye_height`
    /// metres above the sea, under `target`. Kept sets shrink level by level (a coarser level
    /// evaluates a subset of the finer one's waves: the morph needs it).
    pub fn plan(&self, sea: &WaveSet, target: &ErrorTarget, eye_height: f64) -> Vec<LevelPlan> {
        let mut out: Vec<LevelPlan> = Vec::new();
        for l in 0..self.levels() {
            let level = self.plan_level(sea, target, eye_height, l, out.last());
            out.push(level);
        }
        out
    }

    /// Level `l` of [`ClipMapConfig::plan`], given level `l − 1`'s plan `finer`.
    fn plan_level(
        &self,
        sea: &WaveSet,
        target: &ErrorTarget,
        eye_height: f64,
        l: u32,
        finer: Option<&LevelPlan>,
    ) -> LevelPlan {
        let lift: f64 = sea.waves.iter().map(|w| w.amplitude()).sum();
        let h = (eye_height.abs() - lift).max(0.5);
        let cell = self.cell(l);
        let nearest = if l == 0 {
            h
        } else {
            // Level l's lattice shows from where level l−1 starts to morph into it, at
            // (1 − band) of l−1's half side from l−1's centre; the eye is within half a
            // snapping grid of that centre.
            let r = ((1.0 - self.morph_band) * self.half_extent(l - 1) - 0.5 * self.snap(l - 1))
                .max(0.0);
            (h * h + r * r).sqrt()
        };
        let allowed_px = target.pixels_at(nearest);
        let budget = allowed_px * target.metres_per_pixel(nearest);
        // A wave shorter than π s errs by half its amplitude or more when interpolated
        // (A k² L²/8 with k s ≥ 2, L ≥ s): the level drops it (ocean counts it in the bound).
        let culled = sea.cull(budget * 0.5, std::f64::consts::PI * cell);
        let mut kept = culled.kept;
        if let Some(prev) = finer {
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
                let d = self.to_lattice(DVec2::from(w.direction));
                let l = extent_along([d.x, d.y]) * cell;
                w.amplitude() * w.k() * w.k() * l * l / 8.0
            })
            .sum();
        LevelPlan {
            cell,
            half_extent: self.half_extent(l),
            nearest,
            kept,
            dropped_bound,
            interpolation_bound,
            error_px: (dropped_bound + interpolation_bound) / target.metres_per_pixel(nearest),
            allowed_px,
        }
    }

    /// The map whose error bound stays within `target` at every level with the fewest cells
    /// (greedy, see the module docs), for an eye `eye_height` metres up that must see water out
    /// to `reach` metres. Where the target cannot be met (16 levels, 1024 cells) the map is the
    /// closest one; its plan says what it reaches.
    ///
    /// A level's cell is fixed across a level whose error allowance in metres grows with
    /// distance, so a ratio r between levels leaves each level up to r² finer than needed at
    /// its outer edge: the map is built for every ratio of [`LEVEL_RATIOS`] and, as a ladder of
    /// powers alone would leave the far field up to r× too fine, every base cell ladder
    /// s₀ = 2^(e + i/[`BASE_LADDER_STEPS`]); the map with the fewest triangles is kept.
    pub fn for_view(
        sea: &WaveSet,
        target: &ErrorTarget,
        eye_height: f64,
        reach: f64,
    ) -> ClipMapConfig {
        let angle = lattice_angle(sea);
        LEVEL_RATIOS
            .iter()
            .flat_map(|&ratio| {
                (0..BASE_LADDER_STEPS).map(move |i| {
                    let scale = 2f64.powf(f64::from(i) / f64::from(BASE_LADDER_STEPS));
                    Self::greedy(sea, target, eye_height, reach, ratio, scale, angle)
                })
            })
            .min_by_key(ClipMapConfig::full_triangles)
            .expect("at least one ladder")
    }

    /// [`ClipMapConfig::for_view`] with levels `ratio` apart and the base cell restricted to
    /// `scale` · 2^e metres (`scale` in [1, 2)).
    pub fn for_view_on_ladder(
        sea: &WaveSet,
        target: &ErrorTarget,
        eye_height: f64,
        reach: f64,
        ratio: LevelRatio,
        scale: f64,
    ) -> ClipMapConfig {
        let angle = lattice_angle(sea);
        Self::greedy(sea, target, eye_height, reach, ratio, scale, angle)
    }

    /// The greedy construction of the module docs on a lattice turned by `angle`.
    fn greedy(
        sea: &WaveSet,
        target: &ErrorTarget,
        eye_height: f64,
        reach: f64,
        ratio: LevelRatio,
        scale: f64,
        angle: f64,
    ) -> ClipMapConfig {
        const MAX_CELLS: u32 = 1024;
        let step = 2 * ratio.p;
        // `reach` is a half side along the world's axes: a square turned by `angle` covers
        // that square at a half side (|cos| + |sin|) times larger, plus the last level's
        // snapping offset (added below).
        let reach = reach * (angle.cos().abs() + angle.sin().abs());
        // Level l's plan depends on the levels inside it only: plan the candidate level alone.
        let level = |cfg: &ClipMapConfig, l: u32, finer: Option<&LevelPlan>| {
            cfg.plan_level(sea, target, eye_height, l, finer)
        };
        let meets = |p: &LevelPlan| p.error_px <= p.allowed_px;
        // Coarsest base cell on the ladder meeting the target at level 0.
        let mut cfg = ClipMapConfig {
            cells: vec![8u32.next_multiple_of(step)],
            base_cell: scale * 2f64.powi(-8),
            ratio,
            angle,
            morph_band: DEFAULT_MORPH_BAND,
        };
        for e in (-8..=8).rev() {
            let c = ClipMapConfig {
                base_cell: scale * 2f64.powi(e),
                ..cfg.clone()
            };
            if meets(&level(&c, 0, None)) {
                cfg = c;
                break;
            }
        }
        let mut plans = vec![level(&cfg, 0, None)];
        loop {
            let l = cfg.levels() - 1;
            let covers = |c: &ClipMapConfig| c.half_extent(l) >= reach + 0.5 * c.snap(l);
            if l + 1 == MAX_LEVELS && !covers(&cfg) {
                // Widen the last level to reach the far edge.
                let need = (2.0 * (reach + 0.5 * cfg.snap(l)) / cfg.cell(l)).ceil() as u32;
                cfg.cells[l as usize] = need.next_multiple_of(step);
                return cfg;
            }
            // Widen level l until a level `ratio` times coarser meets the target beyond it
            // (and level l nests in it).
            loop {
                if covers(&cfg) {
                    return cfg;
                }
                let mut next = cfg.clone();
                // The narrowest next level that holds level l (its own border needs no margin
                // while it is the last level).
                let inner = cfg.half_extent(l) + cfg.max_centre_offset(l);
                let n = (2.0 * inner / cfg.cell(l + 1)).ceil().max(8.0) as u32;
                next.cells.push(n.next_multiple_of(step));
                while !next.nests(l) {
                    next.cells[l as usize + 1] += step;
                }
                let fits = l == 0 || next.nests(l - 1);
                let plan = (fits || cfg.cells[l as usize] >= MAX_CELLS)
                    .then(|| level(&next, l + 1, plans.last()));
                if let Some(plan) = plan
                    && (meets(&plan) || cfg.cells[l as usize] >= MAX_CELLS)
                {
                    cfg = next;
                    plans.push(plan);
                    break;
                }
                cfg.cells[l as usize] += step;
            }
        }
    }
}

/// Ladders of base cell sizes that [`ClipMapConfig::for_view`] tries: s₀ = 2^(e + i/steps).
pub const BASE_LADDER_STEPS: u32 = 8;

/// The interpolation bound Σ A k² (extent along D)² of a lattice turned by `angle` radians
/// that keeps all of `sea`'s waves, 1/m (per cell² of a unit cell).
pub(crate) fn lattice_bound(sea: &WaveSet, angle: f64) -> f64 {
    let cfg = ClipMapConfig {
        angle,
        ..ClipMapConfig::uniform(1, 8, 1.0)
    };
    sea.waves
        .iter()
        .map(|w| {
            let d = cfg.to_lattice(DVec2::from(w.direction));
            w.amplitude() * w.k() * w.k() * extent_along([d.x, d.y]).powi(2)
        })
        .sum()
}

/// Lattice orientations [`lattice_angle`] tries: every degree of a half turn.
pub(crate) const LATTICE_ANGLES: u32 = 180;

/// The lattice orientation, radians, with the smallest interpolation bound Σ A k² (extent
/// along D)² over the sea's waves (the bound of a level that keeps them all). A wave running
/// along the cells' split diagonal errs twice as much as one running across it (its triangles
/// are √2 against 1/√2 cells long along it), so the lattice turns its diagonal across the
/// short, curved waves. The first best of whole degrees in [0°, 180°).
pub(crate) fn lattice_angle(sea: &WaveSet) -> f64 {
    (0..LATTICE_ANGLES)
        .map(|deg| f64::from(deg).to_radians())
        .map(|a| (lattice_bound(sea, a), a))
        .fold(
            (f64::INFINITY, 0.0),
            |best, x| if x.0 < best.0 { x } else { best },
        )
        .1
}

/// The largest extent, in cells, of one of the mesh's triangles along the unit direction `d`
/// (in lattice coordinates): the triangles are (0,0),(0,1),(1,1) and (0,0),(1,1),(1,0) in
/// cell units. Between 1/√2 (a wave across the split diagonal), 1 (along an axis) and √2
/// (along the diagonal).
pub(crate) fn extent_along(d: [f64; 2]) -> f64 {
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

/// Why a tile or cell is not drawn.
enum Outside {
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
    fn hole(&self, l: u32, eye: DVec2) -> Option<(i64, i64, i64, i64)> {
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

    /// Every tile of every level that survives `culling` for an eye at world (x, z) `eye`:
    /// `visit(level, [i0, i1, j0, j1], cells)` in lattice indices, `cells` having bit
    /// (j − j0) t + (i − i0) set for each cell (i, j) to draw (outside the hole, meeting the
    /// view and the play area). Returns each level's stats.
    fn visit_tiles(
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
        // is not drawn, if it is not.
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
            let t = i64::from(TILE_CELLS).min(n / 2);
            let s = self.cell(l);
            let ci = self.centre_index(l, eye);
            let hole = self.hole(l, eye);
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

    /// Triangles that [`ClipMapConfig::build`] would emit, without building the mesh.
    pub(crate) fn triangles_drawn(&self, eye: DVec2, culling: &Culling) -> u64 {
        self.visit_tiles(eye, culling, |_, _, _| {})
            .iter()
            .map(|s| s.triangles)
            .sum()
    }

    /// Build the mesh for an eye at world (x, z) = `eye`, emitting only the tiles that survive
    /// `culling`.
    pub fn build(&self, eye: DVec2, culling: &Culling) -> ClipMesh {
        let origin = self.origin_for(eye);
        let origin_lattice = self.centre_lattice(self.levels() - 1, eye);
        let (mut vertices, mut indices) = (Vec::new(), Vec::new());
        let centres: Vec<I64Vec2> = (0..self.levels())
            .map(|l| self.centre_index(l, eye))
            .collect();
        let levels = self.visit_tiles(eye, culling, |l, [i0, i1, j0, j1], cells| {
            let t = i64::from(TILE_CELLS).min(i64::from(self.cells[l as usize]) / 2);
            let base = vertices.len() as u32;
            let wi = (i1 - i0 + 1) as u32;
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let (p, fade) = self.morphed_vertex(l, i, j, centres[l as usize]);
                    let q = self.to_world(p - origin_lattice);
                    vertices.push(ClipVertex {
                        rest: [q.x as f32, q.y as f32],
                        fade: fade as f32,
                        level: l,
                    });
                }
            }
            for j in j0..j1 {
                for i in i0..i1 {
                    if cells & (1 << ((j - j0) * t + (i - i0))) == 0 {
                        continue;
                    }
                    let a = base + ((j - j0) as u32) * wi + (i - i0) as u32;
                    let (b, d, e) = (a + 1, a + wi, a + wi + 1);
                    // Every quad split along the same diagonal, at every level, so a fully
                    // morphed fine quad matches the coarse triangulation.
                    indices.extend_from_slice(&[a, d, e, a, e, b]);
                }
            }
        });
        ClipMesh {
            origin,
            vertices,
            indices,
            levels,
        }
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    fn config() -> ClipMapConfig {
        ClipMapConfig {
            cells: vec![32, 24, 20, 32],
            base_cell: 0.5,
            ratio: LevelRatio::DOUBLING,
            angle: 0.0,
            morph_band: DEFAULT_MORPH_BAND,
        }
    }

    /// `config()` for doubling; for the other ratios five levels of 1 m × (p/q)^L cells on a
    /// lattice turned by 0.7 rad, each the narrowest that nests the finer one plus two steps
    /// (so morph bands are wide).
    fn configs() -> Vec<ClipMapConfig> {
        let mut out = vec![config()];
        for ratio in &LEVEL_RATIOS[1..] {
            let step = 2 * ratio.p;
            let mut c = ClipMapConfig {
                cells: vec![4 * step; 5],
                base_cell: 1.0,
                ratio: *ratio,
                angle: 0.7,
                morph_band: DEFAULT_MORPH_BAND,
            };
            for l in 0..c.levels() - 1 {
                while !c.nests(l) {
                    c.cells[l as usize + 1] += step;
                }
                c.cells[l as usize + 1] += 2 * step;
            }
            out.push(c);
        }
        out
    }

    #[test]
    fn coarse_index_is_the_nearest_coarse_point_monotone_onto_and_exact_on_shared_points() {
        for r in LEVEL_RATIOS {
            let (p, q) = (i64::from(r.p), i64::from(r.q));
            let mut hit = std::collections::BTreeSet::new();
            for i in -60i64..=60 {
                let c = r.coarse_index(i);
                // Fine point i sits at i q / p coarse cells: c is the nearest (ties lower).
                let x = i as f64 * r.q as f64 / r.p as f64;
                assert!((x - c as f64).abs() <= 0.5, "{r:?} {i} -> {c}");
                assert!(r.coarse_index(i + 1) - c <= 1 && r.coarse_index(i + 1) >= c);
                if i % p == 0 {
                    assert_eq!(c, i / p * q, "{r:?} {i}");
                }
                hit.insert(c);
            }
            let (lo, hi) = (r.coarse_index(-60), r.coarse_index(60));
            assert_eq!(hit.len() as i64, hi - lo + 1, "{r:?} not onto");
        }
    }

    #[test]
    fn unculled_mesh_has_the_closed_form_triangle_count() {
        for c in configs() {
            for eye in [
                DVec2::ZERO,
                DVec2::new(3.3, -7.9),
                DVec2::new(-1234.6, 987.2),
            ] {
                let m = c.build(eye, &Culling::default());
                assert_eq!(m.triangles(), c.full_triangles(), "{:?} eye {eye}", c.ratio);
                assert_eq!(c.triangles_drawn(eye, &Culling::default()), m.triangles());
            }
        }
    }

    #[test]
    fn levels_tile_the_plane_without_overlap_or_gap() {
        // Every point of the outermost square is covered by exactly one triangle's cell, and
        // after morphing the triangles still cover it exactly (none flips or overlaps).
        for c in configs() {
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
            let tol = 1e-9 * side * side;
            assert!(
                (area - side * side).abs() < tol,
                "{:?}: {area} vs {}",
                c.ratio,
                side * side
            );
            let morphed: f64 = m
                .indices
                .chunks(3)
                .map(|t| {
                    let p = |k: usize| {
                        let r = m.vertices[t[k] as usize].rest;
                        DVec2::new(f64::from(r[0]), f64::from(r[1]))
                    };
                    let (a, b) = (p(1) - p(0), p(2) - p(0));
                    // Signed: a flipped triangle would subtract.
                    (b.x * a.y - a.x * b.y) / 2.0
                })
                .sum();
            assert!(
                (morphed - side * side).abs() < 1e-4 * side * side,
                "{:?}: morphed {morphed} vs {}",
                c.ratio,
                side * side
            );
        }
    }

    #[test]
    fn morphed_border_coincides() {
        // After morphing, every vertex on the outer border of level L is displaced to exactly
        // where a vertex of level L + 1 is: same rest point, same evaluated waves. And every
        // vertex of level L + 1 on the hole's border is met by one: the two borders are the
        // same polyline (no T-junction), for every level ratio.
        let sea = WaveSet::default_sea();
        let target = ErrorTarget::uniform(0.5, 720, 1.0);
        for c in configs() {
            let plan = c.plan(&sea, &target, 8.0);
            assert!(
                plan.windows(2).any(|p| p[1].kept.len() < p[0].kept.len()),
                "{:?}: the test needs a level that drops waves",
                c.ratio
            );
            let eye = DVec2::new(13.2, -4.9);
            let m = c.build(eye, &Culling::default());
            let t = 1234.5;
            let world =
                |v: &ClipVertex| m.origin + DVec2::new(f64::from(v.rest[0]), f64::from(v.rest[1]));
            let mut checked = 0;
            for l in 0..c.levels() - 1 {
                let centre = c.centre_lattice(l, eye);
                let h = c.half_extent(l);
                // Chebyshev distance in the lattice's frame (rest points are f32).
                let on_border =
                    |p: DVec2| ((c.to_lattice(p) - centre).abs().max_element() - h).abs() < 1e-4;
                let coarse: Vec<(DVec2, DVec3, [f32; 2])> = m
                    .vertices
                    .iter()
                    .filter(|v| v.level == l + 1)
                    .map(|v| {
                        let d = vertex_displacement(&sea, &plan, v, m.origin, t);
                        (world(v), d, v.rest)
                    })
                    .collect();
                let mut fine = Vec::new();
                for v in m.vertices.iter().filter(|v| v.level == l) {
                    let p = world(v);
                    if !on_border(p) {
                        continue;
                    }
                    assert_eq!(v.fade, 0.0, "border vertex of level {l} not fully morphed");
                    let d = vertex_displacement(&sea, &plan, v, m.origin, t);
                    let nearest = coarse
                        .iter()
                        .map(|q| (q.1 - d).length())
                        .fold(f64::MAX, f64::min);
                    assert!(
                        nearest < 1e-9,
                        "{:?}: level {l} border vertex {p} is {nearest} m off",
                        c.ratio
                    );
                    fine.push(v.rest);
                    checked += 1;
                }
                for (q, _, rest) in coarse.iter().filter(|q| on_border(q.0)) {
                    assert!(
                        fine.contains(rest),
                        "{:?}: level {} hole vertex {q} meets no level-{l} vertex",
                        c.ratio,
                        l + 1
                    );
                }
            }
            assert!(checked > 100, "only {checked} border vertices checked");
        }
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
        let ci = c.centre_index(0, eye);
        assert_eq!(c.morphed_vertex(0, 1, 0, ci).0, DVec2::new(0.5, 0.0));
        assert_eq!(c.morphed_vertex(0, 1, 16, ci).0, DVec2::new(0.0, 8.0));
        // At ratio 3/2 a border vertex slides onto the nearest coarse point: fine index 4 of
        // 1 m cells (4 m) onto coarse index 3 of 1.5 m cells (4.5 m).
        let c = &configs()[1];
        assert_eq!(c.ratio, LevelRatio { p: 3, q: 2 });
        let h = i64::from(c.cells[0] / 2);
        let (p, fade) = c.morphed_vertex(0, 4, h, I64Vec2::ZERO);
        assert_eq!((p, fade), (DVec2::new(4.5, h as f64 * 1.0), 0.0));
        // Lattice coordinates turn into world ones and back.
        let w = c.to_world(p);
        assert!((w.length() - p.length()).abs() < 1e-12);
        assert!((c.to_lattice(w) - p).length() < 1e-12);
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
            // Tiles touching the area keep their vertices: at most one tile beyond it.
            let slack = 3.0 + c.cell(v.level) * f64::from(TILE_CELLS);
            assert!(p.x.abs() <= slack && p.y.abs() <= slack, "{p}");
        }
        // But only the cells that meet the area are drawn, on a turned lattice too: every
        // triangle has a vertex within a cell's diagonal of the area, and the cells that
        // cover the area are all there (its area is drawn).
        for angle in [0.0, 0.7] {
            let c = ClipMapConfig { angle, ..config() };
            let culling = Culling {
                frustum: None,
                play_area: Some([-3.0, -3.0, 3.0, 3.0]),
                max_displacement: 0.0,
            };
            let small = c.build(DVec2::new(0.4, -0.3), &culling);
            assert_eq!(
                c.triangles_drawn(DVec2::new(0.4, -0.3), &culling),
                small.triangles()
            );
            // A triangle's corners, world metres.
            let corners = |t: &[u32]| -> Vec<DVec2> {
                t.iter()
                    .map(|&k| {
                        let r = small.vertices[k as usize].rest;
                        small.origin + DVec2::new(f64::from(r[0]), f64::from(r[1]))
                    })
                    .collect()
            };
            let mut area = 0.0;
            for t in small.indices.chunks(3) {
                let level = small.vertices[t[0] as usize].level;
                let p = corners(t);
                let slack = 3.0 + c.cell(level) * 2f64.sqrt() + 1e-4;
                assert!(
                    p.iter().any(|q| q.x.abs() <= slack && q.y.abs() <= slack),
                    "{angle}: {p:?}"
                );
                area += (p[1] - p[0]).perp_dot(p[2] - p[0]).abs() / 2.0;
            }
            // Fewer triangles than whole tiles would give, and at least the area's 36 m².
            assert!(area >= 36.0, "{angle}: {area}");
            let whole = small.levels.iter().map(|l| l.tiles_drawn).sum::<u32>();
            assert!(small.triangles() < 2 * 64 * u64::from(whole), "{angle}");
            // Every point of the area lies in a drawn triangle.
            for k in 0..400 {
                let q = DVec2::new(
                    -2.99 + 0.015 * f64::from(k % 400),
                    2.99 - 0.0149 * f64::from((k * 7) % 400),
                );
                let hit = small.indices.chunks(3).any(|t| {
                    let p = corners(t);
                    let d = (p[1] - p[0]).perp_dot(p[2] - p[0]);
                    let u = (q - p[0]).perp_dot(p[2] - p[0]) / d;
                    let v = (p[1] - p[0]).perp_dot(q - p[0]) / d;
                    d.abs() > 0.0 && u >= -1e-6 && v >= -1e-6 && u + v <= 1.0 + 1e-6
                });
                assert!(hit, "{angle}: {q} is not drawn");
            }
        }
    }

    #[test]
    fn interpolated_height_is_exact_at_vertices_and_bounded_between() {
        for angle in [0.0, 0.7] {
            let c = ClipMapConfig { angle, ..config() };
            interpolation_within_bound(&c);
        }
    }

    fn interpolation_within_bound(c: &ClipMapConfig) {
        let sea = WaveSet::default_sea();
        let all: Vec<Vec<usize>> = vec![(0..sea.waves.len()).collect(); c.levels() as usize];
        let (eye, t) = (DVec2::new(0.3, 0.2), 77.0);
        // On a lattice vertex of level 0 the mesh height is the sea's height at that rest point.
        let v = c.to_world(DVec2::new(1.5, -2.0));
        let h = c.interpolated_height(&sea, &all, eye, v, t).unwrap();
        assert!((h - sea.displace([v.x, v.y], t)[1]).abs() < 1e-12);
        // Between vertices the error stays within the stated bound Σ A k² L²/8.
        let s = c.cell(0);
        let bound: f64 = sea
            .waves
            .iter()
            .map(|w| {
                let d = c.to_lattice(DVec2::from(w.direction));
                let l = extent_along([d.x, d.y]) * s;
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
    fn interpolated_height_matches_the_emitted_triangles() {
        // The measure's interpolation and the index buffer split cells the same way: the
        // height at a rest point, barycentric over the emitted triangle that holds it.
        let sea = WaveSet::default_sea();
        let target = ErrorTarget::uniform(0.5, 720, 1.0);
        for angle in [0.0, 0.7] {
            let c = ClipMapConfig { angle, ..config() };
            let plan = c.plan(&sea, &target, 8.0);
            let kept: Vec<Vec<usize>> = plan.iter().map(|p| p.kept.clone()).collect();
            let (eye, t) = (DVec2::ZERO, 55.5);
            let m = c.build(eye, &Culling::default());
            let rest = |k: u32| {
                let r = m.vertices[k as usize].rest;
                m.origin + DVec2::new(f64::from(r[0]), f64::from(r[1]))
            };
            for k in 0..300 {
                // Points well inside level 0's unmorphed part (< 6.4 m from its centre).
                let p = DVec2::new(
                    -4.0 + 0.0266 * f64::from(k),
                    3.5 - 0.024 * f64::from(k % 97) * 3.0,
                );
                let mine = c.interpolated_height(&sea, &kept, eye, p, t).unwrap();
                let tri = m
                    .indices
                    .chunks(3)
                    .filter(|t| m.vertices[t[0] as usize].level == 0)
                    .find_map(|t| {
                        let (a, b, d) = (rest(t[0]), rest(t[1]), rest(t[2]));
                        let det = (b - a).perp_dot(d - a);
                        let u = (p - a).perp_dot(d - a) / det;
                        let v = (b - a).perp_dot(p - a) / det;
                        (u >= -1e-9 && v >= -1e-9 && u + v <= 1.0 + 1e-9).then_some((t, u, v))
                    })
                    .expect("a level-0 triangle holds the point");
                let y = |k: u32| {
                    vertex_displacement(&sea, &plan, &m.vertices[k as usize], m.origin, t).y
                };
                let (t3, u, v) = tri;
                let theirs = y(t3[0]) * (1.0 - u - v) + y(t3[1]) * u + y(t3[2]) * v;
                assert!(
                    (mine - theirs).abs() < 1e-5,
                    "{angle} {p}: {mine} vs {theirs}"
                );
            }
        }
    }

    #[test]
    fn lattice_turns_its_diagonal_across_the_curved_waves() {
        // One wave: whatever its direction, the chosen lattice crosses it with triangles
        // 1/√2 cells long (the least any direction gets), up to the 1° step.
        for direction in [[1.0, 0.0], [0.6, 0.8], [0.8, -0.6]] {
            let mut sea = WaveSet::default_sea();
            sea.waves.truncate(1);
            sea.waves[0].direction = direction;
            let a = lattice_angle(&sea);
            let c = ClipMapConfig {
                angle: a,
                ..config()
            };
            let d = c.to_lattice(DVec2::from(direction));
            let e = extent_along([d.x, d.y]);
            assert!(
                (std::f64::consts::FRAC_1_SQRT_2 - 1e-12..0.72).contains(&e),
                "{e}"
            );
        }
        // The default sea, against an independent scan (Python, 0.1° steps): Σ A k² extent²
        // is 0.42328 m⁻¹ on the axis-aligned lattice and at least 0.24032 (at 53.2°).
        let sea = WaveSet::default_sea();
        let a = lattice_angle(&sea);
        assert!((lattice_bound(&sea, 0.0) - 0.42328).abs() < 1e-5);
        let best = lattice_bound(&sea, a);
        assert!(
            (0.24031..0.2410).contains(&best),
            "{best} at {}°",
            a.to_degrees()
        );
    }

    #[test]
    fn the_extent_bound_is_sharp_for_one_wave_along_each_axis_and_the_diagonal() {
        assert!((extent_along([1.0, 0.0]) - 1.0).abs() < 1e-15);
        assert!((extent_along([0.0, -1.0]) - 1.0).abs() < 1e-15);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((extent_along([h, h]) - 2f64.sqrt()).abs() < 1e-15);
        // Across the split diagonal, a triangle spans half of it.
        assert!((extent_along([h, -h]) - h).abs() < 1e-15);
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
            let pow2 = ClipMapConfig::for_view_on_ladder(
                &sea,
                &target,
                12.0,
                1000.0,
                LevelRatio::DOUBLING,
                1.0,
            );
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
