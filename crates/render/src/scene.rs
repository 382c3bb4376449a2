//! What the renderer draws: the sea at a race time, the boats and marks, the sun, the play area
//! and the camera. Plain data in world metres (f64); the renderer turns it into local f32.
//! Callers fill boats from the race model (the app does); the renderer knows no race type.

use glam::{DMat4, DQuat, DVec2, DVec3};
use ocean::WaveSet;

use crate::camera::Camera;

/// One boat at the frame's race time.
#[derive(Debug, Clone, PartialEq)]
pub struct Boat {
    /// World (x, z), metres.
    pub position: DVec2,
    /// Compass bearing of the bow, radians (0 = north = −z, π/2 = east = +x).
    pub heading: f64,
    /// Linear RGB, 0..1.
    pub colour: [f32; 3],
    /// Hull length, metres.
    pub length: f64,
}

/// A course mark (a buoy) at world (x, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mark {
    pub position: DVec2,
}

/// Everything one frame shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Race time, seconds since the start (f64; reduced on the CPU before any shader).
    pub t: f64,
    /// Shared, not copied: a frame hands the same wave set to every pass.
    pub sea: std::sync::Arc<WaveSet>,
    pub boats: Vec<Boat>,
    pub marks: Vec<Mark>,
    /// Water is drawn only inside this rectangle: min x, min z, max x, max z (world metres).
    pub play_area: [f64; 4],
    /// Unit vector towards the sun.
    pub sun: DVec3,
    pub camera: Camera,
}

/// How far above the sea surface under it a camera is kept, metres.
pub const CAMERA_CLEARANCE_M: f64 = 0.2;

impl Scene {
    /// This scene with its camera raised to [`CAMERA_CLEARANCE_M`] above the sea surface under
    /// the eye, where it is lower, and by how many metres; `None` when the eye is above it.
    /// Eye and target move together, so the view's direction stays.
    ///
    /// Why raise rather than draw: the water is shaded from above only (reflection of the sky,
    /// light from the water body) and the sky fills everything behind it, so from under the
    /// surface the picture would be sky below the horizon and the surface's underside shaded
    /// as if lit from above: nonsense. A race viewer has no under-water view to offer, and an
    /// orbit or AR camera that dips through the surface is better stopped at it than refused.
    pub fn camera_above_water(&self) -> Option<(Scene, f64)> {
        let eye = self.camera.eye;
        // Without a converged inverse (a sea the validator should have refused), the highest
        // crest any wave could make.
        let surface = self
            .sea
            .height_at([eye.x, eye.z], self.t)
            .unwrap_or_else(|_| self.sea.total_amplitude());
        let lift = surface + CAMERA_CLEARANCE_M - eye.y;
        (lift > 0.0).then(|| {
            let mut s = self.clone();
            s.camera.eye.y += lift;
            s.camera.target.y += lift;
            (s, lift)
        })
    }

    /// A play area around `points` (boat tracks, marks) with `margin` metres on every side.
    pub fn play_area_around(points: impl IntoIterator<Item = DVec2>, margin: f64) -> [f64; 4] {
        let (mut lo, mut hi) = (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN));
        for p in points {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if lo.x > hi.x {
            (lo, hi) = (DVec2::ZERO, DVec2::ZERO);
        }
        [lo.x - margin, lo.y - margin, hi.x + margin, hi.y + margin]
    }

    /// The default sun: 35° up, from the south-west, lighting the waves' faces.
    pub fn default_sun() -> DVec3 {
        DVec3::new(-0.55, 0.57, 0.6).normalize()
    }

    /// A camera that frames the boats and marks from the south-east and above.
    pub fn framing_camera(boats: &[Boat], marks: &[Mark], far: f64) -> Camera {
        let pts: Vec<DVec2> = boats
            .iter()
            .map(|b| b.position)
            .chain(marks.iter().map(|m| m.position))
            .collect();
        let [x0, z0, x1, z1] = Scene::play_area_around(pts, 0.0);
        let centre = DVec2::new(x0 + x1, z0 + z1) / 2.0;
        let radius = (DVec2::new(x1 - x0, z1 - z0).length() / 2.0).max(30.0);
        let eye = DVec3::new(
            centre.x + radius * 0.7,
            radius * 0.45,
            centre.y + radius * 1.1,
        );
        Camera::look_at(eye, DVec3::new(centre.x, 0.0, centre.y), far)
    }
}

/// How a floating body sits on the sea: its height and attitude from the surface under it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloatPose {
    /// Height of the waterline above the rest level, metres.
    pub height: f64,
    /// Bow-up angle, radians.
    pub pitch: f64,
    /// Starboard-up angle, radians.
    pub roll: f64,
}

/// The pose of a hull `length` × `beam` metres at world `position` heading `heading` (compass,
/// radians) on `sea` at time `t`: height is the mean of the sea at bow, stern, port and
/// starboard; pitch and roll are the slopes between them. Heights come from ocean's inverse
/// (the sea at a world point); where it does not converge the body sits at rest level.
pub fn float_pose(
    sea: &WaveSet,
    t: f64,
    position: DVec2,
    heading: f64,
    length: f64,
    beam: f64,
) -> FloatPose {
    let fwd = DVec2::new(heading.sin(), -heading.cos());
    let stbd = DVec2::new(-fwd.y, fwd.x);
    let h = |p: DVec2| {
        sea.height_at([p.x, p.y], t).unwrap_or_else(|e| {
            log::warn!("float height at ({:.1}, {:.1}): {e}", p.x, p.y);
            0.0
        })
    };
    let bow = h(position + fwd * length / 2.0);
    let stern = h(position - fwd * length / 2.0);
    let port = h(position - stbd * beam / 2.0);
    let starboard = h(position + stbd * beam / 2.0);
    FloatPose {
        height: (bow + stern + port + starboard) / 4.0,
        pitch: (bow - stern).atan2(length),
        roll: (starboard - port).atan2(beam),
    }
}

/// Model matrix (local metres, relative to `origin`) of a body whose model space has the bow
/// along −z, starboard +x, up +y.
pub fn float_matrix(position: DVec2, heading: f64, pose: &FloatPose, origin: DVec2) -> DMat4 {
    let p = position - origin;
    DMat4::from_rotation_translation(
        DQuat::from_rotation_y(-heading)
            * DQuat::from_rotation_x(pose.pitch)
            * DQuat::from_rotation_z(pose.roll),
        DVec3::new(p.x, pose.height, p.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean::Wave;

    fn one_wave() -> WaveSet {
        WaveSet {
            gravity: 9.81,
            depth: None,
            waves: vec![Wave {
                direction: [1.0, 0.0],
                steepness: 0.2,
                wavelength: 40.0,
                phase: 0.0,
            }],
        }
    }

    #[test]
    fn a_hull_across_a_wave_slope_pitches_with_it() {
        // A boat heading east on an eastward wave: bow and stern straddle the slope.
        let sea = one_wave();
        let t = 3.0;
        let x = 7.0;
        let pose = float_pose(
            &sea,
            t,
            DVec2::new(x, 0.0),
            std::f64::consts::FRAC_PI_2,
            4.0,
            1.5,
        );
        let bow = sea.height_at([x + 2.0, 0.0], t).unwrap();
        let stern = sea.height_at([x - 2.0, 0.0], t).unwrap();
        assert!((pose.pitch - (bow - stern).atan2(4.0)).abs() < 1e-12);
        assert!(
            pose.pitch.abs() > 0.01,
            "the test point should be on a slope"
        );
        // Port and starboard see the same height on a wave along x: no roll.
        assert!(pose.roll.abs() < 1e-9);
        // The model matrix puts the bow where the heading points (east).
        let m = float_matrix(
            DVec2::new(x, 0.0),
            std::f64::consts::FRAC_PI_2,
            &pose,
            DVec2::ZERO,
        );
        let bow_pt = m.transform_point3(DVec3::new(0.0, 0.0, -2.0));
        assert!(bow_pt.x > x + 1.9 && bow_pt.z.abs() < 1e-9);
    }
}
