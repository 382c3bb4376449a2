//! The display rotation transform: which camera-image UV shows at each screen UV, for the
//! phone's rotation and the view's aspect (the image fills the view and is cropped, centred).
//! On the phone ARCore computes this (`ArFrame_transformCoordinates2d`, from
//! `VIEW_NORMALIZED` to `IMAGE_NORMALIZED`) for three points and [`affine_from_three`] fits
//! the map; [`display_uv_transform`] is the same map from first principles, used where ARCore
//! is absent (recordings) and to test the fit.

use glam::{Affine2, DAffine2, DMat2, DVec2, Vec2};

/// `android.view.Surface.ROTATION_*`: how far the display is turned from the device's natural
/// orientation, counter-clockwise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DisplayRotation {
    R0,
    R90,
    R180,
    R270,
}

impl DisplayRotation {
    /// From `Display.getRotation()` (0..=3); `None` for anything else.
    pub fn from_surface(value: i32) -> Option<Self> {
        Some(match value {
            0 => Self::R0,
            1 => Self::R90,
            2 => Self::R180,
            3 => Self::R270,
            _ => return None,
        })
    }

    pub fn degrees(self) -> u32 {
        match self {
            Self::R0 => 0,
            Self::R90 => 90,
            Self::R180 => 180,
            Self::R270 => 270,
        }
    }
}

/// Maps a screen UV (0..1, origin top-left) to the image UV (0..1, origin top-left of the
/// sensor image) shown there, for a back camera whose sensor is mounted `sensor_orientation`
/// degrees clockwise (`CameraCharacteristics.SENSOR_ORIENTATION`, 90 on most phones), with the
/// image filling the view `view` (pixels, as displayed) and cropped evenly.
pub fn display_uv_transform(
    sensor_orientation: u32,
    rotation: DisplayRotation,
    image: (u32, u32),
    view: (u32, u32),
) -> Affine2 {
    // Clockwise turn from the sensor image to the screen (Android's camera orientation rule
    // for back cameras: (sensor − display + 360) mod 360).
    let turn = (sensor_orientation + 360 - rotation.degrees()) % 360;
    let (iw, ih) = (f64::from(image.0.max(1)), f64::from(image.1.max(1)));
    // The image as it appears on screen, before cropping.
    let (rw, rh) = if turn.is_multiple_of(180) {
        (iw, ih)
    } else {
        (ih, iw)
    };
    let (vw, vh) = (f64::from(view.0.max(1)), f64::from(view.1.max(1)));
    let scale = (vw / rw).max(vh / rh);
    let visible = DVec2::new(vw / scale / rw, vh / scale / rh);
    // Screen UV → UV in the turned (screen-aligned) image: centred crop.
    let crop =
        DAffine2::from_scale_angle_translation(visible, 0.0, DVec2::splat(0.5) - 0.5 * visible);
    // Turned image UV (u, v) → sensor image UV for a clockwise turn on display.
    let unturn = match turn {
        0 => DAffine2::IDENTITY,
        90 => DAffine2::from_mat2_translation(
            DMat2::from_cols(DVec2::new(0.0, -1.0), DVec2::new(1.0, 0.0)),
            DVec2::new(0.0, 1.0),
        ),
        180 => {
            DAffine2::from_mat2_translation(DMat2::from_diagonal(DVec2::splat(-1.0)), DVec2::ONE)
        }
        _ => DAffine2::from_mat2_translation(
            DMat2::from_cols(DVec2::new(0.0, 1.0), DVec2::new(-1.0, 0.0)),
            DVec2::new(1.0, 0.0),
        ),
    };
    let m = unturn * crop;
    Affine2::from_mat2_translation(m.matrix2.as_mat2(), m.translation.as_vec2())
}

/// The affine map taking `from[k]` to `to[k]` for three points (ARCore's transformed screen
/// corners); `None` when the three `from` points are collinear.
pub fn affine_from_three(from: [Vec2; 3], to: [Vec2; 3]) -> Option<Affine2> {
    let f = from.map(|p| p.as_dvec2());
    let t = to.map(|p| p.as_dvec2());
    let a = DMat2::from_cols(f[1] - f[0], f[2] - f[0]);
    if a.determinant().abs() < 1e-12 {
        return None;
    }
    let b = DMat2::from_cols(t[1] - t[0], t[2] - t[0]);
    let m = b * a.inverse();
    let translation = t[0] - m * f[0];
    Some(Affine2::from_mat2_translation(
        m.as_mat2(),
        translation.as_vec2(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn portrait_phone_shows_the_landscape_sensor_turned_clockwise() {
        // Sensor 90°, portrait (R0), a 4:3 image on a 3:4 view: no crop, pure turn. The screen's
        // top-left shows the image's bottom-left, the top-right the image's top-left.
        let m = display_uv_transform(90, DisplayRotation::R0, (640, 480), (480, 640));
        assert!(close(
            m.transform_point2(Vec2::new(0.0, 0.0)),
            Vec2::new(0.0, 1.0)
        ));
        assert!(close(
            m.transform_point2(Vec2::new(1.0, 0.0)),
            Vec2::new(0.0, 0.0)
        ));
        assert!(close(
            m.transform_point2(Vec2::new(1.0, 1.0)),
            Vec2::new(1.0, 0.0)
        ));
        // Landscape with the top on the left (R90): the sensor is upright on screen.
        let m = display_uv_transform(90, DisplayRotation::R90, (640, 480), (640, 480));
        assert!(close(
            m.transform_point2(Vec2::new(0.25, 0.75)),
            Vec2::new(0.25, 0.75)
        ));
        // R270: upside down relative to the sensor.
        let m = display_uv_transform(90, DisplayRotation::R270, (640, 480), (640, 480));
        assert!(close(
            m.transform_point2(Vec2::new(0.25, 0.75)),
            Vec2::new(0.75, 0.25)
        ));
    }

    #[test]
    fn a_taller_view_crops_the_image_sides_evenly() {
        // 4:3 sensor turned to portrait (3:4) shown on a 9:19.5 phone: full height, cropped
        // width. Visible image fraction along the screen's x: (9/19.5) / (3/4).
        let m = display_uv_transform(90, DisplayRotation::R0, (640, 480), (1080, 2340));
        let frac = (1080.0 / 2340.0) / (480.0 / 640.0);
        // Screen x runs along the image's −v after the turn; the centre stays the centre.
        assert!(close(
            m.transform_point2(Vec2::splat(0.5)),
            Vec2::splat(0.5)
        ));
        let left = m.transform_point2(Vec2::new(0.0, 0.5));
        assert!(
            close(left, Vec2::new(0.5, 0.5 + 0.5 * frac as f32)),
            "{left}"
        );
        let top = m.transform_point2(Vec2::new(0.5, 0.0));
        assert!(close(top, Vec2::new(0.0, 0.5)), "{top}");
    }

    #[test]
    fn fitting_three_transformed_points_recovers_the_map() {
        let truth = display_uv_transform(90, DisplayRotation::R0, (1920, 1080), (1080, 2400));
        let from = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
        ];
        let to = from.map(|p| truth.transform_point2(p));
        let fit = affine_from_three(from, to).unwrap();
        for p in [Vec2::new(0.3, 0.9), Vec2::new(1.0, 1.0)] {
            assert!(close(fit.transform_point2(p), truth.transform_point2(p)));
        }
        assert!(affine_from_three([Vec2::ZERO, Vec2::ONE, Vec2::splat(2.0)], to).is_none());
    }

    #[test]
    fn surface_rotation_codes() {
        assert_eq!(
            DisplayRotation::from_surface(3),
            Some(DisplayRotation::R270)
        );
        assert_eq!(DisplayRotation::from_surface(4), None);
    }
}
