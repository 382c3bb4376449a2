//! How finely the water's compute stage samples the wake where: the clip-map's levels as
//! squares around the eye, each with its vertex spacing. The wake at a vertex is band limited
//! for its level's spacing (`shaders/ocean/wake.wgsl`, `wake_band_fade`), so a bin of the wake
//! grid needs only the sources whose band-limited term can be non-zero at the finest spacing
//! of any vertex that can land in it (`wake_bins`).
//!
//! Conservative by construction: a level's square is taken as the axis-aligned box around the
//! lattice's (possibly rotated) square, grown by the sea's largest horizontal displacement
//! (a vertex is looked up where the waves have moved it) and the bins' margin. A point outside
//! every grown box is reached by no vertex.

use glam::DVec2;

use crate::clipmap::ClipMapConfig;

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

/// The clip-map's levels, finest first.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SampleSpacing {
    pub levels: Vec<LevelBox>,
}

impl SampleSpacing {
    /// One spacing everywhere (0: no band limit; for tests and views without a clip-map).
    pub fn uniform(spacing: f32) -> SampleSpacing {
        SampleSpacing {
            levels: vec![LevelBox {
                centre: [0.0; 2],
                half: f32::MAX,
                spacing,
            }],
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
        let levels = (0..clipmap.levels())
            .map(|l| {
                let centre = clipmap.centre(l, eye) - origin;
                LevelBox {
                    centre: [centre.x as f32, centre.y as f32],
                    half: (clipmap.half_extent(l) * turn + displacement) as f32,
                    spacing: clipmap.cell(l) as f32,
                }
            })
            .collect();
        SampleSpacing { levels }
    }

    /// The finest spacing of any vertex that can land in the local box [lo, hi] (grown by
    /// `margin`), or none when no level reaches it.
    pub fn finest_in(&self, lo: [f32; 2], hi: [f32; 2], margin: f32) -> Option<f32> {
        self.levels
            .iter()
            .filter(|b| {
                (0..2).all(|a| {
                    let reach = b.half.max(0.0) + margin;
                    lo[a] <= b.centre[a] + reach && hi[a] >= b.centre[a] - reach
                })
            })
            .map(|b| b.spacing)
            .reduce(f32::min)
    }

    /// Each level's spacing in the order of the shader's `level_spacing` (16 levels, the
    /// clip-map's most; unused entries 0).
    pub fn per_level(&self) -> [[f32; 4]; 4] {
        let mut out = [[0.0; 4]; 4];
        for (l, b) in self.levels.iter().take(16).enumerate() {
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
