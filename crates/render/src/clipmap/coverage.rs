//! What the clip-map mesh covers on screen, counted on the CPU: the pixels it draws, how many
//! times its triangles cover them, and the fragments a GPU runs for them at the granularity it
//! shades (2×2 quads on phone GPUs; lavapipe counts 4×4 blocks).
//!
//! Why: lavapipe's pipeline-statistics count of fragment invocations is 16 per 4×4 block that
//! a triangle touches, counted before the depth test (every count it gives is a multiple of
//! 16, and drawing the clip-map's triangles in reverse order gives the same count to the
//! fragment). The clip-map's far triangles are a few pixels each, so that count is about 3.7
//! times the pixels they cover, while the mesh itself covers each pixel about once
//! ([`ScreenCoverage::depth_complexity`]): the excess is the counter's granularity, not
//! overdraw, and no draw order removes it. A phone GPU shades 2×2 quads
//! ([`ScreenCoverage::quad_fragments`]).

use glam::{DMat4, DVec4};

use super::ClipMesh;

/// What a frame's clip-map covers on a viewport, summed over its triangles. A pixel is covered
/// by a triangle when its centre lies inside (on a shared edge, in exactly one of the two
/// triangles), as a GPU rasterises.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct ScreenCoverage {
    /// Pixels some triangle covers.
    pub pixels: u64,
    /// Pixels covered, summed over triangles (overlaps counted each time).
    pub fragments: u64,
    /// The part of `fragments` from back-facing triangles (clockwise on screen: the far sides
    /// of the waves, hidden behind their crests).
    pub back_facing_fragments: u64,
    /// 4 × the 2×2 quads (aligned to even pixels) in which a triangle covers a pixel, summed
    /// over triangles: what a GPU that shades quads runs, helper lanes included.
    pub quad_fragments: u64,
    /// 16 × the 4×4 blocks in which a triangle covers a pixel, summed over triangles: what
    /// lavapipe counts as fragment invocations (for the budget's frame 6,824,880 here against
    /// lavapipe's 6,761,424 with the wakes' displacement; for the A54 `low` frame 713,680
    /// against 713,728).
    pub block_fragments: u64,
    /// Triangles with a vertex at or behind the eye's plane (not counted; none in a view from
    /// above the water).
    pub behind_eye: u64,
}

impl ScreenCoverage {
    /// Times the mesh covers each pixel it covers, on average: 1 without overlap.
    pub fn depth_complexity(&self) -> f64 {
        self.fragments as f64 / self.pixels.max(1) as f64
    }
}

/// A vertex on screen: pixels (x right, y down from the top left).
type ScreenPoint = [f64; 2];

impl ClipMesh {
    /// What the mesh covers on a `size` viewport seen through `view_proj` (the frame's, for
    /// local coordinates). `surface` maps a vertex's rest point (local x, z, metres) to its
    /// displaced local position (x, y, z), e.g. the sea at the frame's time; the vertices'
    /// morph is already in their rest points.
    pub fn screen_coverage(
        &self,
        view_proj: DMat4,
        size: [u32; 2],
        surface: impl Fn([f64; 2]) -> [f64; 3],
    ) -> ScreenCoverage {
        let w = i64::from(size[0]);
        let mut covered = vec![false; (w * i64::from(size[1])).max(0) as usize];
        let mut out = ScreenCoverage::default();
        let (mut quads, mut blocks) = (Vec::new(), Vec::new());
        out.behind_eye = self.rasterise(view_proj, size, surface, |tri| {
            quads.clear();
            blocks.clear();
            for &(x, y) in tri.pixels {
                covered[(y * w + x) as usize] = true;
                quads.push((x / 2, y / 2));
                blocks.push((x / 4, y / 4));
            }
            for cells in [&mut quads, &mut blocks] {
                cells.sort_unstable();
                cells.dedup();
            }
            let n = tri.pixels.len() as u64;
            out.fragments += n;
            if tri.back_facing {
                out.back_facing_fragments += n;
            }
            out.quad_fragments += 4 * quads.len() as u64;
            out.block_fragments += 16 * blocks.len() as u64;
        });
        out.pixels = covered.iter().filter(|&&c| c).count() as u64;
        out
    }

    /// Each triangle's pixel footprint on the rest plane, with the fragments a GPU shading
    /// 2×2 quads runs for it and its clip-map level: (footprint, quad fragments, level) for
    /// every triangle that covers a pixel. The footprint is what a fragment shader's `max(length(dpdx(rest)),
    /// length(dpdy(rest)))` gives inside the triangle (metres of rest plane per pixel): the
    /// larger column of the Jacobian of the triangle's screen → rest map (constant over the
    /// triangle: it ignores the perspective change within it, under a part in a thousand for
    /// triangles of a pixel or two).
    pub fn footprints(
        &self,
        view_proj: DMat4,
        size: [u32; 2],
        surface: impl Fn([f64; 2]) -> [f64; 3],
    ) -> Vec<(f64, u64, u32)> {
        let mut out = Vec::new();
        let mut quads = Vec::new();
        self.rasterise(view_proj, size, surface, |tri| {
            quads.clear();
            quads.extend(tri.pixels.iter().map(|&(x, y)| (x / 2, y / 2)));
            quads.sort_unstable();
            quads.dedup();
            let [a, b, c] = tri.screen;
            let [ra, rb, rc] = tri.rest;
            // J = R S⁻¹ with S = [b − a, c − a] on screen and R the same edges on the rest plane.
            let s = [[b[0] - a[0], c[0] - a[0]], [b[1] - a[1], c[1] - a[1]]];
            let det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
            let inv = [
                [s[1][1] / det, -s[0][1] / det],
                [-s[1][0] / det, s[0][0] / det],
            ];
            let r = [
                [rb[0] - ra[0], rc[0] - ra[0]],
                [rb[1] - ra[1], rc[1] - ra[1]],
            ];
            let column = |j: usize| {
                let x = r[0][0] * inv[0][j] + r[0][1] * inv[1][j];
                let z = r[1][0] * inv[0][j] + r[1][1] * inv[1][j];
                x.hypot(z)
            };
            out.push((column(0).max(column(1)), 4 * quads.len() as u64, tri.level));
        });
        out
    }

    /// Rasterise the mesh as a GPU does (pixel centres, the top-left rule of [`inside_edge`])
    /// and hand each triangle that covers a pixel to `each`; returns the triangles left out
    /// for a vertex at or behind the eye's plane.
    fn rasterise(
        &self,
        view_proj: DMat4,
        size: [u32; 2],
        surface: impl Fn([f64; 2]) -> [f64; 3],
        mut each: impl FnMut(&TriangleOnScreen),
    ) -> u64 {
        let (w, h) = (i64::from(size[0]), i64::from(size[1]));
        let on_screen: Vec<Option<ScreenPoint>> = self
            .vertices
            .iter()
            .map(|v| {
                let p = surface([f64::from(v.rest[0]), f64::from(v.rest[1])]);
                let c = view_proj * DVec4::new(p[0], p[1], p[2], 1.0);
                (c.w > 0.0).then(|| {
                    [
                        (c.x / c.w * 0.5 + 0.5) * w as f64,
                        (0.5 - c.y / c.w * 0.5) * h as f64,
                    ]
                })
            })
            .collect();
        let mut behind_eye = 0;
        let mut pixels = Vec::new();
        for tri in self.indices.chunks_exact(3) {
            let corners = [0, 1, 2].map(|k| on_screen[tri[k] as usize]);
            let [Some(a0), Some(b0), Some(c0)] = corners else {
                behind_eye += 1;
                continue;
            };
            // Twice the signed area, y down: negative for counter-clockwise on screen (front).
            let area = (b0[0] - a0[0]) * (c0[1] - a0[1]) - (b0[1] - a0[1]) * (c0[0] - a0[0]);
            if area == 0.0 {
                continue;
            }
            // Ordered so that the inside is where every edge function is positive.
            let [a, b, c] = if area < 0.0 {
                [a0, b0, c0]
            } else {
                [a0, c0, b0]
            };
            let x0 = a[0].min(b[0]).min(c[0]).floor().max(0.0) as i64;
            let x1 = (a[0].max(b[0]).max(c[0]).ceil() as i64).min(w - 1);
            let y0 = a[1].min(b[1]).min(c[1]).floor().max(0.0) as i64;
            let y1 = (a[1].max(b[1]).max(c[1]).ceil() as i64).min(h - 1);
            pixels.clear();
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let p = [x as f64 + 0.5, y as f64 + 0.5];
                    if [(a, b), (b, c), (c, a)]
                        .iter()
                        .all(|&(from, to)| inside_edge(from, to, p))
                    {
                        pixels.push((x, y));
                    }
                }
            }
            if pixels.is_empty() {
                continue;
            }
            let rest = [0, 1, 2].map(|k| {
                let r = self.vertices[tri[k] as usize].rest;
                [f64::from(r[0]), f64::from(r[1])]
            });
            each(&TriangleOnScreen {
                level: self.vertices[tri[0] as usize].level,
                pixels: &pixels,
                back_facing: area > 0.0,
                screen: [a0, b0, c0],
                rest,
            });
        }
        behind_eye
    }
}

/// One rasterised triangle: the pixels whose centres it covers, and its corners on screen
/// and on the rest plane (local metres), in the mesh's order.
struct TriangleOnScreen<'a> {
    /// The clip-map level of its vertices (each level's triangles are its own).
    level: u32,
    pixels: &'a [(i64, i64)],
    back_facing: bool,
    screen: [ScreenPoint; 3],
    rest: [[f64; 2]; 3],
}

/// Is `p` on the inner side of the edge `from` → `to` of a triangle ordered so that its inside
/// is on every edge's left as seen on screen (y down)? On the edge itself, only for edges
/// running up the screen, or along it to the right: the other triangle on a shared edge runs it
/// the other way, so exactly one of the two covers a pixel centre on it.
fn inside_edge(from: ScreenPoint, to: ScreenPoint, p: ScreenPoint) -> bool {
    let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
    let e = dy * (p[0] - from[0]) - dx * (p[1] - from[1]);
    e > 0.0 || (e == 0.0 && (dy < 0.0 || (dy == 0.0 && dx > 0.0)))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::camera::Camera;
    use crate::clipmap::ClipVertex;
    use crate::frame::FrameContext;

    /// A mesh of the triangles `tris` (rest points, local metres).
    fn mesh(tris: &[[[f32; 2]; 3]]) -> ClipMesh {
        let vertices: Vec<ClipVertex> = tris
            .iter()
            .flatten()
            .map(|&rest| ClipVertex {
                rest,
                fade: 1.0,
                level: 0,
            })
            .collect();
        ClipMesh {
            indices: (0..vertices.len() as u32).collect(),
            vertices,
            ..Default::default()
        }
    }

    /// A 16 × 16 viewport looking straight down: rest (x, z) metres lands on pixel (x, z).
    fn from_above(m: &ClipMesh) -> ScreenCoverage {
        let view_proj = DMat4::from_cols(
            DVec4::new(2.0 / 16.0, 0.0, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 0.0, 0.0),
            DVec4::new(0.0, -2.0 / 16.0, 0.0, 0.0),
            DVec4::new(-1.0, 1.0, 0.5, 1.0),
        );
        m.screen_coverage(view_proj, [16, 16], |p| [p[0], 0.0, p[1]])
    }

    #[test]
    fn a_small_triangle_covers_the_pixels_quads_and_blocks_of_its_closed_form() {
        // Legs of 4.2 px from the corner: the centres (x + ½, y + ½) with x + y + 1 < 4.2,
        // i.e. x + y ≤ 3: 1 + 2 + 3 + 4 = 10 pixels, in the 2×2 quads (0,0), (1,0), (0,1)
        // (quad (1,1) starts at x + y = 4) and one 4×4 block.
        let front = mesh(&[[[0.0, 0.0], [0.0, 4.2], [4.2, 0.0]]]);
        let c = from_above(&front);
        assert_eq!(
            c,
            ScreenCoverage {
                pixels: 10,
                fragments: 10,
                back_facing_fragments: 0,
                quad_fragments: 12,
                block_fragments: 16,
                behind_eye: 0,
            }
        );
        // The same triangle wound the other way faces away from the eye.
        let back = mesh(&[[[0.0, 0.0], [4.2, 0.0], [0.0, 4.2]]]);
        assert_eq!(
            from_above(&back),
            ScreenCoverage {
                back_facing_fragments: 10,
                ..c
            }
        );
    }

    #[test]
    fn a_split_square_covers_each_pixel_once_and_a_doubled_triangle_twice() {
        // An 8 × 8 px cell split along its diagonal as the clip-map splits cells: the centres
        // on the diagonal belong to one triangle. The four 2×2 quads and two 4×4 blocks on the
        // diagonal hold pixels of both triangles, so both shade them.
        let (a, b, d, e) = ([0.0, 0.0], [8.0, 0.0], [0.0, 8.0], [8.0, 8.0]);
        let cell = mesh(&[[a, d, e], [a, e, b]]);
        let c = from_above(&cell);
        assert_eq!((c.pixels, c.fragments), (64, 64));
        assert_eq!(c.depth_complexity(), 1.0);
        assert_eq!(c.quad_fragments, 4 * (16 + 4));
        assert_eq!(c.block_fragments, 16 * (4 + 2));
        // Each triangle holds the 28 centres strictly on its side; the 8 on the diagonal go to
        // one of them.
        let lower = from_above(&mesh(&[[a, d, e]])).fragments;
        let upper = from_above(&mesh(&[[a, e, b]])).fragments;
        assert_eq!([lower.min(upper), lower.max(upper)], [28, 36]);
        let twice = mesh(&[[a, d, e], [a, e, b], [a, d, e]]);
        let c = from_above(&twice);
        assert_eq!((c.pixels, c.fragments), (64, 64 + lower));
    }

    /// The budget's frame (`regatta bench --only budget`: the sample race at 600 s on the
    /// Pixel 2 XL's `high` tier, 1440 × 2880 at render scale ¾), without boats and wakes.
    #[test]
    fn the_budget_frame_covers_each_pixel_about_once_but_its_small_triangles_cost_more() {
        let scene = crate::Scene {
            t: 600.0,
            sea: std::sync::Arc::new(ocean::WaveSet::default_sea()),
            boats: Vec::new(),
            marks: Vec::new(),
            play_area: [-1761.9, -1920.0, 1762.5, 1954.5],
            sun: DVec3::Y,
            camera: Camera::look_at(
                DVec3::new(120.679_156, 83.300_886, 78.974_388),
                DVec3::new(-8.9, 0.0, -124.65),
                20_000.0,
            ),
        };
        let size = [1080, 2160];
        let f = FrameContext::new(&scene, size, 1.0);
        let (o, sea, t) = (f.origin, &scene.sea, scene.t);
        let c = f.mesh.screen_coverage(f.view_proj, size, |p| {
            let d = sea.displace([p[0] + o.x, p[1] + o.y], t);
            [d[0] - o.x, d[1], d[2] - o.y]
        });
        // Below the horizon (14° under the top edge of a 55° view pitched 41° down) the
        // water fills the view but for its corners beyond the play area: 79 % when written.
        assert!(
            c.pixels as f64 > 0.7 * f64::from(size[0] * size[1]),
            "{c:?}"
        );
        assert_eq!(c.behind_eye, 0);
        // The levels tile the sea without overlap (`levels_tile_the_plane_without_overlap_or_gap`;
        // level 1 alone covers 0.8 M of these pixels, so a level drawn under another would add
        // 0.4 or more); what covers a pixel twice is a wave's far side behind its crest
        // (1.07 when written, back faces 3.4 % of the fragments).
        assert!(c.depth_complexity() < 1.1, "{c:?}");
        assert!(
            (c.back_facing_fragments as f64) < 0.05 * c.fragments as f64,
            "{c:?}"
        );
        // The far levels' triangles are 2–8 pixels each: 2×2 quads run 1.79 lanes per pixel
        // and 4×4 blocks, lavapipe's count (6.76 M for this frame with its wakes), 3.68.
        assert!(c.quad_fragments as f64 > 1.5 * c.pixels as f64, "{c:?}");
        assert!(
            c.block_fragments as f64 > 1.8 * c.quad_fragments as f64,
            "{c:?}"
        );
    }
}
