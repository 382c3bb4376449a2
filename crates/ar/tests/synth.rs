//! The synthetic feed written and read back: exact poses and intrinsics, and the marker discs on
//! the table found where the read-back pose and intrinsics project them.

use std::path::PathBuf;

use ar::synth::{MARKER_RADIUS, MARKERS, render_view};
use ar::{FrameImage, ReplayFeed, SynthConfig};
use glam::{DVec2, DVec3};

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn small() -> SynthConfig {
    SynthConfig {
        frames: 5,
        width: 200,
        height: 150,
        ..SynthConfig::default()
    }
}

#[test]
fn written_feed_reads_back_exact_poses_and_intrinsics() {
    let dir = tmp("synth_exact");
    let cfg = small();
    cfg.write(&dir, 90).unwrap();
    let feed = ReplayFeed::open(&dir).unwrap();
    assert_eq!(feed.len(), cfg.frames);
    assert_eq!(feed.intrinsics, cfg.intrinsics());
    assert_eq!(feed.frame_rate, cfg.frame_rate);
    for (i, f) in feed.frames.iter().enumerate() {
        assert_eq!(f.t, cfg.time(i), "frame {i} time");
        assert_eq!(f.pose, cfg.pose(i), "frame {i} pose");
    }
    // The table plane is the frames' detected plane, at y = 0 facing up.
    let frame = feed.frame(2).unwrap();
    assert_eq!(frame.planes.len(), 1);
    let n = frame.planes[0].center_pose.y_axis.truncate();
    assert!((n - glam::Vec3::Y).length() < 1e-6, "normal {n}");
}

/// Centroid (pixel-centre coordinates) of the pixels within `tol` of `color`, and their count.
fn centroid_of_color(img: &FrameImage, color: [u8; 3], tol: i32) -> (DVec2, usize) {
    let (w, _) = img.size();
    let rgba = img.to_rgba8();
    let mut sum = DVec2::ZERO;
    let mut n = 0;
    for (k, p) in rgba.chunks_exact(4).enumerate() {
        let close = (0..3).all(|c| (i32::from(p[c]) - i32::from(color[c])).abs() <= tol);
        if close {
            let (i, j) = (k as u32 % w, k as u32 / w);
            sum += DVec2::new(f64::from(i) + 0.5, f64::from(j) + 0.5);
            n += 1;
        }
    }
    (sum / n.max(1) as f64, n)
}

#[test]
fn markers_show_where_the_read_back_pose_projects_them() {
    let dir = tmp("synth_markers");
    let cfg = SynthConfig {
        frames: 3,
        width: 320,
        height: 240,
        ..SynthConfig::default()
    };
    cfg.write(&dir, 95).unwrap();
    let feed = ReplayFeed::open(&dir).unwrap();
    let mut checked = 0;
    for i in 0..feed.len() {
        let frame = feed.frame(i).unwrap();
        for m in &MARKERS {
            let Some(px) = frame.project_world_point(m.center) else {
                continue;
            };
            // The disc's image is about 2 r f / d pixels across; it must be well inside the image.
            let k = &frame.intrinsics;
            let margin = 12.0;
            if px.x < margin
                || px.y < margin
                || px.x > f64::from(k.width) - margin
                || px.y > f64::from(k.height) - margin
            {
                continue;
            }
            let (c, n) = centroid_of_color(&frame.image, m.color, 50);
            // The disc at ~1 m covers 2·0.025·277/1 ≈ 14 px across: at least ~50 pixels in colour.
            assert!(
                n > 12,
                "frame {i} marker {:?}: only {n} pixels of its colour",
                m.color
            );
            let err = (c - px).length();
            // Perspective moves a disc's centroid from its centre's image by O((r/d)^2) pixels,
            // far below 0.5 px here; JPEG ringing at the disc's edge adds a little.
            assert!(
                err < 0.5,
                "frame {i} marker {:?}: centroid {c} vs projection {px} ({err} px)",
                m.color
            );
            eprintln!("frame {i} marker {:?}: {n} px, error {err:.3} px", m.color);
            checked += 1;
        }
    }
    assert!(checked >= 6, "only {checked} marker sightings checked");
}

#[test]
fn a_table_point_projects_to_the_pixel_that_shows_its_pattern() {
    // Without JPEG: the in-memory render. A pixel centre's ray meets the table at a point; that
    // point, projected forward through the pose, lands back on the same pixel centre, and the
    // pixel shows the marker colour wherever the whole pixel footprint lies inside a disc.
    let cfg = small();
    let k = cfg.intrinsics();
    let pose = cfg.pose(1);
    let img = render_view(&k, &pose, 1);
    let rgba = img.to_rgba8();
    let frame_proj = |p: DVec3| {
        let c = pose.to_dmat4().inverse().transform_point3(p);
        k.project_camera_point(c).unwrap()
    };
    for m in &MARKERS {
        let px = frame_proj(m.center);
        let (i, j) = (px.x.floor() as u32, px.y.floor() as u32);
        if i >= k.width || j >= k.height {
            continue;
        }
        let o = ((j * k.width + i) * 4) as usize;
        assert_eq!(
            &rgba[o..o + 3],
            &m.color,
            "marker at {} seen at pixel ({i}, {j})",
            m.center
        );
    }
    // A point just outside a disc's rim (1.5 radii from its centre) shows wood, not the marker.
    let m = MARKERS[0];
    let outside = m.center + DVec3::new(1.5 * MARKER_RADIUS + 0.01, 0.0, 0.0);
    let px = frame_proj(outside);
    let o = ((px.y.floor() as u32 * k.width + px.x.floor() as u32) * 4) as usize;
    assert_ne!(&rgba[o..o + 3], &m.color);
    let wood = ar::synth::table_color(outside.x, outside.z);
    for c in 0..3 {
        assert!(
            (f64::from(rgba[o + c]) - wood[c]).abs() <= 40.0,
            "wood colour channel {c}"
        );
    }
}

#[test]
fn camera_path_loops_without_a_jump_and_looks_at_the_table() {
    let cfg = SynthConfig::default();
    let n = cfg.frames;
    // Frame n (one past the end) is frame 0 again.
    let a = cfg.pose(0);
    let b = cfg.pose(n);
    assert!((a.position - b.position).length() < 1e-12);
    // Neighbouring frames move at most a few centimetres: hand-held, not teleporting.
    for i in 0..n {
        let d = (cfg.pose(i + 1).position - cfg.pose(i).position).length();
        assert!(d < 0.05, "frame {i} to {}: {d} m", i + 1);
        // The optical axis (-z) points down towards the table centre region.
        let p = cfg.pose(i);
        let fwd = p.rotation * DVec3::NEG_Z;
        let s = -p.position.y / fwd.y;
        let hit = p.position + s * fwd;
        assert!(
            hit.x.abs() < 0.2 && hit.z.abs() < 0.2,
            "frame {i} looks at {hit}"
        );
    }
}

#[test]
fn in_memory_frames_match_the_written_feed() {
    let dir = tmp("synth_memory");
    let cfg = small();
    cfg.write(&dir, 90).unwrap();
    let feed = ReplayFeed::open(&dir).unwrap();
    for i in 0..cfg.frames {
        let (mem, read) = (cfg.frame(i), feed.frame(i).unwrap());
        assert_eq!(mem.camera_to_world, read.camera_to_world);
        assert_eq!(mem.intrinsics, read.intrinsics);
        assert_eq!(mem.planes, read.planes);
        assert_eq!(mem.timestamp, read.timestamp);
        // The same picture, up to JPEG at quality 90: mean absolute error of a few levels.
        let (a, b) = (mem.image.to_rgba8(), read.image.to_rgba8());
        let mae = a
            .iter()
            .zip(&b)
            .map(|(x, y)| f64::from(x.abs_diff(*y)))
            .sum::<f64>()
            / a.len() as f64;
        assert!(mae < 4.0, "frame {i}: mean error {mae}");
    }
    // Looping playback picks the same frames as the reader.
    for t in [0.0, 0.07, 0.2, 0.31, 1.0, -0.05] {
        assert_eq!(cfg.index_at(t), feed.index_at(t), "t = {t}");
    }
}
