//! The camera: a pinhole looking from `eye` at `target` with `up` towards the top of the image,
//! in world metres (f64), and the
//! view-projection that shaders get in *local* metres (world minus the frame's origin), so the
//! matrix never holds a large coordinate. [`OrbitCamera`] is the desktop app's mouse camera.

use glam::{DMat4, DVec2, DVec3, DVec4};

/// A perspective camera in world metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position, world metres.
    pub eye: DVec3,
    /// The point looked at, world metres.
    pub target: DVec3,
    /// The direction that is up in the image (world axes; need not be unit nor perpendicular
    /// to the viewing direction, only not along it). World y ([`DVec3::Y`]) for the orbit
    /// and desktop cameras; a phone held at an angle rolls it about the viewing axis.
    pub up: DVec3,
    /// Vertical field of view, radians.
    pub fov_y: f64,
    /// Near and far clip distances, metres.
    pub near: f64,
    pub far: f64,
}

impl Camera {
    /// Looking from `eye` at `target` with a 55° vertical field of view; the far plane reaches
    /// `far` metres.
    pub fn look_at(eye: DVec3, target: DVec3, far: f64) -> Camera {
        Camera {
            eye,
            target,
            up: DVec3::Y,
            fov_y: 55f64.to_radians(),
            near: (eye.y.abs() * 0.02).clamp(0.05, 2.0),
            far,
        }
    }

    /// The camera of a view matrix (world to camera, camera looking down −z, y up) and an
    /// OpenGL projection (clip z in −w..w, e.g. ARCore's `ArCamera_getProjectionMatrix`).
    ///
    /// `view` may scale uniformly (a race world placed on a table: race metres in, AR metres
    /// out); near and far come back in the world's metres. The camera's roll is kept (`up` is
    /// the view's y axis in the world), so [`Camera::view_local`] gives `view` back (scale
    /// removed). What [`Camera`] cannot hold is lost: an off-centre principal point (ARCore's
    /// is within about 1 % of the image centre); the vertical field of view is the
    /// projection's, the aspect is the viewport's at draw time.
    pub fn from_view_projection(view: DMat4, projection_gl: DMat4) -> Camera {
        let to_world = view.inverse();
        let eye = to_world.transform_point3(DVec3::ZERO);
        let forward = to_world.transform_vector3(DVec3::NEG_Z).normalize();
        let up = to_world.transform_vector3(DVec3::Y).normalize();
        // Camera metres per world metre.
        let scale = view.x_axis.truncate().length();
        // OpenGL perspective: m22 = −(f + n)/(f − n), m32 = −2 f n/(f − n).
        let (m22, m32) = (projection_gl.z_axis.z, projection_gl.w_axis.z);
        Camera {
            eye,
            target: eye + forward,
            up,
            fov_y: 2.0 * (1.0 / projection_gl.y_axis.y).atan(),
            near: m32 / (m22 - 1.0) / scale,
            far: m32 / (m22 + 1.0) / scale,
        }
    }

    /// World-to-clip matrix for points given relative to `origin` (x, z) on the sea level,
    /// in f64; wgpu depth range [0, 1].
    pub fn view_proj_local(&self, origin: DVec2, aspect: f64) -> DMat4 {
        // wgpu's clip space is Direct3D's: depth in [0, 1], y up.
        glam::dcamera::rh::proj::directx::perspective(self.fov_y, aspect, self.near, self.far)
            * self.view_local(origin)
    }

    /// World-to-camera matrix (camera looking down −z, `up` towards +y) for points given
    /// relative to `origin` (x, z) on the sea level; every pass that builds a view from this
    /// camera should take it from here, so roll is never dropped.
    pub fn view_local(&self, origin: DVec2) -> DMat4 {
        let o = DVec3::new(origin.x, 0.0, origin.y);
        glam::dcamera::rh::view::look_at_mat4(self.eye - o, self.target - o, self.up)
    }

    /// Pixels per metre of something at distance `d` metres, facing the camera, on a viewport
    /// `height` pixels tall.
    pub(crate) fn pixels_per_metre(&self, d: f64, height: u32) -> f64 {
        f64::from(height) / (2.0 * d.max(1e-6) * (self.fov_y / 2.0).tan())
    }
}

/// The six planes of a view frustum, each (a, b, c, d) with a·x + b·y + c·z + d ≥ 0 inside,
/// in the same local coordinates as the matrix it came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frustum {
    pub planes: [DVec4; 6],
}

impl Frustum {
    /// Gribb–Hartmann extraction from a view-projection with depth range [0, 1].
    pub(crate) fn from_matrix(m: DMat4) -> Frustum {
        let r = [m.row(0), m.row(1), m.row(2), m.row(3)];
        let planes = [
            r[3] + r[0],
            r[3] - r[0],
            r[3] + r[1],
            r[3] - r[1],
            r[2],
            r[3] - r[2],
        ];
        Frustum {
            planes: planes.map(|p| p / p.truncate().length()),
        }
    }

    /// False when the axis-aligned box [lo, hi] lies entirely outside one plane (conservative:
    /// a box that is reported visible may still be off screen).
    pub(crate) fn intersects_box(&self, lo: DVec3, hi: DVec3) -> bool {
        self.planes.iter().all(|p| {
            // The box corner furthest along the plane's normal.
            let c = DVec3::new(
                if p.x >= 0.0 { hi.x } else { lo.x },
                if p.y >= 0.0 { hi.y } else { lo.y },
                if p.z >= 0.0 { hi.z } else { lo.z },
            );
            p.truncate().dot(c) + p.w >= 0.0
        })
    }
}

/// A camera orbiting a target point: mouse drag turns it, the wheel zooms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    /// The point orbited, world metres.
    pub target: DVec3,
    /// Distance from the target, metres.
    pub distance: f64,
    /// Compass bearing from the target to the eye, radians (0 = the eye is north of it).
    pub yaw: f64,
    /// Elevation of the eye above the target's horizon, radians, in [2°, 89°].
    pub pitch: f64,
    /// Far clip distance, metres.
    pub far: f64,
}

impl OrbitCamera {
    pub(crate) const MIN_PITCH: f64 = 2.0 * std::f64::consts::PI / 180.0;
    pub(crate) const MAX_PITCH: f64 = 89.0 * std::f64::consts::PI / 180.0;

    pub fn camera(&self) -> Camera {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        // North is −z; east is +x.
        let dir = DVec3::new(sy * cp, sp, -cy * cp);
        Camera::look_at(self.target + dir * self.distance, self.target, self.far)
    }

    /// Turn by a mouse drag of (dx, dy) pixels.
    pub fn drag(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * 0.005;
        self.pitch = (self.pitch + dy * 0.005).clamp(Self::MIN_PITCH, Self::MAX_PITCH);
    }

    /// Zoom by `steps` wheel notches (positive = closer).
    pub fn zoom(&mut self, steps: f64) {
        self.distance = (self.distance * 0.9f64.powf(steps)).clamp(3.0, 5000.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frustum_keeps_what_is_ahead_and_drops_what_is_behind() {
        let cam = Camera::look_at(
            DVec3::new(0.0, 10.0, 0.0),
            DVec3::new(0.0, 0.0, -100.0),
            1e4,
        );
        let f = Frustum::from_matrix(cam.view_proj_local(DVec2::ZERO, 1.5));
        let ahead = (DVec3::new(-5.0, -1.0, -60.0), DVec3::new(5.0, 1.0, -50.0));
        let behind = (DVec3::new(-5.0, -1.0, 50.0), DVec3::new(5.0, 1.0, 60.0));
        assert!(f.intersects_box(ahead.0, ahead.1));
        assert!(!f.intersects_box(behind.0, behind.1));
        // The target projects to the screen centre.
        let c = cam.view_proj_local(DVec2::ZERO, 1.5) * DVec4::new(0.0, 0.0, -100.0, 1.0);
        assert!((c.x / c.w).abs() < 1e-9 && (c.y / c.w).abs() < 1e-9);
    }

    /// A view and a GL projection built by glam give back a camera whose view-projection puts
    /// every point where glam's own matrices (depth remapped to wgpu's 0..1) put it, also when
    /// the view scales the world (a course on a table).
    #[test]
    fn camera_from_view_and_gl_projection_matches_glam() {
        let eye = DVec3::new(3.0, 2.0, 5.0);
        let target = DVec3::new(-1.0, 0.5, -2.0);
        let aspect = 0.5;
        let view = glam::dcamera::rh::view::look_at_mat4(eye, target, DVec3::Y);
        let proj = glam::dcamera::rh::proj::opengl::perspective(1.1, aspect, 0.1, 50.0);
        // z' = (z + w)/2: GL clip depth to wgpu's.
        let gl_to_wgpu = DMat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.5, 1.0,
        ]);
        for s in [1.0, 1.0 / 2000.0] {
            // World metres → view metres scaled by s: the camera sits at eye / s in the world.
            let scaled_view = view * DMat4::from_scale(DVec3::splat(s));
            let cam = Camera::from_view_projection(scaled_view, proj);
            assert!((cam.eye - eye / s).length() < 1e-9 / s);
            assert!((cam.near - 0.1 / s).abs() < 1e-9 / s && (cam.far - 50.0 / s).abs() < 1e-6 / s);
            assert!((cam.fov_y - 1.1).abs() < 1e-12);
            let ours = cam.view_proj_local(DVec2::ZERO, aspect);
            let theirs = gl_to_wgpu * proj * scaled_view;
            for p in [
                target / s,
                DVec3::new(0.5, 0.0, 0.0) / s,
                DVec3::new(-2.0, 1.0, -4.0) / s,
            ] {
                let a = ours * p.extend(1.0);
                let b = theirs * p.extend(1.0);
                let (a, b) = (a.truncate() / a.w, b.truncate() / b.w);
                assert!((a - b).length() < 1e-9, "{p}: {a} vs {b}");
            }
        }
    }

    /// A phone pose rolled 30° about its viewing axis (after a yaw and a downward pitch): the
    /// camera made from its view matrix (the pose's inverse, as `ArCamera_getViewMatrix`
    /// gives it) has that same view matrix, so the rolled image is drawn rolled; and a point
    /// on the camera's rolled x axis projects onto the screen's horizontal centre line.
    #[test]
    fn a_rolled_pose_keeps_its_roll() {
        let roll = 30f64.to_radians();
        let rot = glam::DQuat::from_rotation_y(0.7)
            * glam::DQuat::from_rotation_x(-0.5)
            * glam::DQuat::from_rotation_z(roll);
        let pose = DMat4::from_rotation_translation(rot, DVec3::new(0.4, 1.2, -0.3));
        let view = pose.inverse();
        let proj = glam::dcamera::rh::proj::opengl::perspective(1.0, 0.5, 0.01, 100.0);
        let cam = Camera::from_view_projection(view, proj);
        let ours = cam.view_local(DVec2::ZERO);
        for (a, b) in ours.to_cols_array().iter().zip(view.to_cols_array()) {
            assert!((a - b).abs() < 1e-9, "{ours} vs {view}");
        }
        // The image's up is the pose's y axis, 30° off world y about the viewing direction.
        let level_up = (DVec3::Y - rot * DVec3::NEG_Z * (rot * DVec3::NEG_Z).y).normalize();
        assert!((cam.up.angle_between(level_up) - roll).abs() < 1e-9);
        // One metre along the pose's own x axis, 2 m ahead: on screen it stays at ndc y = 0.
        let p = pose.transform_point3(DVec3::new(1.0, 0.0, -2.0));
        let c = cam.view_proj_local(DVec2::ZERO, 0.5) * p.extend(1.0);
        assert!((c.y / c.w).abs() < 1e-9 && c.x / c.w > 0.1);
        // Without roll information, world y stays up.
        assert_eq!(Camera::look_at(DVec3::ONE, DVec3::ZERO, 10.0).up, DVec3::Y);
    }

    #[test]
    fn orbit_eye_is_at_distance_and_bearing() {
        let o = OrbitCamera {
            target: DVec3::new(10.0, 0.0, 20.0),
            distance: 50.0,
            yaw: std::f64::consts::FRAC_PI_2,
            pitch: 0.3,
            far: 1e4,
        };
        let c = o.camera();
        assert!(((c.eye - o.target).length() - 50.0).abs() < 1e-9);
        // Bearing 90°: the eye is east (+x) of the target.
        assert!(c.eye.x > o.target.x + 40.0 && (c.eye.z - o.target.z).abs() < 1e-9);
    }
}
