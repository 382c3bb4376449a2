//! Planning the clip-map: each level's cell, reach and kept waves for an error target
//! ([`ClipMapConfig::plan`]), the greedy choice of ratio, ladder and levels for a view
//! ([`ClipMapConfig::for_view`]) and the lattice's turn across the short waves.

use glam::DVec2;
use ocean::WaveSet;

use super::{
    ClipMapConfig, DEFAULT_MORPH_BAND, ErrorTarget, LEVEL_RATIOS, LevelPlan, LevelRatio, MAX_LEVELS,
};

impl ClipMapConfig {
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
    pub(super) fn plan_level(
        &self,
        sea: &WaveSet,
        target: &ErrorTarget,
        eye_height: f64,
        l: u32,
        finer: Option<&LevelPlan>,
    ) -> LevelPlan {
        let lift = sea.total_amplitude();
        let h = height_over_crests(eye_height, lift);
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
    pub(super) fn greedy(
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

/// How far an eye `eye_height` metres from the rest level is above the highest crest of a sea
/// whose waves lift it at most `lift` metres (Σ amplitudes), at least 0.5 m: the height the
/// planner sees the water from (a level's nearest point; a pixel's grazing angle in
/// `vertex_slopes`).
pub(crate) fn height_over_crests(eye_height: f64, lift: f64) -> f64 {
    (eye_height.abs() - lift).max(0.5)
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
