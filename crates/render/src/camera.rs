//! The camera: a pinhole looking from `eye` at `target`, in world metres (f64), and the
//! view-projection that shaders get in *local* metres (world minus the frame's origin), so the
//! matrix never holds a large coordinate. [`OrbitCamera`] is the desktop app's mouse camera.

use glam::{DMat4, DVec2, DVec3, DVec4, Mat4};

/// A perspective camera in world metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position, world metres.
    pub eye: DVec3,
    /// The point looked at, world metres.
    pub target: DVec3,
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
            fov_y: 55f64.to_radians(),
            near: (eye.y.abs() * 0.02).clamp(0.05, 2.0),
            far,
        }
    }

    /// World-to-clip matrix for points given relative to `origin` (x, z) on the sea level,
    /// in f64; wgpu depth range [0, 1].
    pub fn view_proj_local(&self, origin: DVec2, aspect: f64) -> DMat4 {
        let o = DVec3::new(origin.x, 0.0, origin.y);
        let view = glam::dcamera::rh::view::look_at_mat4(self.eye - o, self.target - o, DVec3::Y);
        // wgpu's clip space is Direct3D's: depth in [0, 1], y up.
        glam::dcamera::rh::proj::directx::perspective(self.fov_y, aspect, self.near, self.far)
            * view
    }

    /// The same matrix in f32 for a shader (every entry is a local, small number).
    pub fn view_proj_local_f32(&self, origin: DVec2, aspect: f64) -> Mat4 {
        self.view_proj_local(origin, aspect).as_mat4()
    }

    /// Pixels per metre of something at distance `d` metres, facing the camera, on a viewport
    /// `height` pixels tall.
    pub fn pixels_per_metre(&self, d: f64, height: u32) -> f64 {
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
    pub fn from_matrix(m: DMat4) -> Frustum {
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
    pub fn intersects_box(&self, lo: DVec3, hi: DVec3) -> bool {
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
    pub const MIN_PITCH: f64 = 2.0 * std::f64::consts::PI / 180.0;
    pub const MAX_PITCH: f64 = 89.0 * std::f64::consts::PI / 180.0;

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
