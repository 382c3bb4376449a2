//! The frame interface's geometry and image conversions against closed forms.

use ar::{FrameImage, Intrinsics, Pose};
use glam::{DVec3, DVec4};

#[test]
fn wgpu_projection_matches_the_pinhole_projection() {
    // An off-centre principal point and non-square pixels, so every term matters.
    let k = Intrinsics {
        fx: 500.0,
        fy: 520.0,
        cx: 300.0,
        cy: 260.0,
        width: 640,
        height: 480,
    };
    let (near, far) = (0.05, 50.0);
    let m = k.projection_wgpu(near, far);
    for p in [
        DVec3::new(0.3, -0.2, -1.5),
        DVec3::new(-1.0, 0.7, -3.0),
        DVec3::new(0.0, 0.0, -0.5),
    ] {
        let px = k.project_camera_point(p).unwrap();
        let clip = m * DVec4::new(p.x, p.y, p.z, 1.0);
        let ndc = clip.truncate() / clip.w;
        // NDC x right, y up, in [-1, 1]; pixels from the top-left corner.
        let u = (ndc.x + 1.0) * 0.5 * 640.0;
        let v = (1.0 - ndc.y) * 0.5 * 480.0;
        assert!(
            (u - px.x).abs() < 1e-9 && (v - px.y).abs() < 1e-9,
            "{p}: ({u}, {v}) vs {px}"
        );
    }
    let depth = |z: f64| {
        let c = m * DVec4::new(0.0, 0.0, z, 1.0);
        c.z / c.w
    };
    assert!(depth(-near).abs() < 1e-12);
    assert!((depth(-far) - 1.0).abs() < 1e-12);
    // A pixel's ray meets the projection again at that pixel.
    let px = glam::DVec2::new(123.5, 77.5);
    let back = k
        .project_camera_point(k.ray_through_pixel(px) * 2.7)
        .unwrap();
    assert!((back - px).length() < 1e-9);
    assert!(k.project_camera_point(DVec3::new(0.0, 0.0, 1.0)).is_none());
}

#[test]
fn hfov_intrinsics_put_the_image_edge_at_half_the_field_of_view() {
    let k = Intrinsics::from_hfov(400, 300, 60f64.to_radians());
    let edge = DVec3::new(30f64.to_radians().tan(), 0.0, -1.0);
    assert!((k.project_camera_point(edge).unwrap().x - 400.0).abs() < 1e-9);
}

#[test]
fn look_at_and_opencv_conversion() {
    let eye = DVec3::new(0.0, 1.0, 2.0);
    let p = Pose::look_at(eye, DVec3::ZERO, DVec3::Y);
    let fwd = p.rotation * DVec3::NEG_Z;
    assert!((fwd - (-eye).normalize()).length() < 1e-12);
    // The camera's right stays horizontal.
    assert!((p.rotation * DVec3::X).y.abs() < 1e-12);
    // The conversion is its own inverse.
    let back = p.to_opencv();
    assert!((Pose::from_opencv(back).rotation.dot(p.rotation).abs() - 1.0).abs() < 1e-12);
    // An OpenCV camera looks down its +z.
    assert!((back.rotation * DVec3::Z - fwd).length() < 1e-12);
}

#[test]
fn yuv_converts_with_bt601_full_range() {
    // 2×2 image, one chroma sample. Y = 76, Cb = 85, Cr = 255 is pure red in BT.601 full range
    // (Y = .299 R + .587 G + .114 B, Cb = 128 + (B - Y)/1.772, Cr = 128 + (R - Y)/1.402).
    let img = FrameImage::Yuv420 {
        width: 2,
        height: 2,
        y: vec![76, 76, 76, 76],
        y_row_stride: 2,
        u: vec![85],
        v: vec![255],
        uv_row_stride: 1,
        uv_pixel_stride: 1,
    };
    let rgba = img.to_rgba8();
    let px = &rgba[..4];
    assert!(
        px[0] >= 253 && px[1] <= 2 && px[2] <= 2 && px[3] == 255,
        "{px:?}"
    );
    let grey = FrameImage::Yuv420 {
        width: 2,
        height: 2,
        y: vec![128; 4],
        y_row_stride: 2,
        u: vec![128, 0],
        v: vec![128, 0],
        uv_row_stride: 2,
        uv_pixel_stride: 2,
    };
    assert_eq!(&grey.to_rgba8()[12..16], &[128, 128, 128, 255]);
}

#[test]
fn frame_images_become_the_renderers_camera_images() {
    use camera_image::CameraImage;
    // NV21 as ARCore gives it: V U pairs, chroma rows padded to 4 bytes.
    let vu = vec![200u8, 60, 0, 0, 10, 250];
    let img = FrameImage::Yuv420 {
        width: 2,
        height: 4,
        y: vec![1, 2, 3, 4, 5, 6, 7, 8],
        y_row_stride: 2,
        u: vu[1..].to_vec(),
        v: vu.clone(),
        uv_row_stride: 4,
        uv_pixel_stride: 2,
    };
    let Ok(CameraImage::Yuv420(p)) = img.to_camera_image() else {
        panic!("YUV planes stay YUV");
    };
    assert_eq!(p.y(), &[1, 2, 3, 4, 5, 6, 7, 8]);
    assert_eq!(p.uv(), &[60, 200, 250, 10]);
    // The CPU conversion is the same reference.
    assert_eq!(img.to_rgba8(), p.to_rgba8());
    let rgba = FrameImage::Rgba8 {
        width: 1,
        height: 1,
        data: vec![9, 8, 7, 255],
    };
    assert_eq!(
        rgba.to_camera_image(),
        Ok(CameraImage::Rgba(
            image::RgbaImage::from_raw(1, 1, vec![9, 8, 7, 255]).unwrap()
        ))
    );
}

#[test]
fn bad_frame_images_are_refused_with_a_sentence() {
    let short = FrameImage::Yuv420 {
        width: 4,
        height: 4,
        y: vec![0; 15],
        y_row_stride: 4,
        u: vec![128; 4],
        v: vec![128; 4],
        uv_row_stride: 2,
        uv_pixel_stride: 1,
    };
    let e = short.to_camera_image().unwrap_err();
    assert_eq!(
        e.message(),
        "YUV image 4×4: the y plane has 15 bytes, its layout needs 16"
    );
    // The CPU conversion does not panic on it: a black image.
    assert_eq!(short.to_rgba8(), [0, 0, 0, 255].repeat(16));
    let rgba = FrameImage::Rgba8 {
        width: 2,
        height: 1,
        data: vec![0; 7],
    };
    assert_eq!(
        rgba.to_camera_image().unwrap_err().message(),
        "RGBA image 2×1: needs 8 bytes, got 7"
    );
}
