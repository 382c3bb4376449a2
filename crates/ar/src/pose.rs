//! Camera poses in f64 and the text form `tx ty tz qx qy qz qw` that replay folders and TUM
//! RGB-D files share.

use std::path::Path;

use glam::{DMat4, DQuat, DVec3, Mat4};

use crate::ArError;

/// A rigid camera-to-world pose in f64: rotate by `rotation`, then translate by `position`
/// (metres). Kept in f64 so a replay written and read back reproduces it exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub position: DVec3,
    /// Unit quaternion.
    pub rotation: DQuat,
}

/// How far a quaternion's norm may be from 1 before it is refused as malformed: recorders write
/// 4–6 decimals, so a genuine unit quaternion is within about 1e-4 of unit norm.
pub const QUAT_NORM_TOLERANCE: f64 = 1e-2;

impl Pose {
    pub const IDENTITY: Pose = Pose {
        position: DVec3::ZERO,
        rotation: DQuat::IDENTITY,
    };

    /// The camera at `eye` looking at `target`, with `up` as the approximate up direction
    /// (camera convention of [`crate::CameraFrame`]: looking down -z, y up).
    pub fn look_at(eye: DVec3, target: DVec3, up: DVec3) -> Pose {
        let back = (eye - target).normalize();
        let right = up.cross(back).normalize();
        let true_up = back.cross(right);
        let m = glam::DMat3::from_cols(right, true_up, back);
        Pose {
            position: eye,
            rotation: DQuat::from_mat3(&m).normalize(),
        }
    }

    pub fn to_dmat4(&self) -> DMat4 {
        DMat4::from_rotation_translation(self.rotation, self.position)
    }

    pub fn to_mat4(&self) -> Mat4 {
        self.to_dmat4().as_mat4()
    }

    /// The pose of a rigid transform (scale is dropped).
    pub fn from_mat4(m: Mat4) -> Pose {
        let (_, rotation, position) = m.as_dmat4().to_scale_rotation_translation();
        Pose {
            position,
            rotation: rotation.normalize(),
        }
    }

    /// Converts a pose whose camera looks down +z with y down (OpenCV, TUM RGB-D) to the
    /// crate's convention (looking down -z, y up): a half turn about the camera's x axis.
    pub fn from_opencv(p: Pose) -> Pose {
        Pose {
            position: p.position,
            rotation: (p.rotation * DQuat::from_xyzw(1.0, 0.0, 0.0, 0.0)).normalize(),
        }
    }

    /// Inverse of [`Pose::from_opencv`].
    pub fn to_opencv(self) -> Pose {
        Self::from_opencv(self)
    }

    /// `tx ty tz qx qy qz qw` with shortest round-trip formatting, so parsing gives the same f64s.
    pub fn to_text(&self) -> String {
        let (p, q) = (self.position, self.rotation);
        format!("{} {} {} {} {} {} {}", p.x, p.y, p.z, q.x, q.y, q.z, q.w)
    }

    /// Parses the seven fields `tx ty tz qx qy qz qw`. Refuses a wrong field count, a field that
    /// is not a finite number, or a quaternion whose norm is not within
    /// [`QUAT_NORM_TOLERANCE`] of 1; a quaternion within it is normalised (exactly-unit input is
    /// kept bit for bit).
    pub fn parse_fields(fields: &[&str], path: &Path, line: usize) -> Result<Pose, ArError> {
        if fields.len() != 7 {
            return Err(ArError::at_line(
                path,
                line,
                format!(
                    "a pose needs 7 numbers `tx ty tz qx qy qz qw`, found {}",
                    fields.len()
                ),
            ));
        }
        let mut v = [0.0f64; 7];
        for (k, f) in fields.iter().enumerate() {
            v[k] = parse_finite(f, path, line, POSE_FIELD_NAMES[k])?;
        }
        let q = DQuat::from_xyzw(v[3], v[4], v[5], v[6]);
        let norm = q.length();
        if (norm - 1.0).abs() > QUAT_NORM_TOLERANCE {
            return Err(ArError::at_line(
                path,
                line,
                format!("the rotation quaternion has norm {norm}, not 1"),
            ));
        }
        Ok(Pose {
            position: DVec3::new(v[0], v[1], v[2]),
            // Within rounding of unit norm the quaternion is kept as written, so a written and
            // re-read pose is bit-identical.
            rotation: if (norm - 1.0).abs() <= 1e-12 {
                q
            } else {
                q / norm
            },
        })
    }
}

const POSE_FIELD_NAMES: [&str; 7] = ["tx", "ty", "tz", "qx", "qy", "qz", "qw"];

/// Parses one finite f64, naming the field on failure.
pub(crate) fn parse_finite(s: &str, path: &Path, line: usize, name: &str) -> Result<f64, ArError> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(ArError::at_line(
            path,
            line,
            format!("{name} is `{s}`, not a finite number"),
        )),
    }
}
