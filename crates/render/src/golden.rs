//! Golden-image checks shared by the render crate's GPU tests (the race scene, the effects,
//! the pool): an image rendered small on lavapipe against a PNG. The limits let driver
//! rounding through and catch a broken shader: mean absolute difference ≤ 2 levels (of 255)
//! per channel, and ≤ 1 % of pixels off by more than 24 levels in some channel.
//!
//! With `REGATTA_UPDATE_GOLDEN` set, [`check`] writes the image instead (after an intended
//! change of the picture; then look at the PNGs).

use std::path::Path;

/// The race scene the golden and GPU tests draw (and the pool bench's baseline): the default sea
/// at race time `t` s with `boats`, one mark 20 m east and 25 m north of the origin, and a fixed
/// camera 14 m up looking down over the water. A test fixture, not an API.
#[doc(hidden)]
pub fn test_scene(t: f64, boats: Vec<crate::Boat>) -> crate::Scene {
    crate::Scene {
        t,
        sea: ocean::WaveSet::default_sea(),
        boats,
        marks: vec![crate::Mark {
            position: glam::DVec2::new(20.0, -25.0),
        }],
        play_area: [-2000.0, -2000.0, 2000.0, 2000.0],
        sun: crate::Scene::default_sun(),
        camera: crate::Camera::look_at(
            glam::DVec3::new(25.0, 14.0, 45.0),
            glam::DVec3::new(-2.0, 0.0, -5.0),
            5000.0,
        ),
    }
}

/// Largest mean absolute difference per channel, levels.
pub const MEAN_TOLERANCE: f64 = 2.0;
/// A pixel is off when some channel differs by more than this many levels.
pub const PIXEL_TOLERANCE: u8 = 24;
/// Largest fraction of pixels off.
pub const MAX_OFF_FRACTION: f64 = 0.01;

/// Mean absolute difference per colour channel (levels) and the fraction of pixels off by more
/// than [`PIXEL_TOLERANCE`] in some channel. Images of different sizes are entirely off:
/// (255, 1).
pub fn compare(a: &image::RgbaImage, b: &image::RgbaImage) -> (f64, f64) {
    if a.dimensions() != b.dimensions() || a.width() * a.height() == 0 {
        return (255.0, 1.0);
    }
    let (mut sum, mut off) = (0.0, 0usize);
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d = [0, 1, 2].map(|c| p[c].abs_diff(q[c]));
        sum += d.iter().map(|&x| f64::from(x)).sum::<f64>();
        off += usize::from(d.iter().any(|&x| x > PIXEL_TOLERANCE));
    }
    let n = f64::from(a.width() * a.height());
    (sum / (3.0 * n), off as f64 / n)
}

/// Compare `img` with the golden PNG at `path` (or write it when `REGATTA_UPDATE_GOLDEN` is
/// set). On a mismatch the image is saved next to the temporary files and the error says where.
pub fn check(path: &Path, img: &image::RgbaImage) -> Result<(), String> {
    check_or_update(
        path,
        img,
        std::env::var_os("REGATTA_UPDATE_GOLDEN").is_some(),
    )
}

fn check_or_update(path: &Path, img: &image::RgbaImage, update: bool) -> Result<(), String> {
    if update {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        img.save(path)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        log::info!("wrote {}", path.display());
        return Ok(());
    }
    let want = image::open(path)
        .map_err(|e| {
            format!(
                "{}: {e}; regenerate with REGATTA_UPDATE_GOLDEN=1",
                path.display()
            )
        })?
        .to_rgba8();
    let (mean, off) = compare(img, &want);
    if mean > MEAN_TOLERANCE || off > MAX_OFF_FRACTION {
        let stem = path
            .file_stem()
            .map_or("image".into(), |s| s.to_string_lossy());
        let got = std::env::temp_dir().join(format!("regatta-{stem}-got.png"));
        let _ = img.save(&got);
        return Err(format!(
            "{}: mean difference {mean:.2} levels, {:.2} % pixels off (limits {MEAN_TOLERANCE}, \
             {:.0} %); got {}",
            path.display(),
            off * 100.0,
            MAX_OFF_FRACTION * 100.0,
            got.display()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(v: u8) -> image::RgbaImage {
        image::RgbaImage::from_pixel(4, 5, image::Rgba([v, v, v, 255]))
    }

    #[test]
    fn compare_counts_levels_and_pixels_off() {
        assert_eq!(compare(&grey(10), &grey(10)), (0.0, 0.0));
        // One pixel of 20 off by 30 levels in one channel: mean 30 / (3 · 20), 5 % off.
        let mut b = grey(10);
        b.put_pixel(2, 3, image::Rgba([40, 10, 10, 255]));
        assert_eq!(compare(&grey(10), &b), (0.5, 0.05));
        // Off by exactly the tolerance is not off; alpha is ignored.
        let c = image::RgbaImage::from_pixel(4, 5, image::Rgba([34, 34, 34, 0]));
        assert_eq!(compare(&grey(10), &c), (24.0, 0.0));
        assert_eq!(
            compare(&grey(10), &image::RgbaImage::new(5, 4)),
            (255.0, 1.0)
        );
    }

    #[test]
    fn check_passes_within_the_limits_and_names_the_file_otherwise() {
        let dir = std::env::temp_dir().join(format!("regatta-golden-{}", std::process::id()));
        let path = dir.join("g.png");
        let missing = check_or_update(&path, &grey(10), false).unwrap_err();
        assert!(missing.contains("g.png") && missing.contains("REGATTA_UPDATE_GOLDEN"));
        check_or_update(&path, &grey(10), true).expect("written");
        check_or_update(&path, &grey(11), false).expect("1 level is within the limits");
        let err = check_or_update(&path, &grey(40), false).unwrap_err();
        assert!(
            err.contains("g.png") && err.contains("mean difference 30.00"),
            "{err}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
