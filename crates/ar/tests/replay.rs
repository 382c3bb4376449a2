//! Replay and TUM RGB-D readers: what they read, and one clear sentence (file and line) for each
//! kind of bad input.

use std::fs;
use std::path::{Path, PathBuf};

use ar::replay::FrameFileFormat;
use ar::{FrameImage, FrameSource, Intrinsics, Pose, ReplayFeed, ReplayPlayer, ReplayWriter};
use glam::{DQuat, DVec3};

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = fs::remove_dir_all(&d);
    fs::create_dir_all(&d).unwrap();
    d
}

fn grey(w: u32, h: u32, v: u8) -> FrameImage {
    FrameImage::Rgba8 {
        width: w,
        height: h,
        data: [v, v, v, 255].repeat((w * h) as usize),
    }
}

fn write_png(path: &Path, w: u32, h: u32) {
    image::RgbaImage::from_pixel(w, h, image::Rgba([10, 20, 30, 255]))
        .save(path)
        .unwrap();
}

/// A valid three-frame replay folder of 32×24 PNGs.
fn replay_folder(name: &str) -> PathBuf {
    let dir = tmp(name);
    let k = Intrinsics::from_hfov(32, 24, 1.0);
    let mut w = ReplayWriter::create(&dir, k, 10.0, None, FrameFileFormat::Png).unwrap();
    for i in 0..3 {
        let pose = Pose {
            position: DVec3::new(0.1 * f64::from(i), 0.5, 1.0),
            rotation: DQuat::from_rotation_y(0.1 * f64::from(i)),
        };
        w.write_frame(f64::from(i) * 0.1, &grey(32, 24, 40 * i as u8), &pose)
            .unwrap();
    }
    w.finish().unwrap();
    dir
}

/// Replaces line `line` (1-based) of `file`.
fn edit_line(file: &Path, line: usize, text: &str) {
    let s = fs::read_to_string(file).unwrap();
    let mut lines: Vec<String> = s.lines().map(String::from).collect();
    lines[line - 1] = text.to_string();
    fs::write(file, lines.join("\n") + "\n").unwrap();
}

fn err(dir: &Path) -> String {
    ReplayFeed::open(dir).unwrap_err().to_string()
}

#[test]
fn writer_output_reads_back() {
    let dir = replay_folder("replay_ok");
    let feed = ReplayFeed::open(&dir).unwrap();
    assert_eq!(feed.len(), 3);
    assert_eq!(feed.frames[2].pose.rotation, DQuat::from_rotation_y(0.2));
    assert_eq!(feed.frames[1].pose.position, DVec3::new(0.1, 0.5, 1.0));
    let f = feed.frame(2).unwrap();
    assert_eq!(f.image.to_rgba8()[..4], [80, 80, 80, 255]);
    assert_eq!(f.timestamp, 0.2);
    assert!(f.planes.is_empty());
}

#[test]
fn missing_frame_names_the_list_line_and_the_file() {
    let dir = replay_folder("replay_missing");
    fs::remove_file(dir.join("frames/000001.png")).unwrap();
    let e = err(&dir);
    assert!(e.contains("frames.txt line 3"), "{e}");
    assert!(e.contains("000001.png does not exist"), "{e}");
}

#[test]
fn wrong_image_size_names_the_line() {
    let dir = replay_folder("replay_size");
    write_png(&dir.join("frames/000002.png"), 30, 24);
    let e = err(&dir);
    assert!(e.contains("frames.txt line 4"), "{e}");
    assert!(e.contains("30×24") && e.contains("32×24"), "{e}");
}

#[test]
fn malformed_poses_name_the_line_and_field() {
    let dir = replay_folder("replay_pose");
    let frames = dir.join("frames.txt");
    edit_line(&frames, 2, "0 frames/000000.png 0 0 0 0 0 0");
    let e = err(&dir);
    assert!(
        e.contains("frames.txt line 2") && e.contains("found 8"),
        "{e}"
    );

    edit_line(&frames, 2, "0 frames/000000.png 0 abc 0 0 0 0 1");
    let e = err(&dir);
    assert!(
        e.contains("frames.txt line 2") && e.contains("ty is `abc`"),
        "{e}"
    );

    edit_line(&frames, 2, "0 frames/000000.png 0 0 0 0 0 0 2");
    let e = err(&dir);
    assert!(
        e.contains("frames.txt line 2") && e.contains("norm 2"),
        "{e}"
    );

    edit_line(&frames, 2, "0 frames/000000.png 0 0 NaN 0 0 0 1");
    let e = err(&dir);
    assert!(e.contains("tz is `NaN`"), "{e}");

    edit_line(&frames, 2, "0.15 frames/000000.png 0 0 0 0 0 0 1");
    let e = err(&dir);
    assert!(
        e.contains("frames.txt line 3") && e.contains("does not come after"),
        "{e}"
    );
}

#[test]
fn a_nearly_unit_quaternion_is_normalised() {
    let dir = replay_folder("replay_norm");
    edit_line(
        &dir.join("frames.txt"),
        2,
        "0 frames/000000.png 0 0 0 0 0 0 1.0001",
    );
    let feed = ReplayFeed::open(&dir).unwrap();
    assert!((feed.frames[0].pose.rotation.length() - 1.0).abs() < 1e-15);
}

#[test]
fn bad_session_json_names_the_line() {
    let dir = replay_folder("replay_session");
    let s = dir.join("session.json");
    let text = fs::read_to_string(&s)
        .unwrap()
        .replace("\"fx\":", "\"fx\": \"wide\", \"x\":");
    fs::write(&s, text).unwrap();
    let e = err(&dir);
    assert!(e.contains("session.json line "), "{e}");

    let dir = replay_folder("replay_session2");
    let s = dir.join("session.json");
    let text = fs::read_to_string(&s)
        .unwrap()
        .replace("\"width\": 32", "\"width\": 0");
    fs::write(&s, text).unwrap();
    let e = err(&dir);
    assert!(e.contains("session.json field `intrinsics`"), "{e}");

    let e = err(&tmp("replay_empty_dir"));
    assert!(e.contains("neither session.json"), "{e}");
}

#[test]
fn player_yields_a_frame_only_when_it_changes_and_loops() {
    let feed = ReplayFeed::open(&replay_folder("replay_player")).unwrap();
    assert!((feed.duration() - 0.3).abs() < 1e-12);
    let mut p = ReplayPlayer::new(feed);
    p.set_time(0.0);
    assert_eq!(p.next_frame().unwrap().unwrap().timestamp, 0.0);
    p.set_time(0.05);
    assert!(p.next_frame().unwrap().is_none());
    p.set_time(0.25);
    assert_eq!(p.next_frame().unwrap().unwrap().timestamp, 0.2);
    p.set_time(0.31); // 0.01 into the second loop
    assert_eq!(p.next_frame().unwrap().unwrap().timestamp, 0.0);
}

/// A TUM folder: poses every 10 ms from t = 100, images at the given times (all 32×24; the
/// override intrinsics.json keeps images small).
fn tum_folder(name: &str, image_times: &[f64]) -> PathBuf {
    let dir = tmp(name);
    fs::create_dir_all(dir.join("rgb")).unwrap();
    let mut gt = String::from("# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n");
    for k in 0..100 {
        let t = 100.0 + 0.01 * f64::from(k);
        gt += &format!("{t:.4} {} 0 0 0 0 0 1\n", f64::from(k));
    }
    fs::write(dir.join("groundtruth.txt"), gt).unwrap();
    let mut rgb = String::from("# color images\n# timestamp filename\n");
    for t in image_times {
        let f = format!("rgb/{t:.6}.png");
        write_png(&dir.join(&f), 32, 24);
        rgb += &format!("{t:.6} {f}\n");
    }
    fs::write(dir.join("rgb.txt"), rgb).unwrap();
    fs::write(
        dir.join("intrinsics.json"),
        r#"{"fx": 30, "fy": 30, "cx": 16, "cy": 12, "width": 32, "height": 24}"#,
    )
    .unwrap();
    dir
}

#[test]
fn tum_matches_each_image_to_the_nearest_pose_and_converts_the_camera_axes() {
    // 100.034 is nearest to the pose at 100.03 (x = 3); 100.0371 to 100.04 (x = 4); 101.5 has
    // no pose within 20 ms and is skipped.
    let dir = tum_folder("tum_ok", &[100.034, 100.0371, 101.5]);
    let feed = ReplayFeed::open(&dir).unwrap();
    assert_eq!(feed.len(), 2);
    assert_eq!(feed.frames[0].pose.position.x, 3.0);
    assert_eq!(feed.frames[1].pose.position.x, 4.0);
    assert!((feed.frames[1].t - 0.0031).abs() < 1e-9);
    // TUM's identity pose looks down world +z with y down; in the crate's convention the camera's
    // -z axis is then world +z and its +y axis world -y.
    let f = feed.frame(0).unwrap();
    let fwd = f.camera_to_world.transform_vector3(glam::Vec3::NEG_Z);
    let up = f.camera_to_world.transform_vector3(glam::Vec3::Y);
    assert!((fwd - glam::Vec3::Z).length() < 1e-6, "{fwd}");
    assert!((up + glam::Vec3::Y).length() < 1e-6, "{up}");
}

#[test]
fn tum_bad_inputs_name_file_and_line() {
    let dir = tum_folder("tum_gt", &[100.01, 100.02]);
    edit_line(&dir.join("groundtruth.txt"), 5, "100.02 0 0 0 0 0 1");
    let e = err(&dir);
    assert!(
        e.contains("groundtruth.txt line 5") && e.contains("found 7"),
        "{e}"
    );

    let dir = tum_folder("tum_missing", &[100.01, 100.02]);
    fs::remove_file(dir.join("rgb/100.020000.png")).unwrap();
    let e = err(&dir);
    assert!(
        e.contains("rgb.txt line 4") && e.contains("does not exist"),
        "{e}"
    );

    let dir = tum_folder("tum_size", &[100.01, 100.02]);
    write_png(&dir.join("rgb/100.010000.png"), 32, 20);
    let e = err(&dir);
    assert!(e.contains("rgb.txt line 3") && e.contains("32×20"), "{e}");

    let dir = tum_folder("tum_nopose", &[200.0]);
    let e = err(&dir);
    assert!(
        e.contains("rgb.txt") && e.contains("no image has a ground-truth pose"),
        "{e}"
    );
}

#[test]
fn tum_intrinsics_follow_the_sensor_in_the_folder_name() {
    let dir = tum_folder("rgbd_dataset_freiburg1_xyz", &[100.01]);
    fs::remove_file(dir.join("intrinsics.json")).unwrap();
    // Published fr1 calibration is for 640×480 images: our 32×24 PNGs are the wrong size.
    let e = err(&dir);
    assert!(e.contains("640×480"), "{e}");
    write_png(&dir.join("rgb/100.010000.png"), 640, 480);
    let k = ReplayFeed::open(&dir).unwrap().intrinsics;
    assert_eq!((k.fx, k.fy, k.cx, k.cy), (517.3, 516.5, 318.6, 255.3));
}

/// Three textured 160×120 frames as JPEGs (what `regatta replay synth` writes): enough image
/// data that a cut lands in it, not in the headers.
fn jpeg_folder(name: &str) -> PathBuf {
    let dir = tmp(name);
    let (width, height) = (160, 120);
    let k = Intrinsics::from_hfov(width, height, 1.0);
    let mut w = ReplayWriter::create(&dir, k, 10.0, None, FrameFileFormat::Jpeg(90)).unwrap();
    for i in 0..3u32 {
        let data = (0..width * height)
            .flat_map(|p| {
                let v = (((p % width) * 7) ^ ((p / width) * 13) ^ (i * 50)) as u8;
                [v, v / 2, 255 - v, 255]
            })
            .collect();
        let image = FrameImage::Rgba8 {
            width,
            height,
            data,
        };
        w.write_frame(f64::from(i) * 0.1, &image, &Pose::IDENTITY)
            .unwrap();
    }
    w.finish().unwrap();
    dir
}

/// Cuts the last tenth of `file` (its headers stay whole: the cut is in the image data).
fn truncate_tail(file: &Path) {
    let bytes = fs::read(file).unwrap();
    fs::write(file, &bytes[..bytes.len() * 9 / 10]).unwrap();
}

/// A truncated PNG or JPEG passed `replay check` (headers only), and the JPEG played, grey
/// below the cut. Every frame is decoded now, and a cut-short file is named with its line.
#[test]
fn truncated_frames_fail_the_decode_check() {
    for (dir, file) in [
        (replay_folder("replay_cut_png"), "frames/000001.png"),
        (jpeg_folder("replay_cut_jpg"), "frames/000001.jpg"),
    ] {
        let feed = ReplayFeed::open(&dir).unwrap();
        feed.check_decodes().unwrap();
        truncate_tail(&dir.join(file));
        let feed = ReplayFeed::open(&dir).unwrap();
        let e = feed.check_decodes().unwrap_err().to_string();
        assert!(
            e.contains("frames.txt line 3") && e.contains(file) && e.contains("is cut short"),
            "{e}"
        );
        // The player refuses the frame too.
        assert!(feed.frame(1).is_err());
        assert!(feed.frame(2).is_ok());
    }
}

#[test]
fn a_frame_that_is_a_directory_says_so() {
    let dir = replay_folder("replay_frame_dir");
    fs::remove_file(dir.join("frames/000001.png")).unwrap();
    fs::create_dir(dir.join("frames/000001.png")).unwrap();
    let e = err(&dir);
    assert!(
        e.contains("frames.txt line 3")
            && e.contains("000001.png is a directory, not an image file"),
        "{e}"
    );
}

/// File names from frames.txt and keys of session.json are input: their control characters
/// are escaped, so the message stays one line and cannot drive the terminal.
#[test]
fn control_characters_from_the_feed_are_escaped() {
    let dir = replay_folder("replay_ctrl");
    edit_line(
        &dir.join("frames.txt"),
        2,
        "0 frames/\u{1b}[2J\u{7}x.png 0 0 1 0 0 0 1",
    );
    let e = err(&dir);
    assert!(!e.chars().any(char::is_control), "{e:?}");
    assert!(
        e.contains("frames/\\u{1b}[2J\\u{7}x.png does not exist"),
        "{e}"
    );
    let dir = replay_folder("replay_ctrl_key");
    let session = fs::read_to_string(dir.join("session.json")).unwrap();
    fs::write(
        dir.join("session.json"),
        session.replacen('{', "{\"\\nname\": 1,", 1),
    )
    .unwrap();
    let e = err(&dir);
    assert!(!e.chars().any(char::is_control), "{e:?}");
    assert!(e.contains("unknown field `\\nname`"), "{e}");
}

/// A frame list that never ends (`"frames": "/dev/zero"`) is refused by its first bytes, not
/// read until memory runs out.
#[test]
fn an_endless_frame_list_is_refused_at_once() {
    if !Path::new("/dev/zero").exists() {
        return;
    }
    let dir = replay_folder("replay_endless_list");
    let session = fs::read_to_string(dir.join("session.json")).unwrap();
    fs::write(
        dir.join("session.json"),
        session.replace("\"frames.txt\"", "\"/dev/zero\""),
    )
    .unwrap();
    assert_eq!(
        err(&dir),
        "/dev/zero is not a feed's text file: byte 0 is NUL, so it is binary, not text"
    );
}
