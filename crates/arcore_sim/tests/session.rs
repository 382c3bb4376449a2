//! A whole AR session through the app's real FFI on the simulator: create, configure,
//! resume, update, the camera image read through the phone's frame-reading code, a tap's hit
//! test, pause, destroy; every object ARCore handed out is released.

mod common;

use ar::arcore::ffi::{FAR_M, NEAR_M};
use ar::arcore::{Event, SessionState, gl_projection_to_wgpu, hit_test, tap_ray};
use ar::{FrameImage, FrameSource, SynthConfig, TrackingState};
use camera_image::{CameraImage, Yuv420, YuvRange};
use common::{Sim, granted, start};
use glam::{DVec2, DVec3, DVec4};

/// The simulator's default feed (arcore_sim::feed::default_synth), rendered here as the truth.
fn truth() -> SynthConfig {
    arcore_sim::feed::default_synth()
}

#[test]
fn a_session_runs_reads_phone_strided_yuv_and_releases_everything() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(granted());
    let mut state = start(&mut core);
    assert_eq!(state, SessionState::Running);
    // Portrait phone: rotation 0, a 1080 × 2160 view.
    core.set_display_geometry(0, 1080, 2160);
    assert_eq!(core.update(), None, "ArSession_update succeeds");
    let frame = core.next_frame().expect("reads").expect("a camera image");
    assert_eq!(sim.frame_index(), 0);

    // The image came as a phone gives it: 640-px rows with stride 704, NV21 chroma.
    let FrameImage::Yuv420 {
        width,
        height,
        y_row_stride,
        uv_row_stride,
        uv_pixel_stride,
        ref y,
        ..
    } = frame.image
    else {
        panic!("ARCore's CPU image is YUV");
    };
    assert_eq!((width, height), (640, 480));
    assert_eq!(
        (y_row_stride, uv_row_stride, uv_pixel_stride),
        (704, 704, 2)
    );
    assert_eq!(y.len(), 479 * 704 + 640, "the last row is not padded");

    // Normalised by camera_image, it is exactly the replay frame's BT.601 encoding, and its
    // pixels are the BT.601 reference conversion of that.
    let replay = truth().frame(0);
    let reference = Yuv420::from_rgba(&replay.image.to_rgba_image(), YuvRange::Full).unwrap();
    let CameraImage::Yuv420(read) = frame.image.to_camera_image().unwrap() else {
        panic!("YUV stays YUV");
    };
    assert_eq!(read.y(), reference.y());
    assert_eq!(read.uv(), reference.uv());
    assert_eq!(read.to_rgba8(), reference.to_rgba8());
    // And close to the rendered RGB on average (4:2:0 chroma smears colour edges only).
    let rgb = replay.image.to_rgba8();
    let mean: f64 = read
        .to_rgba8()
        .iter()
        .zip(&rgb)
        .map(|(a, b)| f64::from(a.abs_diff(*b)))
        .sum::<f64>()
        / rgb.len() as f64;
    assert!(mean < 3.0, "mean channel difference {mean}");

    // Pose, intrinsics and the table as the replay has them.
    assert!(
        frame
            .camera_to_world
            .abs_diff_eq(replay.camera_to_world, 1e-5)
    );
    let k = truth().intrinsics();
    assert!((frame.intrinsics.fx - k.fx).abs() < 1e-3 && (frame.intrinsics.cy - k.cy).abs() < 1e-3);
    assert_eq!(frame.tracking, TrackingState::Tracking);
    assert_eq!(frame.planes.len(), 1);
    assert!(
        frame.planes[0]
            .center_pose
            .abs_diff_eq(replay.planes[0].center_pose, 1e-6)
    );

    // A tap where the table's centre shows hits the table there.
    let centre = frame
        .project_world_point(DVec3::ZERO)
        .expect("the table is in view");
    let (_, point) = hit_test(&tap_ray(&frame, centre), &frame.planes).expect("the table is hit");
    assert!(point.length() < 1e-4, "hit at {point}");

    // The display camera: a point projects to the screen pixel whose image UV (through the
    // display transform) is where the image camera sees it.
    let view = core.view.expect("the display camera is read");
    let clip =
        gl_projection_to_wgpu(view.projection_gl) * view.view * DVec4::new(0.1, 0.0, 0.2, 1.0);
    let screen_uv = DVec2::new(0.5 + 0.5 * clip.x / clip.w, 0.5 - 0.5 * clip.y / clip.w);
    let image_uv = frame
        .display_uv
        .transform_point2(screen_uv.as_vec2())
        .as_dvec2();
    let seen = frame
        .project_world_point(DVec3::new(0.1, 0.0, 0.2))
        .unwrap()
        / DVec2::new(640.0, 480.0);
    assert!((image_uv - seen).length() < 1e-4, "{image_uv} vs {seen}");
    assert!(view.projection_gl.x_axis.x > 0.0 && NEAR_M < FAR_M);

    // Pause (the app goes to the background), then the session ends.
    core.drive(&mut state, Event::AppPaused);
    assert_eq!(state, SessionState::Paused);
    assert_eq!(sim.calls("ArSession_pause"), 1);
    core.close().expect("a session to close").join().unwrap();
    drop(core);
    assert_eq!(sim.calls("ArSession_destroy"), 1);
    assert_eq!(
        sim.live(None),
        0,
        "every acquire released, every object destroyed"
    );
    assert!(sim.calls("ArImage_release") >= 1 && sim.calls("ArTrackable_release") >= 1);
}

#[test]
fn the_display_rotation_turns_the_view_and_the_image_transform() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(granted());
    start(&mut core);
    // Landscape: rotation 1 (90°), a 2160 × 1080 view.
    core.set_display_geometry(1, 2160, 1080);
    core.update();
    let frame = core.next_frame().unwrap().unwrap();
    let view = core.view.unwrap();
    // Landscape with a landscape sensor: the image is shown upright, cropped top and bottom.
    let uv = |x: f32, y: f32| frame.display_uv.transform_point2(glam::Vec2::new(x, y));
    assert!(uv(0.0, 0.5).abs_diff_eq(glam::Vec2::new(0.0, 0.5), 1e-5));
    assert!(uv(1.0, 0.5).abs_diff_eq(glam::Vec2::new(1.0, 0.5), 1e-5));
    let seen = frame
        .project_world_point(DVec3::new(-0.2, 0.0, 0.1))
        .unwrap()
        / DVec2::new(640.0, 480.0);
    let clip =
        gl_projection_to_wgpu(view.projection_gl) * view.view * DVec4::new(-0.2, 0.0, 0.1, 1.0);
    let screen_uv = DVec2::new(0.5 + 0.5 * clip.x / clip.w, 0.5 - 0.5 * clip.y / clip.w);
    let image_uv = frame
        .display_uv
        .transform_point2(screen_uv.as_vec2())
        .as_dvec2();
    assert!((image_uv - seen).length() < 1e-4, "{image_uv} vs {seen}");
    drop(core);
}
