//! The camera-following clip-map of the Sailing+ wave-model thesis (TU Delft 2022;
//! docs/sources.md; after Asirvatham & Hoppe), sized from a
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
//! (ocean's [`ocean::WaveSet::cull`]). The error in pixels of a level is largest where its lattice
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

use glam::DVec2;

mod coverage;
mod displacement;
mod mesh;
mod morph;
mod plan;
#[cfg(test)]
mod tests;
mod tiles;

pub use coverage::ScreenCoverage;
#[cfg(test)]
pub(crate) use displacement::vertex_displacement;
pub use mesh::{ClipMesh, ClipVertex};
pub use plan::BASE_LADDER_STEPS;
pub(crate) use plan::{extent_along, height_over_crests};
pub use tiles::{Culling, LevelStats};

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

/// `a` turned by the angle whose (sine, cosine) is `(s, c)`.
fn rotate((s, c): (f64, f64), a: DVec2) -> DVec2 {
    DVec2::new(c * a.x - s * a.y, s * a.x + c * a.y)
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
        rotate(self.angle.sin_cos(), a)
    }

    /// [`ClipMapConfig::to_world`] with the angle's sine and cosine formed once, for the many
    /// points of a mesh (the same values: `rotate` is its arithmetic).
    pub(crate) fn world_rotation(&self) -> impl Fn(DVec2) -> DVec2 + use<> {
        let sin_cos = self.angle.sin_cos();
        move |a| rotate(sin_cos, a)
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
    pub(super) fn max_centre_offset(&self, l: u32) -> f64 {
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
}
