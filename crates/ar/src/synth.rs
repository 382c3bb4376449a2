//! The synthetic feed: a wooden table seen from a hand-held camera, rendered on the CPU by exact
//! ray–plane intersection through the pinhole intrinsics, with the exact poses and intrinsics.
//!
//! Scene (world frame of [`crate::CameraFrame`], metres): the table top is the plane y = 0,
//! centred on the origin, [`TABLE_EXTENT`] along x and z, wood grain along x, with four coloured
//! discs ([`MARKERS`]) near its corners that tests (and people) can find in the image; the floor
//! is a tiled plane [`FLOOR_Y`] below, a plain wall colour beyond.
//!
//! The camera orbits the table at arm's length and swings ±20° about it, with a small hand
//! tremor: a sum of sinusoids with phases from a fixed seed, all periodic over the clip, so a
//! looping feed has no jump.

use std::f64::consts::TAU;
use std::path::Path;

use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng, rngs::SmallRng};

use crate::replay::{FrameFileFormat, ReplayWriter, TablePlane};
use crate::{ArError, CameraFrame, FrameImage, Intrinsics, Pose, TrackingState};

/// Table top size along x and z, metres.
pub const TABLE_EXTENT: [f64; 2] = [1.2, 0.8];
/// Height of the floor relative to the table top, metres.
pub const FLOOR_Y: f64 = -0.74;
/// Radius of the marker discs on the table, metres.
pub const MARKER_RADIUS: f64 = 0.025;

/// A coloured disc on the table top: centre (y = 0) and sRGB colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Marker {
    pub center: DVec3,
    pub color: [u8; 3],
}

/// The four marker discs, one near each corner of the table, each of its own colour.
pub const MARKERS: [Marker; 4] = [
    Marker {
        center: DVec3::new(0.45, 0.0, 0.28),
        color: [220, 30, 30],
    },
    Marker {
        center: DVec3::new(-0.45, 0.0, 0.28),
        color: [30, 60, 220],
    },
    Marker {
        center: DVec3::new(-0.45, 0.0, -0.28),
        color: [30, 170, 60],
    },
    Marker {
        center: DVec3::new(0.45, 0.0, -0.28),
        color: [225, 40, 215],
    },
];

/// What to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SynthConfig {
    pub frames: usize,
    pub width: u32,
    pub height: u32,
    /// Horizontal field of view, degrees (a phone's main camera: about 65°).
    pub hfov_deg: f64,
    pub frame_rate: f64,
    /// Seed of the hand tremor.
    pub seed: u64,
    /// Supersampling: `ss × ss` rays per pixel, averaged.
    pub supersample: u32,
}

impl Default for SynthConfig {
    fn default() -> Self {
        Self {
            frames: 64,
            width: 400,
            height: 300,
            hfov_deg: 65.0,
            frame_rate: 16.0,
            seed: 7,
            supersample: 2,
        }
    }
}

impl SynthConfig {
    pub fn intrinsics(&self) -> Intrinsics {
        Intrinsics::from_hfov(self.width, self.height, self.hfov_deg.to_radians())
    }

    /// The table as a replay's `table` field.
    pub fn table(&self) -> TablePlane {
        TablePlane {
            center: [0.0; 3],
            rotation: [0.0, 0.0, 0.0, 1.0],
            extent: TABLE_EXTENT,
        }
    }

    /// Time of frame `i`, seconds.
    pub fn time(&self, i: usize) -> f64 {
        i as f64 / self.frame_rate
    }

    /// The clip's length, seconds: the period of the camera path.
    pub fn period(&self) -> f64 {
        self.frames.max(1) as f64 / self.frame_rate
    }

    /// Camera-to-world pose of frame `i`.
    pub fn pose(&self, i: usize) -> Pose {
        let phase = TAU * self.time(i) / self.period();
        let tremor = Tremor::new(self.seed);
        // Orbit: 0.9 m from the table centre, 0.55 m above it, swinging ±20° about the +z side.
        let angle = 0.35 * phase.sin();
        let radius = 0.9 + 0.04 * (2.0 * phase).cos();
        let eye = DVec3::new(radius * angle.sin(), 0.55, radius * angle.cos())
            + tremor.offset(phase, 0.006);
        let target = DVec3::new(0.0, 0.0, -0.05) + tremor.offset(phase + 1.0, 0.012);
        Pose::look_at(eye, target, DVec3::Y)
    }

    /// Renders frame `i`.
    pub fn render(&self, i: usize) -> FrameImage {
        render_view(&self.intrinsics(), &self.pose(i), self.supersample)
    }

    /// Frame `i` as a camera frame (rendered now; the table is its detected plane), the same
    /// frame that [`SynthConfig::write`] writes and a reader gives back, before JPEG.
    pub fn frame(&self, i: usize) -> CameraFrame {
        CameraFrame {
            image: self.render(i),
            camera_to_world: self.pose(i).to_mat4(),
            intrinsics: self.intrinsics(),
            planes: vec![self.table().to_detected_plane()],
            timestamp: self.time(i),
            display_uv: glam::Affine2::IDENTITY,
            tracking: TrackingState::Tracking,
        }
    }

    /// The frame showing at `t` seconds when the clip loops.
    pub fn index_at(&self, t: f64) -> usize {
        ((t.rem_euclid(self.period()) * self.frame_rate).floor() as usize)
            .min(self.frames.max(1) - 1)
    }

    /// Writes the feed as a replay folder (JPEG frames at `jpeg_quality`).
    pub fn write(&self, dir: &Path, jpeg_quality: u8) -> Result<(), ArError> {
        let mut w = ReplayWriter::create(
            dir,
            self.intrinsics(),
            self.frame_rate,
            Some(self.table()),
            FrameFileFormat::Jpeg(jpeg_quality),
        )?;
        for i in 0..self.frames {
            log::info!("synth frame {}/{}", i + 1, self.frames);
            w.write_frame(self.time(i), &self.render(i), &self.pose(i))?;
        }
        w.finish()?;
        Ok(())
    }
}

/// Smooth hand tremor: harmonics 2–6 of the clip period with random phases and directions.
struct Tremor {
    terms: Vec<(f64, f64, DVec3)>,
}

impl Tremor {
    fn new(seed: u64) -> Self {
        let mut rng = SmallRng::seed_from_u64(seed);
        let terms = (2..=6)
            .map(|k| {
                let dir = DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                (f64::from(k), rng.random_range(0.0..TAU), dir)
            })
            .collect();
        Self { terms }
    }

    /// Offset at clip phase `phase`, of magnitude about `amplitude` metres.
    fn offset(&self, phase: f64, amplitude: f64) -> DVec3 {
        self.terms
            .iter()
            .map(|&(k, phi, dir)| dir * (amplitude / k.sqrt()) * (k * phase + phi).sin())
            .sum()
    }
}

/// Renders the scene from `pose` through `k`: for each of `ss × ss` sub-pixel rays, the exact
/// intersection with the table plane, else the floor, else the wall; colours are averaged.
pub fn render_view(k: &Intrinsics, pose: &Pose, ss: u32) -> FrameImage {
    let (w, h) = (k.width, k.height);
    let ss = ss.max(1);
    let mut data = vec![255u8; (w * h * 4) as usize];
    for j in 0..h {
        for i in 0..w {
            let mut acc = DVec3::ZERO;
            for sj in 0..ss {
                for si in 0..ss {
                    let px = DVec2::new(
                        f64::from(i) + (f64::from(si) + 0.5) / f64::from(ss),
                        f64::from(j) + (f64::from(sj) + 0.5) / f64::from(ss),
                    );
                    let dir = pose.rotation * k.ray_through_pixel(px);
                    acc += shade(pose.position, dir);
                }
            }
            let c = acc / f64::from(ss * ss);
            let o = ((j * w + i) * 4) as usize;
            data[o] = to_u8(c.x);
            data[o + 1] = to_u8(c.y);
            data[o + 2] = to_u8(c.z);
        }
    }
    FrameImage::Rgba8 {
        width: w,
        height: h,
        data,
    }
}

fn to_u8(x: f64) -> u8 {
    x.round().clamp(0.0, 255.0) as u8
}

/// Colour (sRGB 0–255) seen along the ray `origin + s dir`.
fn shade(origin: DVec3, dir: DVec3) -> DVec3 {
    if let Some(p) = hit_plane_y(origin, dir, 0.0)
        && p.x.abs() <= 0.5 * TABLE_EXTENT[0]
        && p.z.abs() <= 0.5 * TABLE_EXTENT[1]
    {
        return table_color(p.x, p.z);
    }
    if let Some(p) = hit_plane_y(origin, dir, FLOOR_Y)
        && (p - origin).length() < 8.0
    {
        return floor_color(p.x, p.z);
    }
    // Wall: a soft vertical gradient, lighter upwards.
    let up = dir.normalize().y.clamp(-1.0, 1.0);
    DVec3::new(200.0, 196.0, 188.0) + DVec3::splat(25.0 * up)
}

/// The point where the ray meets the plane y = `y` in front of the origin, if it does.
fn hit_plane_y(origin: DVec3, dir: DVec3, y: f64) -> Option<DVec3> {
    if dir.y == 0.0 {
        return None;
    }
    let s = (y - origin.y) / dir.y;
    (s > 0.0).then(|| origin + s * dir)
}

/// The table top at (x, z): markers over oak planks with grain along x.
pub fn table_color(x: f64, z: f64) -> DVec3 {
    for m in &MARKERS {
        if DVec2::new(x - m.center.x, z - m.center.z).length() <= MARKER_RADIUS {
            return DVec3::new(
                f64::from(m.color[0]),
                f64::from(m.color[1]),
                f64::from(m.color[2]),
            );
        }
    }
    // Planks 0.16 m wide along x; each plank's grain is shifted by a hash of its index.
    let plank = (z / 0.16).floor();
    let seam = ((z / 0.16) - plank).min(1.0 - ((z / 0.16) - plank));
    let offset = hash1(plank) * 10.0;
    let grain =
        (z * 90.0 + 2.5 * value_noise(x * 3.0 + offset, z * 12.0) + 0.6 * (x * 7.0 + offset).sin())
            .sin();
    let tone = 0.5 + 0.5 * grain;
    let light = DVec3::new(196.0, 148.0, 98.0);
    let dark = DVec3::new(150.0, 102.0, 62.0);
    let plank_shade = 0.92 + 0.16 * hash1(plank + 17.0);
    let c = (dark + (light - dark) * tone) * plank_shade;
    // Dark seam between planks, 3 mm wide.
    if seam * 0.16 < 0.0015 { c * 0.55 } else { c }
}

/// Grey stone tiles, 0.4 m, with darker grout.
fn floor_color(x: f64, z: f64) -> DVec3 {
    let (tx, tz) = ((x / 0.4).floor(), (z / 0.4).floor());
    let (fx, fz) = (x / 0.4 - tx, z / 0.4 - tz);
    if fx < 0.02 || fz < 0.02 {
        return DVec3::splat(90.0);
    }
    DVec3::splat(120.0 + 30.0 * hash1(tx * 31.0 + tz))
}

/// A hash of a float to [0, 1).
fn hash1(x: f64) -> f64 {
    let s = (x * 12.9898).sin() * 43_758.545_3;
    s - s.floor()
}

/// Smooth value noise in [0, 1).
fn value_noise(x: f64, y: f64) -> f64 {
    let (ix, iy) = (x.floor(), y.floor());
    let (fx, fy) = (x - ix, y - iy);
    let smooth = |t: f64| t * t * (3.0 - 2.0 * t);
    let (sx, sy) = (smooth(fx), smooth(fy));
    let corner = |a: f64, b: f64| hash1(a * 57.0 + b * 113.0);
    let top = corner(ix, iy) * (1.0 - sx) + corner(ix + 1.0, iy) * sx;
    let bottom = corner(ix, iy + 1.0) * (1.0 - sx) + corner(ix + 1.0, iy + 1.0) * sx;
    top * (1.0 - sy) + bottom * sy
}
