//! Refraction of the real table, seen through the water (f64 reference of
//! `shaders/refraction.wgsl`).
//!
//! The AR water thesis (TU Delft 2022, report 000 in docs/sources.md) offsets the screen UV by the surface normal, so "every object is distorted the
//! same amount regardless of the angle" (its stated limitation). Here the view ray is refracted
//! by Snell's law (n = 1.333) through the actual surface normal, followed down to the table
//! plane under the water, and that table point is projected through the camera's intrinsics and
//! pose into the camera image: the displacement grows with the viewing angle and the depth,
//! as it does in a real glass of water.
//!
//! **Outside the image.** A refracted table point may project outside the camera frame (near
//! the frame's edges, or through a steep wave face). The sample is then *clamped to the edge
//! and faded to the unrefracted sample*: the weight of the refracted sample falls linearly from
//! 1 at the image border to 0 at [`EDGE_FADE`] (in UV units) outside it, and the rest of the
//! weight goes to the unrefracted sample (the table point straight along the view ray, which is
//! on screen wherever the water is). The result is continuous across the border, never samples
//! outside the texture and never shows a smeared edge stripe at full strength. A refracted ray
//! that does not reach the table (parallel to it, or bent upwards through an overhanging
//! face) or a table point behind the camera gets weight 0.

use glam::{DVec2, DVec3};

use render::optics::{N_AIR, N_WATER, PinholeCamera, Plane, refract};

/// How far outside the image (UV units) the refracted sample fades out completely.
pub const EDGE_FADE: f64 = 0.05;

/// One refracted camera-image sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableSample {
    /// Where the refracted ray meets the table (world, metres); `None` when it does not.
    pub table_point: Option<DVec3>,
    /// Camera-image UV to sample for the refracted view, clamped into [0, 1]².
    pub uv: DVec2,
    /// UV of the unrefracted view (straight through the water), clamped into [0, 1]².
    pub straight_uv: DVec2,
    /// Weight of the refracted sample; the unrefracted one gets 1 − weight.
    pub weight: f64,
    /// Length of the light's path in the water, metres: from the surface point to the
    /// refracted table point, or, when the refracted ray does not reach the table, along the
    /// view to the table (0 when that misses it too). The water's absorption acts over it.
    pub path: f64,
}

impl TableSample {
    /// The one camera-image point the shader samples (`refracted_table`): `weight` of the way
    /// from the unrefracted uv to the refracted one. Where the image is linear along that
    /// segment, its colour there is the blend of the two samples; elsewhere the two differ in
    /// the fade band only (see `shaders/refraction.wgsl`).
    pub fn sampled_uv(&self) -> DVec2 {
        self.straight_uv.lerp(self.uv, self.weight)
    }
}

/// The camera-image sample that a water pixel shows: the view ray from `eye` to the surface
/// point `surface` is refracted through the unit surface normal `normal` into the water and
/// followed down to `table`; the table point is projected into `camera`'s image.
pub fn refract_to_table(
    eye: DVec3,
    surface: DVec3,
    normal: DVec3,
    table: &Plane,
    camera: &PinholeCamera,
) -> TableSample {
    let view = (surface - eye).normalize();
    // Straight through the water: the table point behind the pixel, where the eye's ray
    // through it runs down to the table (seen by the camera); else the image's centre. Where
    // the render camera is the physical one (the phone) this is the water pixel itself.
    let straight = (view.y <= -1e-12)
        .then(|| table.intersect_ray(eye, view))
        .flatten()
        .and_then(|(_, p)| camera.project_uv(p));
    let straight_uv = clamp_uv(straight.unwrap_or(DVec2::splat(0.5)));
    // The path along the view from the surface down to the table (none: a trough below it).
    let straight_hit = table.intersect_ray(surface, view);
    let refracted =
        refract(view, normal, N_AIR, N_WATER).and_then(|t| table.intersect_ray(surface, t));
    let table_point = refracted.map(|(_, p)| p);
    let path = refracted.or(straight_hit).map_or(0.0, |(s, _)| s);
    let Some(uv) = table_point.and_then(|p| camera.project_uv(p)) else {
        return TableSample {
            table_point,
            uv: straight_uv,
            straight_uv,
            weight: 0.0,
            path,
        };
    };
    TableSample {
        table_point,
        uv: clamp_uv(uv),
        straight_uv,
        weight: edge_weight(uv),
        path,
    }
}

/// Weight of a sample at `uv`: 1 inside [0, 1]², falling linearly to 0 at [`EDGE_FADE`]
/// outside it, by the max-norm distance to the image rectangle (the larger of the two
/// distances past its edges: the Euclidean distance beside an edge, and at most √2 times
/// shorter than it off a corner). The max norm, not the Euclidean, because it is 11
/// operations a pixel where the length was 20; the fade's shape off the image's corners is
/// all that differs.
pub fn edge_weight(uv: DVec2) -> f64 {
    let outside = (DVec2::ZERO - uv).max(uv - DVec2::ONE);
    (1.0 - outside.max_element() / EDGE_FADE).clamp(0.0, 1.0)
}

fn clamp_uv(uv: DVec2) -> DVec2 {
    uv.clamp(DVec2::ZERO, DVec2::ONE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn camera(eye: DVec3, target: DVec3) -> PinholeCamera {
        crate::test_camera(eye, target, 400.0)
    }

    #[test]
    fn flat_water_bends_by_snell_and_more_at_grazing_angles() {
        // Flat water at y = 0 over a table 0.05 m below. For a view ray at θi the refracted
        // ray reaches the table at a horizontal distance depth·tan θt (sin θt = sin θi / 1.333)
        // instead of depth·tan θi.
        let depth = 0.05;
        let table = Plane::horizontal(-depth);
        let surface = DVec3::ZERO;
        let mut shifts = Vec::new();
        for deg in [0.0f64, 20.0, 40.0, 60.0, 75.0] {
            let ti = deg.to_radians();
            let eye = DVec3::new(-ti.sin(), ti.cos(), 0.0) * 0.6;
            let cam = camera(eye, surface);
            let s = refract_to_table(eye, surface, DVec3::Y, &table, &cam);
            let p = s.table_point.unwrap();
            let tt = (ti.sin() / N_WATER).asin();
            assert!((p.x - depth * tt.tan()).abs() < 1e-12, "{deg}°: {p}");
            assert!((p.y + depth).abs() < 1e-12 && p.z.abs() < 1e-12);
            // The refracted point is seen nearer the surface point than the straight one.
            let straight_x = depth * ti.tan();
            shifts.push(straight_x - p.x);
            assert_eq!(s.weight, 1.0);
            assert_eq!(s.uv, cam.project_uv(p).unwrap());
            // The light crosses the depth at θt: a path of depth / cos θt.
            assert!(
                (s.path - depth / tt.cos()).abs() < 1e-12,
                "{deg}°: {}",
                s.path
            );
            assert_eq!(s.sampled_uv(), s.uv);
        }
        // Not "the same regardless of angle": the apparent shift grows with the angle.
        assert!(shifts[0].abs() < 1e-15);
        assert!(shifts.windows(2).all(|w| w[1] > w[0]), "{shifts:?}");
    }

    #[test]
    fn a_tilted_normal_moves_the_sample_and_deeper_water_moves_it_more() {
        let eye = DVec3::new(0.0, 0.5, 0.3);
        let cam = camera(eye, DVec3::ZERO);
        let n = (DQuat::from_rotation_z(0.15) * DVec3::Y).normalize();
        let shallow = refract_to_table(eye, DVec3::ZERO, n, &Plane::horizontal(-0.02), &cam);
        let deep = refract_to_table(eye, DVec3::ZERO, n, &Plane::horizontal(-0.08), &cam);
        let flat = refract_to_table(eye, DVec3::ZERO, DVec3::Y, &Plane::horizontal(-0.08), &cam);
        let d = |s: &TableSample| (s.uv - s.straight_uv).length();
        assert!(
            d(&deep) > 3.0 * d(&shallow) && d(&deep) > d(&flat),
            "{deep:?} {shallow:?}"
        );
    }

    #[test]
    fn points_outside_the_image_clamp_to_the_edge_and_fade_to_the_straight_sample() {
        assert_eq!(edge_weight(DVec2::new(0.5, 0.5)), 1.0);
        assert_eq!(edge_weight(DVec2::new(0.0, 1.0)), 1.0);
        assert!((edge_weight(DVec2::new(1.0 + EDGE_FADE / 2.0, 0.5)) - 0.5).abs() < 1e-12);
        assert!((edge_weight(DVec2::new(-EDGE_FADE / 4.0, 0.3)) - 0.75).abs() < 1e-12);
        assert_eq!(edge_weight(DVec2::new(1.2, 0.5)), 0.0);
        // Off a corner the larger of the two distances past the edges counts (the max norm).
        let c = EDGE_FADE * 0.5;
        assert!((edge_weight(DVec2::new(1.0 + c, -c)) - 0.5).abs() < 1e-12);
        assert!((edge_weight(DVec2::new(-c / 2.0, 1.0 + c)) - 0.5).abs() < 1e-12);
        // Continuous across the border.
        let a = edge_weight(DVec2::new(1.0 - 1e-9, 0.5));
        let b = edge_weight(DVec2::new(1.0 + 1e-9, 0.5));
        assert!((a - b).abs() < 1e-6);

        // A water pixel at the right edge of the frame, seen at a grazing angle through deep
        // water with the normal tilted away: its refracted table point leaves the image.
        let eye = DVec3::new(0.0, 0.3, 0.6);
        let cam = camera(eye, DVec3::new(0.0, 0.0, -0.2));
        let edge_px = DVec2::new(639.0, 300.0);
        let ray = cam.pixel_ray(edge_px);
        let (_, surface) = Plane::horizontal(0.0).intersect_ray(eye, ray).unwrap();
        let n = (DQuat::from_rotation_z(0.8) * DVec3::Y).normalize();
        let s = refract_to_table(eye, surface, n, &Plane::horizontal(-1.0), &cam);
        let raw = cam.project_uv(s.table_point.unwrap()).unwrap();
        assert!(
            raw.x > 1.0 + EDGE_FADE,
            "the test needs a point well outside: {raw}"
        );
        assert_eq!(s.weight, 0.0);
        assert!(
            s.uv.x == 1.0 && (0.0..=1.0).contains(&s.uv.y),
            "clamped: {}",
            s.uv
        );
        // The straight sample is the water pixel itself.
        assert!((s.straight_uv - edge_px / DVec2::new(640.0, 480.0)).length() < 1e-9);
    }

    #[test]
    fn rays_that_miss_the_table_fall_back_to_the_straight_sample() {
        let eye = DVec3::new(0.0, 0.4, 0.4);
        let cam = camera(eye, DVec3::ZERO);
        // A table plane above the surface point: the refracted ray goes down and never meets it.
        let s = refract_to_table(eye, DVec3::ZERO, DVec3::Y, &Plane::horizontal(0.1), &cam);
        assert!(s.table_point.is_none());
        assert_eq!(s.weight, 0.0);
        assert_eq!(s.uv, s.straight_uv);
        assert!(
            (s.uv - DVec2::splat(0.5)).length() < 1e-12,
            "the water pixel itself"
        );
        // Nor does the view: no path in the water.
        assert_eq!(s.path, 0.0);
        assert_eq!(s.sampled_uv(), s.straight_uv);
        // A grazing view (1 in 10) into the underside of an overhanging face is bent upwards
        // and misses the table the view reaches: the path runs along the view down to it,
        // 0.1 m below, 0.1 · √101 / 10 = √1.01 m.
        let eye = DVec3::new(-1.0, 0.1, 0.0);
        let n = DVec3::new(-0.6, -0.8, 0.0);
        let up = refract((DVec3::ZERO - eye).normalize(), n, N_AIR, N_WATER).unwrap();
        assert!(up.y > 0.0, "bent upwards: {up}");
        let s = refract_to_table(eye, DVec3::ZERO, n, &Plane::horizontal(-0.1), &cam);
        assert!(s.table_point.is_none() && s.weight == 0.0);
        assert!((s.path - 1.01f64.sqrt()).abs() < 1e-12, "{}", s.path);
    }

    #[test]
    fn the_shaders_one_sample_lies_the_weight_along_the_way_to_the_refracted_one() {
        let s = TableSample {
            table_point: None,
            uv: DVec2::new(1.0, 0.4),
            straight_uv: DVec2::new(0.6, 0.2),
            weight: 0.25,
            path: 0.0,
        };
        assert!((s.sampled_uv() - DVec2::new(0.7, 0.25)).length() < 1e-15);
        assert_eq!(TableSample { weight: 0.0, ..s }.sampled_uv(), s.straight_uv);
        assert_eq!(TableSample { weight: 1.0, ..s }.sampled_uv(), s.uv);
    }
}
