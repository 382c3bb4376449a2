//! The screen part the play area's water certainly covers: the camera background is not drawn
//! there.
//!
//! The background pass drew the camera image over the whole screen, and the AR water then drew
//! over most of it. On a GPU without hidden-surface removal every one of those pixels was
//! shaded twice; on the OPPO A54's PowerVR, whose hidden-surface removal would drop an opaque
//! background under opaque water, the water's play-area `discard` makes it a punch-through
//! object, whose pixels are shaded before the hardware knows what they hide, so the background
//! under it is shaded too. Now the background is drawn only outside a convex polygon of the
//! screen that the water covers whatever its waves and wakes do ([`water_cover`]), as a ring
//! of triangles between the polygon and a copy of it scaled about its centroid until it holds
//! the screen (`shaders/effects/background.wgsl`).
//!
//! Why the polygon is covered. Let a pixel's ray meet the rest plane y = 0 at F, below the
//! horizon by an angle θ. The water the pixel shows is a point X of the displaced mesh on that
//! ray: X = r + D with r its rest point and D the sea's displacement interpolated over a
//! triangle (a blend of the vertices' displacements: horizontally at most H = Σ amplitudes,
//! vertically at most V = Σ amplitudes plus [`WAKE_HEIGHT_MARGIN`]). So X is at most V above
//! or below the plane, hence within V / tan θ of F horizontally, and r within
//! m = H + V / tan θ of F. The polygon is the set of F, on the plane, with
//! - θ ≥ θ_cut: F within h / tan θ_cut of the eye's foot (h the eye's height; an inscribed
//!   polygon of that disc),
//! - the play area shrunk by m: r is inside it, so the shader's play-area test keeps X,
//! - the clip-map's square shrunk by m: the mesh is there,
//! - the view depth (clip w, affine on the plane) at least near + V / sin θ_cut and at most
//!   far − V / sin θ_cut: X lies between the near and far planes,
//!
//! all convex, so the polygon is convex; every pixel whose F lies in it is therefore covered
//! by water. In the screen the polygon is its vertices projected (all in front of the camera),
//! convex again. θ_cut is the one of a few candidates that covers the most screen.

use glam::{DMat4, DVec2, DVec4};

use render::frame::FrameContext;

use super::scissor::WAKE_HEIGHT_MARGIN;

/// Most vertices of the screen polygon the uniform carries (two per vec4).
pub const MAX_COVER_VERTICES: usize = 20;

/// Sides of the polygon inscribed in the disc θ ≥ θ_cut (it loses 1 − cos(π/12), 3.4 %, of
/// the disc's radius between its corners).
const DISC_SIDES: usize = 12;

/// Below this share of the screen the ring of triangles is not worth drawing.
const MIN_SCREEN_SHARE: f64 = 0.05;

/// The largest scale of the outer copy: a polygon so far from the screen's centre needs more,
/// and covers too little to matter.
const MAX_SCALE: f64 = 64.0;

/// The screen polygon the water certainly covers, in NDC, counter-clockwise, with the centroid
/// the ring is scaled about and the scale that makes the scaled copy hold the screen; `None`
/// where no polygon covers at least [`MIN_SCREEN_SHARE`] of the screen (the background is
/// drawn whole).
#[derive(Debug, Clone, PartialEq)]
pub struct WaterCover {
    pub ndc: Vec<DVec2>,
    pub centroid: DVec2,
    pub scale: f64,
}

/// Candidates for θ_cut, degrees: a small angle reaches far but needs a wide margin.
const THETA_CUTS: [f64; 5] = [3.0, 6.0, 12.0, 24.0, 45.0];

/// See the module docs.
pub fn water_cover(frame: &FrameContext) -> Option<WaterCover> {
    let amplitudes = frame.scene.sea.total_amplitude();
    cover_within(frame, amplitudes, amplitudes + WAKE_HEIGHT_MARGIN)
}

/// The cover for a water surface that moves at most `horizontal` metres across and
/// `vertical` metres up or down from its rest points.
fn cover_within(frame: &FrameContext, horizontal: f64, vertical: f64) -> Option<WaterCover> {
    THETA_CUTS
        .iter()
        .filter_map(|&deg| cover_at(frame, deg.to_radians(), horizontal, vertical))
        .max_by(|a, b| area(&a.ndc).total_cmp(&area(&b.ndc)))
}

/// The cover for one θ_cut (`v`: the surface's largest height off its rest plane).
fn cover_at(frame: &FrameContext, theta_cut: f64, horizontal: f64, v: f64) -> Option<WaterCover> {
    let s = frame.scene;
    let cam = &s.camera;
    let h = cam.eye.y;
    if h <= 0.0 {
        return None;
    }
    let m = horizontal + v / theta_cut.tan();
    let o = frame.origin;
    let eye = DVec2::new(cam.eye.x, cam.eye.z) - o;
    let radius = h / theta_cut.tan();
    let poly: Vec<DVec2> = (0..DISC_SIDES)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / DISC_SIDES as f64;
            eye + radius * DVec2::new(a.cos(), a.sin())
        })
        .collect();
    // Half-planes a·p + c ≥ 0 on the plane (local metres).
    let [ax, az, bx, bz] = s.play_area;
    let (lo, hi) = (DVec2::new(ax, az) - o + m, DVec2::new(bx, bz) - o - m);
    let reach = frame.reach - m;
    let w_row = frame.view_proj.row(3);
    let depth_margin = v / theta_cut.sin();
    let halves = [
        (DVec2::X, -lo.x),
        (DVec2::Y, -lo.y),
        (-DVec2::X, hi.x),
        (-DVec2::Y, hi.y),
        (DVec2::X, reach - eye.x),
        (DVec2::Y, reach - eye.y),
        (-DVec2::X, reach + eye.x),
        (-DVec2::Y, reach + eye.y),
        // Clip w of (x, 0, z, 1) is w_row·(x, 0, z, 1): the view depth.
        (
            DVec2::new(w_row.x, w_row.z),
            w_row.w - cam.near - depth_margin,
        ),
        (
            -DVec2::new(w_row.x, w_row.z),
            cam.far - depth_margin - w_row.w,
        ),
    ];
    let poly = clip_all(poly, &halves)?;
    let ndc: Vec<DVec2> = poly
        .iter()
        .map(|p| project(frame.view_proj, *p))
        .collect::<Option<_>>()?;
    // Only its part on the screen matters (convex again, and covered again).
    let screen = [
        (DVec2::X, 1.0),
        (DVec2::Y, 1.0),
        (-DVec2::X, 1.0),
        (-DVec2::Y, 1.0),
    ];
    let mut ndc = clip_all(counter_clockwise(ndc), &screen)?;
    // A vertex on a clipping line comes back twice: one of each pair.
    ndc.dedup_by(|b, a| (*a - *b).length() < 1e-9);
    while ndc.len() > 1 && (ndc[0] - ndc[ndc.len() - 1]).length() < 1e-9 {
        ndc.pop();
    }
    if ndc.len() < 3 || ndc.len() > MAX_COVER_VERTICES || area(&ndc) < MIN_SCREEN_SHARE * 4.0 {
        return None;
    }
    let centroid = ndc.iter().sum::<DVec2>() / ndc.len() as f64;
    let corners = [
        DVec2::new(-1.0, -1.0),
        DVec2::new(1.0, -1.0),
        DVec2::new(1.0, 1.0),
        DVec2::new(-1.0, 1.0),
    ];
    // The smallest scale about the centroid at which the copy holds each screen corner (the
    // polygon's gauge), with a margin, and never below 1.
    let scale = corners
        .iter()
        .map(|&x| gauge(&ndc, centroid, x))
        .fold(1.0, f64::max)
        * 1.01;
    (scale <= MAX_SCALE).then_some(WaterCover {
        ndc,
        centroid,
        scale,
    })
}

/// `poly` cut to every half-plane of `halves` in turn ([`clip`]); `None` once fewer than three
/// vertices are left.
fn clip_all(mut poly: Vec<DVec2>, halves: &[(DVec2, f64)]) -> Option<Vec<DVec2>> {
    for &(normal, offset) in halves {
        poly = clip(&poly, normal, offset);
        if poly.len() < 3 {
            return None;
        }
    }
    Some(poly)
}

/// `poly` cut to the half-plane normal·p + offset ≥ 0 (Sutherland–Hodgman).
fn clip(poly: &[DVec2], normal: DVec2, offset: f64) -> Vec<DVec2> {
    let side = |p: DVec2| normal.dot(p) + offset;
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, &a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            out.push(a + (b - a) * (sa / (sa - sb)));
        }
    }
    out
}

/// The NDC of the plane point (x, 0, z), `None` behind the eye.
fn project(view_proj: DMat4, p: DVec2) -> Option<DVec2> {
    let c = view_proj * DVec4::new(p.x, 0.0, p.y, 1.0);
    (c.w > 0.0).then(|| DVec2::new(c.x, c.y) / c.w)
}

/// The polygon's signed area (positive counter-clockwise), by the shoelace formula.
fn signed_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| poly[i].perp_dot(poly[(i + 1) % n]))
        .sum::<f64>()
        / 2.0
}

fn area(poly: &[DVec2]) -> f64 {
    signed_area(poly).abs()
}

fn counter_clockwise(mut poly: Vec<DVec2>) -> Vec<DVec2> {
    if signed_area(&poly) < 0.0 {
        poly.reverse();
    }
    poly
}

/// The smallest k with x in the copy of the convex counter-clockwise `poly` scaled by k about
/// `c` (inside it): the largest, over the edges, of x's reach past c towards the edge's line
/// over the edge's own.
fn gauge(poly: &[DVec2], c: DVec2, x: DVec2) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            // Outward normal of a counter-clockwise edge.
            let out = -(b - a).perp();
            out.dot(x - c) / out.dot(a - c)
        })
        .fold(0.0, f64::max)
}

/// The cover as the effects' uniform carries it: the vertices two to a vec4, the centroid
/// and scale, and the vertex count (0: no cover, the background whole).
pub fn cover_uniform(cover: Option<&WaterCover>) -> ([[f32; 4]; 10], [f32; 4], u32) {
    let mut vertices = [[0.0f32; 4]; MAX_COVER_VERTICES / 2];
    let Some(c) = cover else {
        return (vertices, [0.0; 4], 0);
    };
    for (i, p) in c.ndc.iter().enumerate() {
        let slot = &mut vertices[i / 2];
        slot[2 * (i % 2)] = p.x as f32;
        slot[2 * (i % 2) + 1] = p.y as f32;
    }
    (
        vertices,
        [
            c.centroid.x as f32,
            c.centroid.y as f32,
            c.scale as f32,
            0.0,
        ],
        c.ndc.len() as u32,
    )
}
#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, DVec4};
    use render::frame::FrameContext;

    use super::*;

    /// The demo table's own camera and the render crate's test views over its ±30 m.
    fn cameras() -> Vec<render::Camera> {
        let mut views = vec![crate::demo_table_scene(0.0).camera];
        views.extend(render::golden::test_views(30.0, 0x9e37_79b9_7f4a_7c15, 24));
        views
    }

    /// Where the ray from `eye` along unit `d` first meets the f64 sea surface raised by
    /// `lift` metres (a wake's height), as the surface's rest point and the distance along the
    /// ray; the ray is marched in 5 cm steps over the heights the surface can take, then
    /// bisected; `None` where the eye is under that surface. The rest point under a
    /// horizontal position is found by fixed-point iteration (the sea's horizontal map is a
    /// contraction for the demo's steepness).
    fn ray_hit(
        scene: &render::Scene,
        eye: DVec3,
        d: DVec3,
        lift: f64,
        top: f64,
    ) -> Option<(DVec2, f64)> {
        let t = scene.t;
        let rest_under = |x: DVec2| {
            let mut r = x;
            for _ in 0..60 {
                let p = scene.sea.surface([r.x, r.y], t).position;
                r += x - DVec2::new(p[0], p[2]);
            }
            let p = scene.sea.surface([r.x, r.y], t).position;
            (r, p[1] + lift)
        };
        let above = |s: f64| {
            let q = eye + d * s;
            q.y - rest_under(DVec2::new(q.x, q.z)).1
        };
        let (mut a, end) = ((eye.y - top) / -d.y, (eye.y + top) / -d.y);
        a = a.max(0.0);
        if above(a) <= 0.0 {
            return None;
        }
        let mut b = a;
        while above(b) > 0.0 {
            a = b;
            b += 0.05;
            assert!(
                b <= end + 1.0,
                "the ray passed under the surface's lowest height"
            );
        }
        for _ in 0..50 {
            let m = 0.5 * (a + b);
            if above(m) > 0.0 { a = m } else { b = m }
        }
        let q = eye + d * b;
        Some((rest_under(DVec2::new(q.x, q.z)).0, b))
    }

    /// Every pixel inside the cover polygon shows water: its ray meets the f64 sea surface
    /// (raised or lowered by the wake margin) at a rest point inside the play area, between
    /// the near and far planes, inside the clip-map's square, within the margin m of where it
    /// meets the rest plane. Points sampled inside each view's polygon on a 9 × 9 grid of its
    /// bounding box.
    #[test]
    fn every_pixel_of_the_cover_shows_water_of_the_play_area() {
        let (views, misses) = pixels_of_no_water(water_cover);
        assert!(views >= 20, "only {views} views have a cover");
        assert!(misses.is_empty(), "{}", misses.join("\n"));
    }

    /// The margins are what the argument needs: the same polygons without them (as if the
    /// water lay flat on its rest plane) hold pixels whose water lies outside the play area.
    #[test]
    fn a_cover_without_its_margins_holds_pixels_of_no_water() {
        let (_, misses) = pixels_of_no_water(|frame| cover_within(frame, 0.0, 0.0));
        assert!(!misses.is_empty());
    }

    /// For each view with a cover: the views counted, and the pixels of the cover whose water
    /// (the f64 sea, raised or lowered by the wake margin) misses the play area, the depth
    /// range or the clip-map's square.
    fn pixels_of_no_water(
        cover_of: impl Fn(&FrameContext) -> Option<WaterCover>,
    ) -> (usize, Vec<String>) {
        let size = [360, 640];
        let mut covered_views = 0;
        let mut misses = Vec::new();
        for (k, camera) in cameras().into_iter().enumerate() {
            let scene = render::Scene {
                camera,
                ..crate::demo_table_scene(17.0 * k as f64)
            };
            let frame = FrameContext::new(&scene, size, 1.0);
            let Some(cover) = cover_of(&frame) else {
                continue;
            };
            covered_views += 1;
            let inv = frame.view_proj.inverse();
            let eye = scene.camera.eye;
            let o = frame.origin;
            let amplitudes = scene.sea.total_amplitude();
            let top = amplitudes + WAKE_HEIGHT_MARGIN;
            let [ax, az, bx, bz] = scene.play_area;
            let (lo, hi) = cover
                .ndc
                .iter()
                .fold((DVec2::splat(9.0), DVec2::splat(-9.0)), |(l, h), p| {
                    (l.min(*p), h.max(*p))
                });
            let n = cover.ndc.len();
            let inside = |x: DVec2| {
                (0..n).all(|i| {
                    (cover.ndc[(i + 1) % n] - cover.ndc[i]).perp_dot(x - cover.ndc[i]) >= 0.0
                })
            };
            for i in 0..9 {
                for j in 0..9 {
                    let x =
                        lo + (hi - lo) * DVec2::new(f64::from(i) + 0.5, f64::from(j) + 0.5) / 9.0;
                    if !inside(x) {
                        continue;
                    }
                    let far = inv * DVec4::new(x.x, x.y, 1.0, 1.0);
                    let far = far.truncate() / far.w + DVec3::new(o.x, 0.0, o.y);
                    let d = (far - eye).normalize();
                    for lift in [-WAKE_HEIGHT_MARGIN, 0.0, WAKE_HEIGHT_MARGIN] {
                        let Some((rest, s)) = ray_hit(&scene, eye, d, lift, top) else {
                            misses.push(format!("view {k}, ndc {x}: the eye is under the water"));
                            continue;
                        };
                        let hit = eye + d * s - DVec3::new(o.x, 0.0, o.y);
                        let w = (frame.view_proj * hit.extend(1.0)).w;
                        let from_eye = (rest - DVec2::new(eye.x, eye.z)).abs().max_element();
                        let in_area = rest.x > ax && rest.x < bx && rest.y > az && rest.y < bz;
                        let in_depth = w > scene.camera.near && w < scene.camera.far;
                        if !in_area || !in_depth || from_eye >= frame.reach {
                            misses.push(format!(
                                "view {k}, ndc {x}: water at rest point {rest}, depth {w}, \
                                 {from_eye} m from the eye (reach {})",
                                frame.reach
                            ));
                        }
                    }
                }
            }
        }
        (covered_views, misses)
    }

    /// The polygon is convex and counter-clockwise on the screen, and the scaled copy holds
    /// the screen's corners.
    #[test]
    fn the_ring_around_the_cover_holds_the_screen() {
        for camera in cameras() {
            let scene = render::Scene {
                camera,
                ..crate::demo_table_scene(3.0)
            };
            let Some(c) = water_cover(&FrameContext::new(&scene, [360, 640], 1.0)) else {
                continue;
            };
            let n = c.ndc.len();
            for i in 0..n {
                let (a, b, e) = (c.ndc[i], c.ndc[(i + 1) % n], c.ndc[(i + 2) % n]);
                assert!((b - a).perp_dot(e - b) >= -1e-12, "not convex: {:?}", c.ndc);
                assert!(a.x.abs() <= 1.0 + 1e-12 && a.y.abs() <= 1.0 + 1e-12);
            }
            let scaled: Vec<DVec2> = c
                .ndc
                .iter()
                .map(|&p| c.centroid + (p - c.centroid) * c.scale)
                .collect();
            for corner in
                [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]].map(DVec2::from_array)
            {
                assert!(
                    (0..n).all(
                        |i| (scaled[(i + 1) % n] - scaled[i]).perp_dot(corner - scaled[i]) > 0.0
                    ),
                    "the screen corner {corner} is outside the ring's outer edge"
                );
            }
        }
    }
}
