//! Recorded feeds: the Regatta replay folder (reader and writer) and the TUM RGB-D layout
//! (reader), both read into one [`ReplayFeed`].
//!
//! # The replay folder (version 1)
//!
//! ```text
//! DIR/session.json   metadata (below)
//! DIR/frames.txt     one line per frame: `t file tx ty tz qx qy qz qw`
//! DIR/frames/…       the images, JPEG or PNG, all of the size in session.json
//! ```
//!
//! `session.json`:
//!
//! ```json
//! {"format": "regatta-replay", "version": 1,
//!  "intrinsics": {"fx": 277.1, "fy": 277.1, "cx": 200.0, "cy": 150.0, "width": 400, "height": 300},
//!  "frame_rate": 15.0,
//!  "pose_convention": "opengl",
//!  "table": {"center": [0, 0, 0], "rotation": [0, 0, 0, 1], "extent": [1.2, 0.8]},
//!  "frames": "frames.txt"}
//! ```
//!
//! - `pose_convention`: `"opengl"` (camera looks down -z, y up: ARCore's) or `"opencv"` (looks
//!   down +z, y down: TUM's); poses are converted to the first on reading.
//! - `table` (optional): the table top, a horizontal plane facing up: its centre pose (local y is
//!   the normal) and full size along local x and z, metres. It becomes the frames' detected plane.
//! - `frames.txt`: `t` seconds from the first frame, strictly increasing; `file` relative to the
//!   folder, without spaces; the pose is camera-to-world. `#` starts a comment line.
//!
//! # TUM RGB-D
//!
//! `rgb.txt` (`timestamp filename`) and `groundtruth.txt` (`timestamp tx ty tz qx qy qz qw`, the
//! colour camera's optical centre, OpenCV convention); each image takes the ground-truth pose
//! nearest in time, and images farther than [`TUM_MAX_POSE_GAP_S`] from every pose are skipped
//! (as TUM's `associate.py` does). Intrinsics are the published calibration of the Freiburg
//! sensor named in the folder name (`freiburg1/2/3`), else TUM's stated default (525, 525, 319.5,
//! 239.5); an `intrinsics.json` (`{"fx", "fy", "cx", "cy", "width", "height"}`) overrides both.

use std::fs;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use glam::{Affine2, DQuat, DVec3, Vec2};
use serde::{Deserialize, Serialize};

use crate::pose::{Pose, parse_finite};
use crate::{
    ArError, CameraFrame, DetectedPlane, FrameImage, FrameSource, Intrinsics, PlaneKind,
    TrackingState,
};

/// Largest time between a TUM image and its ground-truth pose, seconds (`associate.py`'s default).
pub const TUM_MAX_POSE_GAP_S: f64 = 0.02;

/// The `format` value of `session.json`.
pub const REPLAY_FORMAT: &str = "regatta-replay";
/// The `version` this crate reads and writes.
pub const REPLAY_VERSION: u32 = 1;

/// How the poses in a replay's `frames.txt` orient the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PoseConvention {
    /// Camera looks down -z, y up (ARCore, OpenGL).
    Opengl,
    /// Camera looks down +z, y down (OpenCV, TUM RGB-D).
    Opencv,
}

/// The table top of a replay: a horizontal plane facing up.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TablePlane {
    /// Centre of the table top in world coordinates, metres.
    pub center: [f64; 3],
    /// Plane-to-world rotation `[qx, qy, qz, qw]`; local y is the normal.
    #[serde(default = "identity_quat")]
    pub rotation: [f64; 4],
    /// Full size along local x and z, metres.
    pub extent: [f64; 2],
}

fn identity_quat() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

impl TablePlane {
    pub fn to_detected_plane(&self) -> DetectedPlane {
        let [qx, qy, qz, qw] = self.rotation;
        let pose = Pose {
            position: DVec3::from_array(self.center),
            rotation: DQuat::from_xyzw(qx, qy, qz, qw).normalize(),
        };
        let (hx, hz) = (0.5 * self.extent[0] as f32, 0.5 * self.extent[1] as f32);
        DetectedPlane {
            center_pose: pose.to_mat4(),
            extent: Vec2::new(self.extent[0] as f32, self.extent[1] as f32),
            // Counter-clockwise seen from +y (x right, z towards the viewer).
            polygon: vec![
                Vec2::new(-hx, -hz),
                Vec2::new(-hx, hz),
                Vec2::new(hx, hz),
                Vec2::new(hx, -hz),
            ],
            kind: PlaneKind::HorizontalUp,
        }
    }

    fn validate(&self, path: &Path) -> Result<(), ArError> {
        let finite = self
            .center
            .iter()
            .chain(&self.rotation)
            .chain(&self.extent)
            .all(|x| x.is_finite());
        let q = DQuat::from_array(self.rotation);
        if !finite
            || self.extent.iter().any(|&e| e <= 0.0)
            || (q.length() - 1.0).abs() > crate::pose::QUAT_NORM_TOLERANCE
        {
            return Err(ArError::in_file(
                path,
                "field `table` needs a finite centre, a unit rotation quaternion and a positive extent",
            ));
        }
        Ok(())
    }
}

/// `session.json` of a replay folder.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Session {
    pub format: String,
    pub version: u32,
    pub intrinsics: Intrinsics,
    /// Nominal frames per second (the timestamps in `frames.txt` are what counts).
    pub frame_rate: f64,
    pub pose_convention: PoseConvention,
    #[serde(default)]
    pub table: Option<TablePlane>,
    /// The frame list, relative to the folder.
    #[serde(default = "default_frames_file")]
    pub frames: String,
}

fn default_frames_file() -> String {
    "frames.txt".to_string()
}

/// One frame of a feed: where its image is and the camera's pose then.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameEntry {
    /// Seconds from the feed's first frame.
    pub t: f64,
    pub image_path: PathBuf,
    /// Camera-to-world pose in the crate's convention (looking down -z, y up).
    pub pose: Pose,
    /// Where this frame is listed: `(file, line)`, for messages.
    pub listed_at: (PathBuf, usize),
}

/// A recorded feed read into memory (poses and file names; images are decoded on demand).
#[derive(Clone, Debug)]
pub struct ReplayFeed {
    pub dir: PathBuf,
    pub intrinsics: Intrinsics,
    pub planes: Vec<DetectedPlane>,
    pub frames: Vec<FrameEntry>,
    /// Nominal frames per second.
    pub frame_rate: f64,
}

impl ReplayFeed {
    /// Opens a replay folder (`session.json`) or a TUM RGB-D folder (`rgb.txt`), whichever `dir`
    /// holds.
    pub fn open(dir: &Path) -> Result<ReplayFeed, ArError> {
        if dir.join("session.json").is_file() {
            Self::open_replay(dir)
        } else if dir.join("rgb.txt").is_file() {
            Self::open_tum(dir)
        } else {
            Err(ArError::in_file(
                dir,
                "is not a feed: it holds neither session.json (a Regatta replay) nor rgb.txt (TUM RGB-D)",
            ))
        }
    }

    /// Opens a Regatta replay folder (module docs) and checks every frame's file and image size.
    pub fn open_replay(dir: &Path) -> Result<ReplayFeed, ArError> {
        let session_path = dir.join("session.json");
        let text = read_text(&session_path)?;
        let session: Session = serde_json::from_str(&text)
            .map_err(|e| ArError::at_line(&session_path, e.line(), format!("{e}")))?;
        if session.format != REPLAY_FORMAT || session.version != REPLAY_VERSION {
            return Err(ArError::in_file(
                &session_path,
                format!(
                    "format is `{}` version {}, this program reads `{REPLAY_FORMAT}` version {REPLAY_VERSION}",
                    session.format, session.version
                ),
            ));
        }
        session.intrinsics.validate(&format!(
            "{} field `intrinsics`",
            input::show_path(&session_path)
        ))?;
        if !(session.frame_rate.is_finite() && session.frame_rate > 0.0) {
            return Err(ArError::in_file(
                &session_path,
                "field `frame_rate` must be a positive number",
            ));
        }
        let planes = match &session.table {
            Some(t) => {
                t.validate(&session_path)?;
                vec![t.to_detected_plane()]
            }
            None => Vec::new(),
        };
        let frames_path = dir.join(&session.frames);
        let text = read_text(&frames_path)?;
        let mut frames: Vec<FrameEntry> = Vec::new();
        for (line, fields) in data_lines(&text) {
            if fields.len() != 9 {
                return Err(ArError::at_line(
                    &frames_path,
                    line,
                    format!(
                        "expected 9 fields `t file tx ty tz qx qy qz qw`, found {}",
                        fields.len()
                    ),
                ));
            }
            let t = parse_finite(fields[0], &frames_path, line, "t")?;
            if let Some(prev) = frames.last()
                && t <= prev.t
            {
                return Err(ArError::at_line(
                    &frames_path,
                    line,
                    format!(
                        "time {t} s does not come after the previous frame's {} s",
                        prev.t
                    ),
                ));
            }
            let mut pose = Pose::parse_fields(&fields[2..], &frames_path, line)?;
            if session.pose_convention == PoseConvention::Opencv {
                pose = Pose::from_opencv(pose);
            }
            frames.push(FrameEntry {
                t,
                image_path: dir.join(fields[1]),
                pose,
                listed_at: (frames_path.clone(), line),
            });
        }
        let feed = ReplayFeed {
            dir: dir.to_path_buf(),
            intrinsics: session.intrinsics,
            planes,
            frames,
            frame_rate: session.frame_rate,
        };
        feed.check_frames(&frames_path)?;
        Ok(feed)
    }

    /// Opens a TUM RGB-D folder (module docs).
    pub fn open_tum(dir: &Path) -> Result<ReplayFeed, ArError> {
        let rgb_path = dir.join("rgb.txt");
        let gt_path = dir.join("groundtruth.txt");
        let mut poses: Vec<(f64, Pose)> = Vec::new();
        for (line, fields) in data_lines(&read_text(&gt_path)?) {
            if fields.len() != 8 {
                return Err(ArError::at_line(
                    &gt_path,
                    line,
                    format!(
                        "expected 8 fields `timestamp tx ty tz qx qy qz qw`, found {}",
                        fields.len()
                    ),
                ));
            }
            let t = parse_finite(fields[0], &gt_path, line, "timestamp")?;
            if let Some((prev, _)) = poses.last()
                && t <= *prev
            {
                return Err(ArError::at_line(
                    &gt_path,
                    line,
                    format!("timestamp {t} does not come after the previous pose's {prev}"),
                ));
            }
            poses.push((
                t,
                Pose::from_opencv(Pose::parse_fields(&fields[1..], &gt_path, line)?),
            ));
        }
        if poses.is_empty() {
            return Err(ArError::in_file(&gt_path, "holds no poses"));
        }
        let mut frames = Vec::new();
        let mut t0 = None;
        let mut skipped = 0usize;
        for (line, fields) in data_lines(&read_text(&rgb_path)?) {
            if fields.len() != 2 {
                return Err(ArError::at_line(
                    &rgb_path,
                    line,
                    format!(
                        "expected 2 fields `timestamp filename`, found {}",
                        fields.len()
                    ),
                ));
            }
            let t = parse_finite(fields[0], &rgb_path, line, "timestamp")?;
            let (pose_t, pose) = nearest_pose(&poses, t);
            if (pose_t - t).abs() > TUM_MAX_POSE_GAP_S {
                skipped += 1;
                continue;
            }
            let t0 = *t0.get_or_insert(t);
            if let Some(prev) = frames.last().map(|f: &FrameEntry| f.t)
                && t - t0 <= prev
            {
                return Err(ArError::at_line(
                    &rgb_path,
                    line,
                    format!("timestamp {t} does not come after the previous image's"),
                ));
            }
            frames.push(FrameEntry {
                t: t - t0,
                image_path: dir.join(fields[1]),
                pose,
                listed_at: (rgb_path.clone(), line),
            });
        }
        if frames.is_empty() {
            return Err(ArError::in_file(
                &rgb_path,
                format!("no image has a ground-truth pose within {TUM_MAX_POSE_GAP_S} s"),
            ));
        }
        if skipped > 0 {
            log::info!(
                "{}: skipped {skipped} images without a pose within {TUM_MAX_POSE_GAP_S} s",
                rgb_path.display()
            );
        }
        let intrinsics = tum_intrinsics(dir)?;
        let span = frames.last().map_or(0.0, |f| f.t);
        let frame_rate = if span > 0.0 {
            (frames.len() - 1) as f64 / span
        } else {
            30.0
        };
        let feed = ReplayFeed {
            dir: dir.to_path_buf(),
            intrinsics,
            planes: Vec::new(),
            frames,
            frame_rate,
        };
        feed.check_frames(&rgb_path)?;
        Ok(feed)
    }

    /// Every listed image exists and has the feed's size (image headers only, no decoding).
    fn check_frames(&self, list: &Path) -> Result<(), ArError> {
        if self.frames.is_empty() {
            return Err(ArError::in_file(list, "lists no frames"));
        }
        for f in &self.frames {
            let (w, h) = image_size(f)?;
            self.check_size(f, w, h)?;
        }
        Ok(())
    }

    fn check_size(&self, f: &FrameEntry, w: u32, h: u32) -> Result<(), ArError> {
        let (iw, ih) = (self.intrinsics.width, self.intrinsics.height);
        if (w, h) != (iw, ih) {
            return Err(ArError::at_line(
                &f.listed_at.0,
                f.listed_at.1,
                format!(
                    "image {} is {w}×{h} pixels, but the feed's intrinsics are for {iw}×{ih}",
                    input::show_path(&f.image_path)
                ),
            ));
        }
        Ok(())
    }

    pub fn len(&self) -> usize {
        self.frames.len()
    }

    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// Time from the first to the last frame plus one nominal frame interval, seconds: the loop
    /// period when the feed plays in a loop.
    pub fn duration(&self) -> f64 {
        self.frames.last().map_or(0.0, |f| f.t) + 1.0 / self.frame_rate
    }

    /// The index of the frame showing at `t` seconds when the feed loops: the last frame whose
    /// time is at or before `t` modulo [`ReplayFeed::duration`].
    pub fn index_at(&self, t: f64) -> usize {
        let tl = t.rem_euclid(self.duration());
        self.frames.partition_point(|f| f.t <= tl).saturating_sub(1)
    }

    /// Decodes every frame (what `regatta replay check` does): a truncated or damaged image is
    /// an error naming its line, not a frame that plays half grey.
    pub fn check_decodes(&self) -> Result<(), ArError> {
        (0..self.len()).try_for_each(|i| self.frame(i).map(drop))
    }

    /// Decodes frame `i` into a [`CameraFrame`].
    pub fn frame(&self, i: usize) -> Result<CameraFrame, ArError> {
        let f = &self.frames[i];
        let img = crate::frame_file::decode(&f.image_path).map_err(|why| {
            ArError::at_line(
                &f.listed_at.0,
                f.listed_at.1,
                format!("frame image {}: {why}", input::show_path(&f.image_path)),
            )
        })?;
        let rgba = img.to_rgba8();
        self.check_size(f, rgba.width(), rgba.height())?;
        Ok(CameraFrame {
            image: FrameImage::Rgba8 {
                width: rgba.width(),
                height: rgba.height(),
                data: rgba.into_raw(),
            },
            camera_to_world: f.pose.to_mat4(),
            intrinsics: self.intrinsics,
            planes: self.planes.clone(),
            timestamp: f.t,
            display_uv: Affine2::IDENTITY,
            tracking: TrackingState::Tracking,
        })
    }
}

fn image_size(f: &FrameEntry) -> Result<(u32, u32), ArError> {
    let at = |what: String| ArError::at_line(&f.listed_at.0, f.listed_at.1, what);
    if let Some(why) = crate::frame_file::not_a_file(&f.image_path) {
        return Err(at(format!(
            "frame image {} {why}",
            input::show_path(&f.image_path)
        )));
    }
    image::ImageReader::open(&f.image_path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| {
            at(format!(
                "cannot open image {}: {e}",
                input::show_path(&f.image_path)
            ))
        })?
        .into_dimensions()
        .map_err(|e| {
            at(format!(
                "cannot read image {}: {e}",
                input::show_path(&f.image_path)
            ))
        })
}

/// Largest text file of a feed (`session.json`, `frames.txt`, TUM's lists), bytes: 100,000
/// frames listed at about 120 bytes a line take 12 MB.
pub const MAX_FEED_TEXT_BYTES: u64 = 64 << 20;

fn read_text(path: &Path) -> Result<String, ArError> {
    let bytes = input::read_capped(
        path,
        MAX_FEED_TEXT_BYTES,
        "a feed's text file",
        input::text_sniff,
    )
    .map_err(|e| ArError::new(e.0))?;
    String::from_utf8(bytes).map_err(|e| {
        ArError::in_file(
            path,
            format!("byte {} is not UTF-8 text", e.utf8_error().valid_up_to()),
        )
    })
}

/// Non-empty, non-comment lines with their 1-based line numbers, split on whitespace.
fn data_lines(text: &str) -> impl Iterator<Item = (usize, Vec<&str>)> {
    text.lines().enumerate().filter_map(|(i, l)| {
        let l = l.trim();
        (!l.is_empty() && !l.starts_with('#')).then(|| (i + 1, l.split_whitespace().collect()))
    })
}

/// The pose nearest in time to `t` (poses sorted by time, non-empty).
fn nearest_pose(poses: &[(f64, Pose)], t: f64) -> (f64, Pose) {
    let i = poses.partition_point(|(pt, _)| *pt < t);
    let candidates = [i.checked_sub(1), (i < poses.len()).then_some(i)];
    candidates
        .into_iter()
        .flatten()
        .map(|k| poses[k])
        .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
        .expect("poses is non-empty")
}

/// TUM's published colour-camera calibrations (https://cvg.cit.tum.de/data/datasets/rgbd-dataset/file_formats).
fn tum_intrinsics(dir: &Path) -> Result<Intrinsics, ArError> {
    let override_path = dir.join("intrinsics.json");
    if override_path.is_file() {
        let text = read_text(&override_path)?;
        let k: Intrinsics = serde_json::from_str(&text)
            .map_err(|e| ArError::at_line(&override_path, e.line(), format!("{e}")))?;
        k.validate(&input::show_path(&override_path))?;
        return Ok(k);
    }
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let (fx, fy, cx, cy) = if name.contains("freiburg1") {
        (517.3, 516.5, 318.6, 255.3)
    } else if name.contains("freiburg2") {
        (520.9, 521.0, 325.1, 249.7)
    } else if name.contains("freiburg3") {
        (535.4, 539.2, 320.1, 247.6)
    } else {
        (525.0, 525.0, 319.5, 239.5)
    };
    Ok(Intrinsics {
        fx,
        fy,
        cx,
        cy,
        width: 640,
        height: 480,
    })
}

/// Image file format of a written replay.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameFileFormat {
    /// JPEG at the given quality (1–100): small, for shipped feeds and phone recordings.
    Jpeg(u8),
    /// Lossless.
    Png,
}

/// Writes a replay folder (module docs) frame by frame; [`ReplayWriter::finish`] writes
/// `session.json` and `frames.txt`. The phone's recording button and `regatta replay synth` use it.
pub struct ReplayWriter {
    dir: PathBuf,
    session: Session,
    format: FrameFileFormat,
    lines: Vec<String>,
    last_t: Option<f64>,
}

impl ReplayWriter {
    /// Creates `dir` (and `dir/frames`) for a feed with these intrinsics.
    pub fn create(
        dir: &Path,
        intrinsics: Intrinsics,
        frame_rate: f64,
        table: Option<TablePlane>,
        format: FrameFileFormat,
    ) -> Result<ReplayWriter, ArError> {
        intrinsics.validate("replay writer")?;
        fs::create_dir_all(dir.join("frames"))
            .map_err(|e| ArError::in_file(dir, format!("cannot be created: {e}")))?;
        Ok(ReplayWriter {
            dir: dir.to_path_buf(),
            session: Session {
                format: REPLAY_FORMAT.to_string(),
                version: REPLAY_VERSION,
                intrinsics,
                frame_rate,
                pose_convention: PoseConvention::Opengl,
                table,
                frames: default_frames_file(),
            },
            format,
            lines: Vec::new(),
            last_t: None,
        })
    }

    /// Writes one frame: `t` seconds from the first frame (strictly increasing), the image (of the
    /// intrinsics' size) and the camera-to-world pose.
    pub fn write_frame(&mut self, t: f64, image: &FrameImage, pose: &Pose) -> Result<(), ArError> {
        let k = &self.session.intrinsics;
        if image.size() != (k.width, k.height) {
            return Err(ArError::new(format!(
                "replay writer: frame {} is {}×{} pixels, but the feed is {}×{}",
                self.lines.len(),
                image.size().0,
                image.size().1,
                k.width,
                k.height
            )));
        }
        if self.last_t.is_some_and(|l| t <= l) || !t.is_finite() {
            return Err(ArError::new(format!(
                "replay writer: frame {} has time {t} s, not after the previous frame's",
                self.lines.len()
            )));
        }
        let ext = match self.format {
            FrameFileFormat::Jpeg(_) => "jpg",
            FrameFileFormat::Png => "png",
        };
        let name = format!("frames/{:06}.{ext}", self.lines.len());
        let path = self.dir.join(&name);
        let (w, h) = image.size();
        let rgba = image.to_rgba8();
        let io =
            |e: &dyn std::fmt::Display| ArError::in_file(&path, format!("cannot be written: {e}"));
        let file = fs::File::create(&path).map_err(|e| io(&e))?;
        let mut out = BufWriter::new(file);
        match self.format {
            FrameFileFormat::Jpeg(q) => {
                let rgb: Vec<u8> = rgba
                    .chunks_exact(4)
                    .flat_map(|p| [p[0], p[1], p[2]])
                    .collect();
                image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, q)
                    .encode(&rgb, w, h, image::ExtendedColorType::Rgb8)
                    .map_err(|e| io(&e))?;
            }
            FrameFileFormat::Png => {
                use image::ImageEncoder;
                image::codecs::png::PngEncoder::new(&mut out)
                    .write_image(&rgba, w, h, image::ExtendedColorType::Rgba8)
                    .map_err(|e| io(&e))?;
            }
        }
        self.lines.push(format!("{t} {name} {}", pose.to_text()));
        self.last_t = Some(t);
        Ok(())
    }

    /// Writes `session.json` and `frames.txt`; returns the folder.
    pub fn finish(self) -> Result<PathBuf, ArError> {
        let frames_path = self.dir.join(&self.session.frames);
        let mut text =
            String::from("# t file tx ty tz qx qy qz qw (camera-to-world, opengl convention)\n");
        for l in &self.lines {
            text.push_str(l);
            text.push('\n');
        }
        fs::write(&frames_path, text)
            .map_err(|e| ArError::in_file(&frames_path, format!("cannot be written: {e}")))?;
        let session_path = self.dir.join("session.json");
        let json = serde_json::to_string_pretty(&self.session).expect("a session serialises");
        fs::write(&session_path, json + "\n")
            .map_err(|e| ArError::in_file(&session_path, format!("cannot be written: {e}")))?;
        Ok(self.dir)
    }
}

/// Plays a [`ReplayFeed`] as a [`FrameSource`]: the app sets the feed time (wall-clock seconds
/// since playback began) and each call yields the frame showing then, if it changed.
pub struct ReplayPlayer {
    feed: ReplayFeed,
    time: f64,
    shown: Option<usize>,
}

impl ReplayPlayer {
    pub fn new(feed: ReplayFeed) -> Self {
        Self {
            feed,
            time: 0.0,
            shown: None,
        }
    }

    /// Feed time, seconds; the feed loops.
    pub fn set_time(&mut self, t: f64) {
        self.time = t;
    }

    pub fn feed(&self) -> &ReplayFeed {
        &self.feed
    }
}

impl FrameSource for ReplayPlayer {
    fn next_frame(&mut self) -> Result<Option<CameraFrame>, ArError> {
        let i = self.feed.index_at(self.time);
        if self.shown == Some(i) {
            return Ok(None);
        }
        let frame = self.feed.frame(i)?;
        self.shown = Some(i);
        Ok(Some(frame))
    }

    fn describe(&self) -> String {
        format!(
            "replay {} ({} frames)",
            self.feed.dir.display(),
            self.feed.len()
        )
    }
}
