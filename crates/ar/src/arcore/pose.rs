//! ARCore's pose and projection conventions, and where the race sits in ARCore's world.
//!
//! ARCore: right-handed, metres, y up against gravity, x and z in an arbitrary heading fixed at
//! session start; a pose is `[qx, qy, qz, qw, tx, ty, tz]` (rotation, then translation) mapping
//! local to world, like an OpenGL model matrix; the virtual camera looks down its −z with y up on
//! the display (`ArCamera_getDisplayOrientedPose`), exactly [`crate::CameraFrame`]'s convention.
//! Its projection matrix is OpenGL's (clip z in −w..w, column-major `float[16]`); wgpu wants
//! 0..w. The race world (x east, y up, z south, race metres) is placed on the table by a
//! [`CoursePlacement`]: a point on a detected plane, a turn about the vertical, and the
//! `course_to_table` scale.

use glam::{DMat4, DQuat, DVec3, Mat4, Quat, Vec3};

use crate::Intrinsics;

/// The rigid transform of an ARCore raw pose `[qx, qy, qz, qw, tx, ty, tz]`
/// (`ArPose_getPoseRaw`); the quaternion is normalised first.
pub fn pose_from_raw(raw: [f32; 7]) -> Mat4 {
    let q = Quat::from_xyzw(raw[0], raw[1], raw[2], raw[3]).normalize();
    Mat4::from_rotation_translation(q, Vec3::new(raw[4], raw[5], raw[6]))
}

/// An OpenGL projection (clip z in −w..w, `ArCamera_getProjectionMatrix`) as a wgpu one (clip z
/// in 0..w): z' = (z + w) / 2, so near still maps to 0 and far to 1.
pub fn gl_projection_to_wgpu(gl: DMat4) -> DMat4 {
    let remap = DMat4::from_cols_array(&[
        1.0, 0.0, 0.0, 0.0, //
        0.0, 1.0, 0.0, 0.0, //
        0.0, 0.0, 0.5, 0.0, //
        0.0, 0.0, 0.5, 1.0,
    ]);
    remap * gl
}

/// The pinhole intrinsics, for a view of `width` × `height` pixels, of a perspective projection
/// (OpenGL or wgpu: only its x and y rows are read). This makes ARCore's display-oriented
/// virtual camera a plain [`Intrinsics`], so the renderer needs no ARCore special case.
pub fn intrinsics_from_projection(p: DMat4, width: u32, height: u32) -> Intrinsics {
    let (w, h) = (f64::from(width), f64::from(height));
    // Inverse of Intrinsics::projection_wgpu: a = 2 fx / w, b = 1 − 2 cx / w, c = 2 fy / h,
    // d = 2 cy / h − 1, with b and d in the third column.
    Intrinsics {
        fx: p.x_axis.x * w / 2.0,
        fy: p.y_axis.y * h / 2.0,
        cx: (1.0 - p.z_axis.x) * w / 2.0,
        cy: (p.z_axis.y + 1.0) * h / 2.0,
        width,
        height,
    }
}

/// Where the course stands on the table, in ARCore's world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoursePlacement {
    /// AR-world point (metres) where the course origin (race (0, 0, 0)) sits: the tapped
    /// point on the table.
    pub anchor: DVec3,
    /// Turn about the vertical (radians, counter-clockwise seen from above) from race axes to
    /// AR axes.
    pub yaw: f64,
    /// AR metres per race metre (docs/command-line.md `course_to_table`), e.g. 1/2000 for a 2 km course
    /// on a 1 m table.
    pub course_to_table: f64,
}

impl CoursePlacement {
    /// Smallest and largest `course_to_table` a pinch may reach: 1:1,000,000 to 1:1.
    pub const SCALE_RANGE: (f64, f64) = (1e-6, 1.0);

    /// Race world (race metres) → AR world (AR metres): scale, turn about y, move to the anchor.
    /// Both frames are y-up and right-handed, so no axis changes sign.
    pub fn race_to_ar(&self) -> DMat4 {
        DMat4::from_scale_rotation_translation(
            DVec3::splat(self.course_to_table),
            DQuat::from_rotation_y(self.yaw),
            self.anchor,
        )
    }

    /// AR world → race world (the inverse of [`Self::race_to_ar`]).
    pub fn ar_to_race(&self) -> DMat4 {
        self.race_to_ar().inverse()
    }

    /// Applies a two-finger gesture: scale the course by `pinch` (clamped to
    /// [`Self::SCALE_RANGE`]) and turn it by `twist` radians about the anchor. `twist` is the
    /// fingers' turn on screen, counter-clockwise positive as seen by the user looking down on
    /// the table, so the course follows the fingers.
    pub fn apply_gesture(&mut self, pinch: f64, twist: f64) {
        if pinch.is_finite() && pinch > 0.0 {
            let (lo, hi) = Self::SCALE_RANGE;
            self.course_to_table = (self.course_to_table * pinch).clamp(lo, hi);
        }
        if twist.is_finite() {
            self.yaw = (self.yaw + twist).rem_euclid(std::f64::consts::TAU);
        }
    }

    /// Moves the course, keeping its turn and scale, so that the race point `race` (race
    /// metres) lands on the AR point `ar` (e.g. the play area's centre on a tapped table point).
    pub fn put(&mut self, race: DVec3, ar: DVec3) {
        let turned = DQuat::from_rotation_y(self.yaw) * (race * self.course_to_table);
        self.anchor = ar - turned;
    }

    /// [`Self::apply_gesture`] about the race point `pivot` instead of the race origin: the
    /// pivot stays where it is on the table while the course scales and turns under the fingers.
    pub fn apply_gesture_about(&mut self, pivot: DVec3, pinch: f64, twist: f64) {
        let on_table = self.race_to_ar().transform_point3(pivot);
        self.apply_gesture(pinch, twist);
        self.put(pivot, on_table);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn raw_pose_rotates_then_translates() {
        // 90° about +y: the camera's forward (−z) turns to world −x.
        let (s, c) = (
            std::f32::consts::FRAC_PI_4.sin(),
            std::f32::consts::FRAC_PI_4.cos(),
        );
        let m = pose_from_raw([0.0, s, 0.0, c, 1.0, 2.0, 3.0]);
        let fwd = m.transform_vector3(Vec3::NEG_Z);
        assert!((fwd - Vec3::NEG_X).length() < 1e-6, "{fwd}");
        let p = m.transform_point3(Vec3::new(0.0, 0.0, -1.0));
        assert!((p - Vec3::new(0.0, 2.0, 3.0)).length() < 1e-6, "{p}");
        // An unnormalised quaternion is normalised, not a scale.
        let m2 = pose_from_raw([0.0, 2.0 * s, 0.0, 2.0 * c, 0.0, 0.0, 0.0]);
        assert!((m2.transform_vector3(Vec3::X).length() - 1.0).abs() < 1e-6);
    }

    /// glFrustum (OpenGL red book) for the given planes: the independent reference.
    fn gl_frustum(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> DMat4 {
        DMat4::from_cols_array(&[
            2.0 * n / (r - l),
            0.0,
            0.0,
            0.0, //
            0.0,
            2.0 * n / (t - b),
            0.0,
            0.0, //
            (r + l) / (r - l),
            (t + b) / (t - b),
            -(f + n) / (f - n),
            -1.0, //
            0.0,
            0.0,
            -2.0 * f * n / (f - n),
            0.0,
        ])
    }

    #[test]
    fn gl_projection_becomes_the_intrinsics_projection() {
        // A camera with an off-centre principal point, like ARCore's.
        let k = Intrinsics {
            fx: 1500.0,
            fy: 1490.0,
            cx: 530.0,
            cy: 970.0,
            width: 1080,
            height: 1920,
        };
        let (n, f) = (0.05, 100.0);
        // Frustum planes at the near plane from the pixel geometry (v down, y up).
        let l = -k.cx / k.fx * n;
        let r = (f64::from(k.width) - k.cx) / k.fx * n;
        let t = k.cy / k.fy * n;
        let b = -(f64::from(k.height) - k.cy) / k.fy * n;
        let gl = gl_frustum(l, r, b, t, n, f);
        let ours = gl_projection_to_wgpu(gl);
        let reference = k.projection_wgpu(n, f);
        for (a, b) in ours.to_cols_array().iter().zip(reference.to_cols_array()) {
            assert!((a - b).abs() < 1e-9, "{ours} vs {reference}");
        }
        let back = intrinsics_from_projection(gl, k.width, k.height);
        for (a, b) in [
            (back.fx, k.fx),
            (back.fy, k.fy),
            (back.cx, k.cx),
            (back.cy, k.cy),
        ] {
            assert!((a - b).abs() < 1e-9, "{back:?}");
        }
        // Depth: near → 0, far → 1 after the remap.
        for (z, want) in [(-n, 0.0), (-f, 1.0)] {
            let c = ours * glam::DVec4::new(0.0, 0.0, z, 1.0);
            assert!((c.z / c.w - want).abs() < 1e-12);
        }
    }

    #[test]
    fn placement_maps_race_east_to_the_turned_table_axis() {
        let p = CoursePlacement {
            anchor: DVec3::new(0.2, -0.7, -0.5),
            yaw: FRAC_PI_2,
            course_to_table: 0.01,
        };
        // 100 m east (race +x) turned 90° ccw about y → AR −z, at 1 m on the table.
        let q = p.race_to_ar().transform_point3(DVec3::new(100.0, 0.0, 0.0));
        assert!((q - DVec3::new(0.2, -0.7, -1.5)).length() < 1e-12, "{q}");
        // Up stays up (scaled): a 10 m mast is 10 cm tall.
        let top = p.race_to_ar().transform_point3(DVec3::new(0.0, 10.0, 0.0));
        assert!((top - DVec3::new(0.2, -0.6, -0.5)).length() < 1e-12);
        let back = p.ar_to_race().transform_point3(q);
        assert!((back - DVec3::new(100.0, 0.0, 0.0)).length() < 1e-9);
    }

    #[test]
    fn put_and_gestures_about_a_pivot_keep_the_pivot_on_the_table() {
        let mut p = CoursePlacement {
            anchor: DVec3::ZERO,
            yaw: 0.7,
            course_to_table: 1.0 / 2000.0,
        };
        let centre = DVec3::new(800.0, -30.0, -500.0);
        let tap = DVec3::new(0.2, 0.75, -0.4);
        p.put(centre, tap);
        assert!((p.race_to_ar().transform_point3(centre) - tap).length() < 1e-12);
        // A point 2000 race metres east of the centre is 1 AR metre away, turned by the yaw
        // (counter-clockwise from above: east (+x) turns towards north (−z)).
        let east = p.race_to_ar().transform_point3(centre + DVec3::X * 2000.0) - tap;
        assert!((east - DVec3::new(0.7f64.cos(), 0.0, -0.7f64.sin())).length() < 1e-12);
        p.apply_gesture_about(centre, 2.0, FRAC_PI_2);
        assert!((p.race_to_ar().transform_point3(centre) - tap).length() < 1e-12);
        assert!((p.course_to_table - 1.0 / 1000.0).abs() < 1e-15);
        assert!((p.yaw - (0.7 + FRAC_PI_2)).abs() < 1e-12);
    }

    #[test]
    fn gestures_scale_and_turn_within_bounds() {
        let mut p = CoursePlacement {
            anchor: DVec3::ZERO,
            yaw: 0.0,
            course_to_table: 0.001,
        };
        p.apply_gesture(2.0, FRAC_PI_2);
        assert!((p.course_to_table - 0.002).abs() < 1e-15);
        assert!((p.yaw - FRAC_PI_2).abs() < 1e-15);
        p.apply_gesture(1e9, -std::f64::consts::PI);
        assert_eq!(p.course_to_table, 1.0);
        assert!((p.yaw - 1.5 * std::f64::consts::PI).abs() < 1e-12);
        p.apply_gesture(f64::NAN, f64::INFINITY);
        assert_eq!(p.course_to_table, 1.0);
        let _ = DVec2::ZERO;
    }
}
