//! Placing the course by a tap: the screen point becomes a world ray through the virtual
//! camera, which is intersected with the detected upward-facing planes (the table). ARCore has
//! its own hit test (`ArFrame_hitTest`); this one works on any [`crate::CameraFrame`] (desktop
//! replays too) and is what the tests pin down. Also the two-finger gesture (pinch and twist).

use glam::{DMat4, DVec2, DVec3, Vec2};

use crate::{CameraFrame, DetectedPlane, PlaneKind};

/// A ray in world coordinates: `origin + t · direction`, `t ≥ 0`, direction unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
}

/// The world ray through pixel `px` (pixel centres at half-integers) of `frame`'s view.
pub fn tap_ray(frame: &CameraFrame, px: DVec2) -> Ray {
    let c2w: DMat4 = frame.camera_to_world.as_dmat4();
    let dir_cam = frame.intrinsics.ray_through_pixel(px);
    Ray {
        origin: c2w.transform_point3(DVec3::ZERO),
        direction: c2w.transform_vector3(dir_cam).normalize(),
    }
}

/// Where `ray` meets the top of `plane` inside its boundary, with the distance along the ray;
/// `None` for planes that do not face up, rays from below or parallel, hits behind the origin
/// or outside the polygon (or, without one, the extent's rectangle).
pub fn hit_plane(ray: &Ray, plane: &DetectedPlane) -> Option<(f64, DVec3)> {
    if plane.kind != PlaneKind::HorizontalUp {
        return None;
    }
    let pose = plane.center_pose.as_dmat4();
    let centre = pose.transform_point3(DVec3::ZERO);
    let normal = pose.transform_vector3(DVec3::Y).normalize();
    let denom = ray.direction.dot(normal);
    // From above only: the camera must look down onto the table's top.
    if denom > -1e-9 {
        return None;
    }
    let t = (centre - ray.origin).dot(normal) / denom;
    if t < 0.0 {
        return None;
    }
    let hit = ray.origin + t * ray.direction;
    let local = pose.inverse().transform_point3(hit);
    let p = Vec2::new(local.x as f32, local.z as f32);
    let inside = if plane.polygon.len() >= 3 {
        point_in_polygon(p, &plane.polygon)
    } else {
        p.x.abs() <= 0.5 * plane.extent.x && p.y.abs() <= 0.5 * plane.extent.y
    };
    inside.then_some((t, hit))
}

/// The nearest hit of `ray` among `planes`: index of the plane and the world point.
pub fn hit_test(ray: &Ray, planes: &[DetectedPlane]) -> Option<(usize, DVec3)> {
    planes
        .iter()
        .enumerate()
        .filter_map(|(i, p)| hit_plane(ray, p).map(|(t, q)| (t, i, q)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, i, q)| (i, q))
}

/// Even-odd rule; points on an edge may fall either way.
fn point_in_polygon(p: Vec2, poly: &[Vec2]) -> bool {
    let mut inside = false;
    let mut j = poly.len() - 1;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[j]);
        if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// A two-finger gesture measured from where both fingers went down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoFingerGesture {
    start: (DVec2, DVec2),
    last: (DVec2, DVec2),
}

impl TwoFingerGesture {
    /// Starts a gesture at the two touch points (screen pixels, y down).
    pub fn new(a: DVec2, b: DVec2) -> Self {
        Self {
            start: (a, b),
            last: (a, b),
        }
    }

    /// Moves the fingers; returns the pinch (distance ratio since the last update) and the
    /// twist (radians, counter-clockwise on screen as the user sees it, since the last update).
    /// A pinch of fingers closer than one pixel is ignored (ratio 1).
    pub fn update(&mut self, a: DVec2, b: DVec2) -> (f64, f64) {
        let before = self.last.1 - self.last.0;
        let now = b - a;
        self.last = (a, b);
        let pinch = if before.length() >= 1.0 && now.length() >= 1.0 {
            now.length() / before.length()
        } else {
            1.0
        };
        // Screen y points down, so a counter-clockwise turn seen by the user is a negative
        // angle in (x right, y down) coordinates.
        let twist = -(before.perp_dot(now)).atan2(before.dot(now));
        (pinch, twist)
    }

    /// Total pinch and twist since the fingers went down.
    pub fn total(&self) -> (f64, f64) {
        let mut g = Self::new(self.start.0, self.start.1);
        g.update(self.last.0, self.last.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FrameImage, Intrinsics, TrackingState};
    use glam::{Affine2, Mat4, Vec3};

    /// A phone 0.5 m above a table (top at y = −0.7 in the AR world), looking 45° down north.
    fn frame_over_table() -> CameraFrame {
        let eye = Vec3::new(0.0, -0.2, 0.3);
        let target = Vec3::new(0.0, -0.7, -0.2);
        // Camera axes: x right, y up, looking down −z.
        let f = (target - eye).normalize();
        let r = f.cross(Vec3::Y).normalize();
        let u = r.cross(f);
        CameraFrame {
            image: FrameImage::Rgba8 {
                width: 1,
                height: 1,
                data: vec![0; 4],
            },
            camera_to_world: Mat4::from_cols(
                r.extend(0.0),
                u.extend(0.0),
                (-f).extend(0.0),
                eye.extend(1.0),
            ),
            intrinsics: Intrinsics::from_hfov(1080, 1920, 60f64.to_radians()),
            planes: vec![table()],
            timestamp: 0.0,
            display_uv: Affine2::IDENTITY,
            tracking: TrackingState::Tracking,
        }
    }

    fn table() -> DetectedPlane {
        DetectedPlane {
            center_pose: Mat4::from_translation(Vec3::new(0.0, -0.7, -0.3)),
            extent: glam::Vec2::new(1.2, 0.8),
            polygon: vec![],
            kind: PlaneKind::HorizontalUp,
        }
    }

    #[test]
    fn tapping_a_known_table_point_hits_it() {
        let f = frame_over_table();
        for want in [
            DVec3::new(0.0, -0.7, -0.2),
            DVec3::new(0.3, -0.7, -0.5),
            DVec3::new(-0.5, -0.7, 0.05),
        ] {
            let px = f.project_world_point(want).unwrap();
            let (i, got) = hit_test(&tap_ray(&f, px), &f.planes).unwrap();
            assert_eq!(i, 0);
            // f32 poses: micrometres.
            assert!((got - want).length() < 1e-5, "{got} vs {want}");
        }
    }

    #[test]
    fn misses_outside_behind_and_from_below() {
        let f = frame_over_table();
        // Beyond the table's far edge (z = −0.7).
        let px = f.project_world_point(DVec3::new(0.0, -0.7, -0.9)).unwrap();
        assert!(hit_test(&tap_ray(&f, px), &f.planes).is_none());
        // Looking up at the sky: the plane is behind the ray.
        let up = Ray {
            origin: DVec3::new(0.0, -0.2, 0.0),
            direction: DVec3::Y,
        };
        assert!(hit_plane(&up, &table()).is_none());
        // From under the table.
        let below = Ray {
            origin: DVec3::new(0.0, -1.0, -0.3),
            direction: DVec3::Y,
        };
        assert!(hit_plane(&below, &table()).is_none());
        // Parallel to the top.
        let flat = Ray {
            origin: DVec3::new(0.0, -0.7, 0.0),
            direction: DVec3::NEG_Z,
        };
        assert!(hit_plane(&flat, &table()).is_none());
        // Ceilings and walls are not tables.
        let mut ceiling = table();
        ceiling.kind = PlaneKind::HorizontalDown;
        let down = Ray {
            origin: DVec3::new(0.0, 0.0, -0.3),
            direction: DVec3::NEG_Y,
        };
        assert!(hit_plane(&down, &ceiling).is_none());
        assert!(hit_plane(&down, &table()).is_some());
    }

    #[test]
    fn polygon_bounds_win_over_extent_and_nearest_plane_wins() {
        // An L-shaped table: the notch at +x +z is not table.
        let mut l = table();
        l.polygon = [
            (-0.6, -0.4),
            (0.6, -0.4),
            (0.6, 0.0),
            (0.0, 0.0),
            (0.0, 0.4),
            (-0.6, 0.4),
        ]
        .map(|(x, z)| glam::Vec2::new(x, z))
        .to_vec();
        let down = |x: f64, z: f64| Ray {
            origin: DVec3::new(x, 0.0, z),
            direction: DVec3::NEG_Y,
        };
        assert!(hit_plane(&down(0.3, -0.3 + 0.2), &l).is_none());
        assert!(hit_plane(&down(-0.3, -0.3 + 0.2), &l).is_some());
        // A box on the table (higher plane) is hit first.
        let mut top = table();
        top.center_pose = Mat4::from_translation(Vec3::new(0.0, -0.5, -0.3));
        top.extent = glam::Vec2::splat(0.2);
        let (i, q) = hit_test(&down(0.0, -0.3), &[table(), top]).unwrap();
        assert_eq!(i, 1);
        assert!((q.y + 0.5).abs() < 1e-6);
    }

    #[test]
    fn pinch_and_twist_follow_the_fingers() {
        let mut g = TwoFingerGesture::new(DVec2::new(100.0, 500.0), DVec2::new(300.0, 500.0));
        // Spread to twice the distance, turned 30° counter-clockwise as seen (y down).
        let a = std::f64::consts::FRAC_PI_6;
        let c = DVec2::new(200.0, 500.0);
        let half = 200.0 * DVec2::new(a.cos(), -a.sin());
        let (pinch, twist) = g.update(c - half, c + half);
        assert!((pinch - 2.0).abs() < 1e-12);
        assert!((twist - a).abs() < 1e-12);
        let (tp, tt) = g.total();
        assert!((tp - 2.0).abs() < 1e-12 && (tt - a).abs() < 1e-12);
        // Fingers on one spot: no pinch.
        let mut z = TwoFingerGesture::new(c, c);
        assert_eq!(z.update(c, c + DVec2::X * 50.0).0, 1.0);
    }
}
