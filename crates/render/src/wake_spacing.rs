//! How finely the water's compute stage samples the wake where: the clip-map's levels as
//! squares around the eye, each with its vertex spacing. The wake at a vertex is band limited
//! for its level's spacing (`shaders/ocean/wake.wgsl`, `wake_band_edges`), so a bin of the wake
//! grid needs, for each level whose vertices can land in it, only the sources whose term band
//! limited for that level's spacing can be non-zero there (`wake_bins`).
//!
//! Conservative by construction: a level's square is taken as the axis-aligned box around the
//! lattice's (possibly rotated) square, grown by the sea's largest horizontal displacement
//! (a vertex is looked up where the waves have moved it) and the bins' margin. A point outside
//! every grown box is reached by no vertex. With the frame's mesh ([`SampleSpacing::of_mesh`])
//! it is tighter: each vertex reaches only the square of its rest point grown by the
//! displacement, so a bin knows which levels' vertices can land in it, and none where the
//! mesh draws no water.

use glam::DVec2;

use crate::clipmap::{ClipMapConfig, ClipMesh};

/// The most clip-map levels the shader's `level_spacing` holds.
pub const MAX_LEVELS: usize = 16;

/// One level as the wake sees it: the local box its vertices can reach and their spacing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelBox {
    /// Local (x, z) centre, m.
    pub centre: [f32; 2],
    /// Half side of the box, m.
    pub half: f32,
    /// The level's vertex spacing (cell), m.
    pub spacing: f32,
}

/// The clip-map's levels, finest first, and where its vertices can land when the mesh is
/// known.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SampleSpacing {
    pub levels: Vec<LevelBox>,
    /// Each vertex's local rest point and level, or empty: then the level boxes say where
    /// each level can land.
    pub vertices: Vec<([f32; 2], u32)>,
    /// How far (m) a vertex can land from its rest point: the sea's largest horizontal
    /// displacement, grown for the GPU's f32 cosines (`DISPLACEMENT_SLACK`).
    pub displacement: f32,
}

/// The relative slack on the sea's horizontal displacement for the GPU's evaluation: WGSL's
/// `cos` errs by at most 2⁻¹¹ absolute on [−π, π], so a wave's f32 horizontal term a·cos θ
/// stays within a·(1 + 2⁻¹¹) plus rounding; 10⁻³ covers both.
const DISPLACEMENT_SLACK: f64 = 1e-3;

impl SampleSpacing {
    /// One spacing everywhere (0: no band limit; for tests and views without a clip-map).
    pub fn uniform(spacing: f32) -> SampleSpacing {
        SampleSpacing {
            levels: vec![LevelBox {
                centre: [0.0; 2],
                half: f32::MAX,
                spacing,
            }],
            vertices: Vec::new(),
            displacement: 0.0,
        }
    }

    /// The levels of `clipmap` for an eye at world (x, z) `eye`, relative to the local
    /// `origin`, grown by `displacement` (the sea's largest horizontal displacement, m).
    pub fn of_clipmap(
        clipmap: &ClipMapConfig,
        eye: DVec2,
        origin: DVec2,
        displacement: f64,
    ) -> SampleSpacing {
        let (s, c) = clipmap.angle.sin_cos();
        // The rotated square's axis-aligned box: half side × (|cos| + |sin|).
        let turn = c.abs() + s.abs();
        let grown = displacement * (1.0 + DISPLACEMENT_SLACK);
        let levels = (0..clipmap.levels())
            .map(|l| {
                let centre = clipmap.centre(l, eye) - origin;
                LevelBox {
                    centre: [centre.x as f32, centre.y as f32],
                    half: (clipmap.half_extent(l) * turn + grown) as f32,
                    spacing: clipmap.cell(l) as f32,
                }
            })
            .collect();
        SampleSpacing {
            levels,
            vertices: Vec::new(),
            displacement: grown as f32,
        }
    }

    /// [`SampleSpacing::of_clipmap`] with the frame's mesh: a bin is sampled only by the
    /// levels whose vertices, displaced by up to `displacement`, can land in it.
    pub fn of_mesh(
        clipmap: &ClipMapConfig,
        mesh: &ClipMesh,
        eye: DVec2,
        displacement: f64,
    ) -> SampleSpacing {
        SampleSpacing {
            vertices: mesh.vertices.iter().map(|v| (v.rest, v.level)).collect(),
            ..SampleSpacing::of_clipmap(clipmap, eye, mesh.origin, displacement)
        }
    }

    /// The finest spacing of any vertex that can land in the local box [lo, hi] (grown by
    /// `margin`), or none when no level reaches it (by the level boxes).
    pub fn finest_in(&self, lo: [f32; 2], hi: [f32; 2], margin: f32) -> Option<f32> {
        let mask = self.box_levels_in(lo, hi, margin);
        (mask != 0).then(|| self.levels[mask.trailing_zeros() as usize].spacing)
    }

    /// The levels (bit l: level l) whose boxes reach the local box [lo, hi] grown by
    /// `margin`.
    pub fn box_levels_in(&self, lo: [f32; 2], hi: [f32; 2], margin: f32) -> u32 {
        self.levels
            .iter()
            .take(MAX_LEVELS)
            .enumerate()
            .filter(|(_, b)| {
                (0..2).all(|a| {
                    let reach = b.half.max(0.0) + margin;
                    lo[a] <= b.centre[a] + reach && hi[a] >= b.centre[a] - reach
                })
            })
            .fold(0, |m, (l, _)| m | 1 << l)
    }

    /// Each level's spacing in the order of the shader's `level_spacing` (16 levels, the
    /// clip-map's most; unused entries 0).
    pub fn per_level(&self) -> [[f32; 4]; 4] {
        let mut out = [[0.0; 4]; 4];
        for (l, b) in self.levels.iter().take(MAX_LEVELS).enumerate() {
            out[l / 4][l % 4] = b.spacing;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every vertex of a built clip-map lies, displaced by up to the grown amount, inside its
    /// level's box, and the finest spacing found around it is at most its level's.
    #[test]
    fn every_vertex_is_inside_its_levels_box() {
        for angle in [0.0, 0.4, 1.1] {
            let cfg = ClipMapConfig {
                angle,
                ..ClipMapConfig::uniform(5, 16, 1.0)
            };
            let eye = DVec2::new(37.3, -12.9);
            let mesh = cfg.build(eye, &Default::default());
            let spacing = SampleSpacing::of_clipmap(&cfg, eye, mesh.origin, 2.0);
            assert_eq!(spacing.levels.len(), 5);
            for v in &mesh.vertices {
                let b = spacing.levels[v.level as usize];
                for (dx, dz) in [(0.0, 0.0), (1.99, 0.0), (-1.4, 1.4)] {
                    let p = [v.rest[0] + dx, v.rest[1] + dz];
                    for a in 0..2 {
                        assert!(
                            (p[a] - b.centre[a]).abs() <= b.half * (1.0 + 1e-6),
                            "angle {angle} level {} {p:?} outside {b:?}",
                            v.level
                        );
                    }
                    let finest = spacing.finest_in(p, p, 0.0).expect("a level");
                    assert!(finest <= b.spacing, "{finest} > {}", b.spacing);
                }
            }
        }
    }

    #[test]
    fn far_from_every_level_nothing_samples() {
        let cfg = ClipMapConfig::uniform(3, 8, 1.0);
        let spacing = SampleSpacing::of_clipmap(&cfg, DVec2::ZERO, DVec2::ZERO, 0.5);
        assert_eq!(
            spacing.finest_in([1e4, 1e4], [1e4 + 1.0, 1e4 + 1.0], 0.5),
            None
        );
        assert_eq!(spacing.finest_in([-1.0; 2], [1.0; 2], 0.0), Some(1.0));
        assert_eq!(
            SampleSpacing::uniform(0.0).finest_in([1e6; 2], [1e6; 2], 0.0),
            Some(0.0)
        );
    }
}
