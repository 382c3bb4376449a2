//! The table plane seen through the camera image, formed in f64 on the CPU for the effects'
//! uniform: the projection's constant column for table points (`table_uv`), and the map from a
//! screen point to the camera-image point of the table straight behind it (`straight_through` in refraction.wgsl).
//!
//! Both take projections in the form of `PinholeCamera::image_projection`: a `DMat4` whose
//! rows 0–2 map a local point (p, 1) to (u·w, v·w, w), w > 0 in front of the camera.

use glam::{DMat3, DMat4, DVec4};

/// The constant column of `image_projection` (`PinholeCamera::image_projection`, local points
/// → (u w, v w, w)) for points on the table plane y = −`depth`: column 1 · (−depth) + column 3,
/// in f64, so that the shader's `table_uv` projects a table point (x, z) with two columns and
/// this one (xyz; w is 0).
pub fn table_column(image_projection: DMat4, depth: f64) -> DVec4 {
    image_projection.y_axis * -depth + image_projection.w_axis
}

/// [`table_column`] as the effects' uniform holds it.
pub fn table_image(image_projection: DMat4, depth: f64) -> [f32; 4] {
    let c = table_column(image_projection, depth);
    [c.x as f32, c.y as f32, c.z as f32, 0.0]
}

/// The render's view-projection (local points → clip space) as a projection to the screen's
/// uv (0..1 across, v down): rows (u·w, v·w, w) with w the clip w, so that it has the form of
/// `image_projection`. u = (ndc x + 1)/2, v = (1 − ndc y)/2.
pub fn screen_projection(view_proj: DMat4) -> DMat4 {
    let t = view_proj.transpose();
    let (x, y, w) = (t.x_axis, t.y_axis, t.w_axis);
    DMat4::from_cols((x + w) * 0.5, (w - y) * 0.5, w, DVec4::ZERO).transpose()
}

/// The map from a screen point to the camera-image point of the table straight behind it: the
/// point where the eye's ray through screen uv (s, t) meets the table plane y = −`depth`,
/// projected by `image_projection`, as the 3 × 3 matrix M with M·(s, t, 1) = (u·w, v·w, w)
/// (w > 0 where that point is in front of the camera and of the eye). Both maps are
/// projective (a plane seen from a point), so their composition is one matrix and exact: a
/// pixel pays three columns and a division where a ray-plane solve and a projection took 46
/// operations. `screen` is [`screen_projection`] of the render's view (or an
/// `image_projection` when the render camera is a pinhole camera).
///
/// `None` when the eye (at height `eye_y`, the render's) is not above the table plane (no ray
/// from it meets the table ahead through the water) or the plane is seen edge-on (the map is
/// singular).
pub fn straight_image(
    screen: DMat4,
    image_projection: DMat4,
    depth: f64,
    eye_y: f64,
) -> Option<DMat3> {
    let on_plane = |m: DMat4| {
        let c = table_column(m, depth);
        DMat3::from_cols(m.x_axis.truncate(), m.z_axis.truncate(), c.truncate())
    };
    // Table (x, z, 1) → screen (s·w, t·w, w), w the eye's depth (clip w) of the point.
    let to_screen = on_plane(screen);
    let det = to_screen.determinant();
    if eye_y <= -depth || !det.is_finite() || det.abs() < 1e-300 {
        return None;
    }
    Some(on_plane(image_projection) * to_screen.inverse())
}

/// [`straight_image`] as the effects' uniform holds it: its three columns, each padded to 4
/// (WGSL's mat3x3 layout); zero when there is no such map, which the shader reads as "no
/// table ahead" (w = 0).
pub fn straight_columns(map: Option<DMat3>) -> [[f32; 4]; 3] {
    let Some(m) = map else {
        return [[0.0; 4]; 3];
    };
    [m.x_axis, m.y_axis, m.z_axis].map(|c| [c.x as f32, c.y as f32, c.z as f32, 0.0])
}

/// `straight_image_of_clip` of refraction.wgsl in f64: the straight map `m` of a vertex's
/// screen point times its clip w, from its clip position `clip` (screen uv times w is
/// (½(x + w), ½(w − y))). Linear in the clip coordinates, so the rasteriser's perspective-
/// correct interpolation of it (and its clipping at the near plane) gives each pixel its own
/// `m·(s, t, 1)` times the pixel's clip w: the AR water's pixels take the straight-through
/// point from it without forming the map.
pub fn straight_image_of_clip(m: DMat3, clip: DVec4) -> glam::DVec3 {
    m * glam::DVec3::new(0.5 * (clip.x + clip.w), 0.5 * (clip.w - clip.y), clip.w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};
    use render::optics::{PinholeCamera, Plane};

    fn camera(eye: DVec3, target: DVec3, f: f64, cx: f64) -> PinholeCamera {
        PinholeCamera {
            fx: f,
            fy: f,
            cx,
            cy: 240.0,
            width: 640.0,
            height: 480.0,
            pose: glam::dcamera::rh::view::look_at_mat4(eye, target, DVec3::Y).inverse(),
        }
    }

    /// M·(s, t, 1) as a uv.
    fn apply(m: DMat3, s: DVec2) -> Option<DVec2> {
        let h = m * s.extend(1.0);
        (h.z > 0.0).then(|| h.truncate() / h.z)
    }

    #[test]
    fn the_straight_map_sends_a_pixel_to_the_table_point_behind_it() {
        // A render camera that is not the physical one (the desktop's orbit view over a
        // recorded feed): the eye's ray through each screen point, met with the table, then
        // projected by the physical camera (the f64 construction the map stands for).
        let depth = 0.3;
        let table = Plane::horizontal(-depth);
        let render_eye = DVec3::new(1.5, 2.0, 3.0);
        let render = camera(render_eye, DVec3::new(0.2, 0.0, -0.5), 420.0, 300.0);
        let physical = camera(DVec3::new(-0.5, 1.2, 2.0), DVec3::ZERO, 500.0, 320.0);
        let view = render.pose.inverse();
        let screen = render.image_projection(view);
        let image = physical.image_projection(physical.pose.inverse());
        let m =
            straight_image(screen, image, depth, render_eye.y).expect("the eye is above the table");
        let mut checked = 0;
        for k in 0..17 * 13 {
            let px = DVec2::new(f64::from(k % 17) * 40.0, f64::from(k / 17) * 40.0);
            let s = px / DVec2::new(640.0, 480.0);
            let ray = render.pixel_ray(px);
            let Some((_, point)) = table.intersect_ray(render_eye, ray) else {
                continue;
            };
            let want = physical.project_uv(point);
            assert_eq!(apply(m, s).is_some(), want.is_some(), "{px}");
            if let (Some(got), Some(want)) = (apply(m, s), want) {
                assert!((got - want).length() < 1e-9, "{px}: {got} {want}");
                checked += 1;
            }
        }
        assert!(checked > 100, "{checked}");
    }

    #[test]
    fn the_screen_projection_is_the_render_views_screen_uv() {
        // view_proj of a perspective camera: a point's screen uv from its clip coordinates.
        let view =
            glam::dcamera::rh::view::look_at_mat4(DVec3::new(0.0, 1.0, 2.0), DVec3::ZERO, DVec3::Y);
        let proj = glam::dcamera::rh::proj::directx::perspective(0.9, 0.5, 0.01, 100.0);
        let vp = proj * view;
        let screen = screen_projection(vp);
        for p in [DVec3::new(0.1, 0.0, 0.2), DVec3::new(-0.4, -0.3, -1.0)] {
            let c = vp * p.extend(1.0);
            let want = DVec2::new(0.5 * c.x / c.w + 0.5, 0.5 - 0.5 * c.y / c.w);
            let h = screen * p.extend(1.0);
            assert!((h.truncate().truncate() / h.z - want).length() < 1e-12);
            assert!((h.z - c.w).abs() < 1e-12);
        }
        // And the map from it agrees with the table point behind the pixel.
        let physical = camera(DVec3::new(0.3, 0.9, 1.5), DVec3::ZERO, 500.0, 320.0);
        let image = physical.image_projection(physical.pose.inverse());
        let m = straight_image(screen, image, 0.1, 1.0).unwrap();
        let s = DVec2::new(0.4, 0.7);
        let ndc = DVec2::new(2.0 * s.x - 1.0, 1.0 - 2.0 * s.y);
        let inv = vp.inverse();
        let near = inv.project_point3(ndc.extend(0.0));
        let far = inv.project_point3(ndc.extend(1.0));
        let eye = DVec3::new(0.0, 1.0, 2.0);
        let (_, point) = Plane::horizontal(-0.1)
            .intersect_ray(eye, (far - near).normalize())
            .unwrap();
        let want = physical.project_uv(point).unwrap();
        assert!((apply(m, s).unwrap() - want).length() < 1e-9);
    }

    /// What the AR water's pixels read: each vertex's `straight_image_of_clip`, interpolated
    /// as the rasteriser does (screen-space barycentrics, perspective-correct: Σλᵢaᵢ/wᵢ over
    /// Σλᵢ/wᵢ), names the same camera-image point as the map at the pixel's own screen uv, for
    /// triangles of the render view seen at grazing and steep angles (fixed-seed points).
    #[test]
    fn the_vertices_straight_map_interpolates_to_the_pixels_own() {
        let render_eye = DVec3::new(0.4, 1.1, 2.5);
        let view =
            glam::dcamera::rh::view::look_at_mat4(render_eye, DVec3::new(0.0, 0.0, -1.0), DVec3::Y);
        let proj = glam::dcamera::rh::proj::directx::perspective(0.9, 0.45, 0.01, 100.0);
        let vp = proj * view;
        let physical = camera(DVec3::new(-0.3, 0.9, 1.8), DVec3::ZERO, 500.0, 320.0);
        let image = physical.image_projection(physical.pose.inverse());
        let m = straight_image(screen_projection(vp), image, 0.2, render_eye.y).unwrap();
        let mut next = render::golden::fixed_seed_uniform(0x2545_f491_4f6c_dd1d);
        for _ in 0..200 {
            // A triangle on the water (y = 0), near and far, and a point inside it.
            let mut corner = || DVec3::new(4.0 * next() - 2.0, 0.0, -12.0 * next() + 1.5);
            let tri = [corner(), corner(), corner()];
            let clip = tri.map(|p| vp * p.extend(1.0));
            if clip.iter().any(|c| c.w <= 0.05) {
                continue;
            }
            let screen = clip.map(|c| DVec2::new(0.5 * c.x / c.w + 0.5, 0.5 - 0.5 * c.y / c.w));
            let (a, b) = (next(), next());
            let lambda = if a + b < 1.0 {
                [a, b, 1.0 - a - b]
            } else {
                [1.0 - a, 1.0 - b, a + b - 1.0]
            };
            let pixel: DVec2 = (0..3).map(|i| screen[i] * lambda[i]).sum();
            let per_w: f64 = (0..3).map(|i| lambda[i] / clip[i].w).sum();
            let h: DVec3 = (0..3)
                .map(|i| straight_image_of_clip(m, clip[i]) * (lambda[i] / clip[i].w))
                .sum::<DVec3>()
                / per_w;
            let want = m * pixel.extend(1.0);
            // The same point of the image (the same ray), scaled by the pixel's clip w > 0.
            assert!(h.z * want.z > 0.0, "{h} {want}");
            let (got, want) = (h.truncate() / h.z, want.truncate() / want.z);
            assert!((got - want).length() < 1e-9, "{got} {want}");
        }
    }

    #[test]
    fn an_eye_under_the_table_plane_has_no_straight_map() {
        let eye = DVec3::new(0.0, -0.5, 2.0);
        let render = camera(eye, DVec3::new(0.0, -0.6, 0.0), 500.0, 320.0);
        let screen = render.image_projection(render.pose.inverse());
        assert!(straight_image(screen, screen, 0.3, eye.y).is_none());
        assert_eq!(straight_columns(None), [[0.0; 4]; 3]);
        // The same camera above the table has one, and it is the identity (the render camera
        // is the physical one: the table point behind a pixel is seen at that pixel).
        let render = camera(DVec3::new(0.0, 0.5, 2.0), DVec3::ZERO, 500.0, 320.0);
        let screen = render.image_projection(render.pose.inverse());
        let m = straight_image(screen, screen, 0.3, 0.5).unwrap();
        let m = m / m.z_axis.z;
        assert!(
            (m - DMat3::IDENTITY)
                .to_cols_array()
                .iter()
                .all(|e| e.abs() < 1e-9)
        );
    }
}
