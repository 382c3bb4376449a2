//! Golden-image checks shared by the render crate's GPU tests (the race scene, the effects,
//! the pool): an image rendered small on lavapipe against a PNG. The whole frame's limits let
//! driver rounding through and catch a broken picture: mean absolute difference ≤ 2 levels (of
//! 255) per channel, and ≤ 1 % of pixels off by more than 24 levels in some channel. An effect
//! that moves few pixels a little (the flow map: 0.08 levels over the frame) hides under those,
//! so a golden may add [`Region`]s, the pixels where one effect acts, each with its own mean
//! limit ([`check_regions`]).
//!
//! With `REGATTA_UPDATE_GOLDEN=1` (or `true`) [`check`] writes the image instead and says on
//! stderr how far it moved from the old one (after an intended change of the picture; then
//! look at the PNGs). Any other value but `0`/`false`/empty is refused.

use std::path::Path;

/// The race scene the golden and GPU tests draw (and the pool bench's baseline): the default sea
/// at race time `t` s with `boats`, one mark 20 m east and 25 m north of the origin, and a fixed
/// camera 14 m up looking down over the water. A test fixture, not an API.
#[doc(hidden)]
pub fn test_scene(t: f64, boats: Vec<crate::Boat>) -> crate::Scene {
    crate::Scene {
        t,
        sea: ocean::WaveSet::default_sea().into(),
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

/// Uniform numbers in [0, 1) from a fixed seed (xorshift64, its top 53 bits): the tests'
/// deterministic stream. A test fixture, not an API.
#[doc(hidden)]
pub fn fixed_seed_uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed.max(1);
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Cameras over water about `scale` metres each way from the origin: high and steep, low and
/// grazing, close and oblique, straight down, from outside, rolled, and `random` more from
/// `seed` (eyes up to ⅔ `scale` across and 0.03–1.03 `scale` up, looking at points up to 0.4
/// `scale` away); the far plane 50 `scale` off. A test fixture, not an API.
#[doc(hidden)]
pub fn test_views(scale: f64, seed: u64, random: usize) -> Vec<crate::Camera> {
    let look = |eye: [f64; 3], target: [f64; 3]| {
        crate::Camera::look_at(
            glam::DVec3::from_array(eye) * scale,
            glam::DVec3::from_array(target) * scale,
            50.0 * scale,
        )
    };
    let mut rolled = look([0.17, 0.3, 0.47], [0.0, 0.0, 0.0]);
    rolled.up = glam::DVec3::new(0.6, 1.0, 0.2);
    let mut views = vec![
        look([0.0, 1.33, 0.67], [0.0, 0.0, 0.0]),
        look([0.0, 0.133, 0.4], [0.0, 0.0, -1.0]),
        look([-0.1, 0.4, 0.1], [0.067, 0.0, -0.067]),
        look([0.0, 0.83, 0.0003], [0.0, 0.0, 0.0]),
        look([1.0, 0.33, 0.83], [0.0, 0.0, 0.0]),
        rolled,
    ];
    let mut next = fixed_seed_uniform(seed);
    for _ in 0..random {
        let eye = [1.33 * next() - 0.67, 0.033 + next(), 1.33 * next() - 0.67];
        let target = [0.8 * next() - 0.4, 0.0, 0.53 * next() - 0.27];
        views.push(look(eye, target));
    }
    views
}

/// Largest mean absolute difference per channel, levels.
pub const MEAN_TOLERANCE: f64 = 2.0;
/// A pixel is off when some channel differs by more than this many levels.
pub(crate) const PIXEL_TOLERANCE: u8 = 24;
/// Largest fraction of pixels off.
pub const MAX_OFF_FRACTION: f64 = 0.01;

/// Mean absolute difference per colour channel (levels) and the fraction of pixels off by more
/// than [`PIXEL_TOLERANCE`] in some channel. Images of different sizes are entirely off:
/// (255, 1).
pub fn compare(a: &image::RgbaImage, b: &image::RgbaImage) -> (f64, f64) {
    compare_in(a, b, None)
}

/// [`compare`] over the pixels where `mask` (row-major, one per pixel) is true; an empty
/// region or a mask of the wrong size is entirely off.
pub(crate) fn compare_in(
    a: &image::RgbaImage,
    b: &image::RgbaImage,
    mask: Option<&[bool]>,
) -> (f64, f64) {
    let n_pixels = (a.width() * a.height()) as usize;
    if a.dimensions() != b.dimensions()
        || n_pixels == 0
        || mask.is_some_and(|m| m.len() != n_pixels || !m.contains(&true))
    {
        return (255.0, 1.0);
    }
    let (mut sum, mut off, mut n) = (0.0, 0usize, 0usize);
    for (k, (p, q)) in a.pixels().zip(b.pixels()).enumerate() {
        if mask.is_some_and(|m| !m[k]) {
            continue;
        }
        let d = [0, 1, 2].map(|c| p[c].abs_diff(q[c]));
        sum += d.iter().map(|&x| f64::from(x)).sum::<f64>();
        off += usize::from(d.iter().any(|&x| x > PIXEL_TOLERANCE));
        n += 1;
    }
    (sum / (3.0 * n as f64), off as f64 / n as f64)
}

/// The pixels where `a` and `b` differ at all: where an effect acts, from its image with and
/// without it.
pub fn differing(a: &image::RgbaImage, b: &image::RgbaImage) -> Vec<bool> {
    a.pixels()
        .zip(b.pixels())
        .map(|(p, q)| (0..3).any(|c| p[c] != q[c]))
        .collect()
}

/// Pixels of a golden where one effect acts, and the largest mean difference (levels per
/// channel) allowed there.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    pub name: String,
    pub mask: Vec<bool>,
    pub mean_tolerance: f64,
}

/// Should goldens be rewritten? `REGATTA_UPDATE_GOLDEN` = `1`/`true` yes; unset, empty,
/// `0`/`false` no; anything else is an error (a typo must not rewrite every golden).
pub(crate) fn update_requested(value: Option<&str>) -> Result<bool, String> {
    match value.map(|v| v.trim().to_ascii_lowercase()).as_deref() {
        None | Some("" | "0" | "false") => Ok(false),
        Some("1" | "true") => Ok(true),
        Some(other) => Err(format!(
            "REGATTA_UPDATE_GOLDEN={other:?}: use 1 or true to regenerate the goldens, 0 or \
             false (or unset) to check them"
        )),
    }
}

fn update_from_env() -> Result<bool, String> {
    let value = std::env::var_os("REGATTA_UPDATE_GOLDEN");
    update_requested(value.as_ref().map(|v| v.to_string_lossy()).as_deref())
}

/// Compare `img` with the golden PNG at `path` (or write it when `REGATTA_UPDATE_GOLDEN=1`).
/// On a mismatch the image is saved next to the temporary files and the error says where.
pub fn check(path: &Path, img: &image::RgbaImage) -> Result<(), String> {
    check_regions(path, img, &[])
}

/// [`check`] with the whole frame's limits and, in each of `regions`, its own mean limit.
pub fn check_regions(
    path: &Path,
    img: &image::RgbaImage,
    regions: &[Region],
) -> Result<(), String> {
    if update_from_env()? {
        return update(path, img);
    }
    verify(path, img, regions)
}

/// Write `img` as the golden at `path`, and say on stderr how far it moved from the old one.
fn update(path: &Path, img: &image::RgbaImage) -> Result<(), String> {
    let old = image::open(path).ok().map(|i| i.to_rgba8());
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    img.save(path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let change = match old {
        Some(old) if old == *img => "unchanged".to_string(),
        Some(old) => {
            let (mean, off) = compare(img, &old);
            let moved = differing(img, &old).iter().filter(|&&d| d).count();
            format!(
                "changed: mean {mean:.3} levels, {moved} pixels differ, {:.2} % by more than \
                 {PIXEL_TOLERANCE} levels",
                off * 100.0
            )
        }
        None => "new".to_string(),
    };
    eprintln!("golden {}: {change}", path.display());
    Ok(())
}

/// Check `img` against the golden at `path` and its `regions`, never writing it (whatever
/// `REGATTA_UPDATE_GOLDEN` says: for tests that feed a broken image on purpose).
pub fn verify(path: &Path, img: &image::RgbaImage, regions: &[Region]) -> Result<(), String> {
    let want = image::open(path)
        .map_err(|e| {
            format!(
                "{}: {e}; regenerate with REGATTA_UPDATE_GOLDEN=1",
                path.display()
            )
        })?
        .to_rgba8();
    let save_got = || {
        let stem = path
            .file_stem()
            .map_or("image".into(), |s| s.to_string_lossy());
        let got = std::env::temp_dir().join(format!("regatta-{stem}-got.png"));
        let _ = img.save(&got);
        got
    };
    let (mean, off) = compare(img, &want);
    if mean > MEAN_TOLERANCE || off > MAX_OFF_FRACTION {
        return Err(format!(
            "{}: mean difference {mean:.2} levels, {:.2} % pixels off (limits {MEAN_TOLERANCE}, \
             {:.0} %); got {}",
            path.display(),
            off * 100.0,
            MAX_OFF_FRACTION * 100.0,
            save_got().display()
        ));
    }
    for r in regions {
        let (mean, _) = compare_in(img, &want, Some(&r.mask));
        if mean > r.mean_tolerance {
            return Err(format!(
                "{}: mean difference {mean:.3} levels where {} acts (limit {}); got {}",
                path.display(),
                r.name,
                r.mean_tolerance,
                save_got().display()
            ));
        }
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
        let missing = verify(&path, &grey(10), &[]).unwrap_err();
        assert!(missing.contains("g.png") && missing.contains("REGATTA_UPDATE_GOLDEN"));
        update(&path, &grey(10)).expect("written");
        verify(&path, &grey(11), &[]).expect("1 level is within the limits");
        // Within the frame's limits but not within a region's own.
        let mut one = grey(10);
        one.put_pixel(0, 0, image::Rgba([14, 10, 10, 255]));
        verify(&path, &one, &[]).expect("a small change passes the frame's limits");
        let mut mask = vec![false; 20];
        mask[0] = true;
        let region = Region {
            name: "the test effect".into(),
            mask,
            mean_tolerance: 1.0,
        };
        let err = verify(&path, &one, std::slice::from_ref(&region)).unwrap_err();
        assert!(err.contains("where the test effect acts"), "{err}");
        let err = verify(&path, &grey(40), &[]).unwrap_err();
        assert!(
            err.contains("g.png") && err.contains("mean difference 30.00"),
            "{err}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn only_one_or_true_regenerates_the_goldens() {
        for v in [None, Some(""), Some("0"), Some("false"), Some("FALSE")] {
            assert_eq!(update_requested(v), Ok(false), "{v:?}");
        }
        for v in ["1", "true", "True"] {
            assert_eq!(update_requested(Some(v)), Ok(true), "{v}");
        }
        for v in ["yes", "2", "flase"] {
            let e = update_requested(Some(v)).unwrap_err();
            assert!(e.contains("REGATTA_UPDATE_GOLDEN") && e.contains(v), "{e}");
        }
    }

    #[test]
    fn a_region_compares_only_its_pixels() {
        let mut b = grey(10);
        b.put_pixel(1, 1, image::Rgba([40, 40, 40, 255]));
        let mask = differing(&grey(10), &b);
        assert_eq!(mask.iter().filter(|&&m| m).count(), 1);
        assert_eq!(compare_in(&grey(10), &b, Some(&mask)), (30.0, 1.0));
        assert_eq!(compare_in(&grey(10), &b, Some(&[false; 20])), (255.0, 1.0));
    }
}
