//! GPU tests of the camera background on lavapipe: YUV 4:2:0 planes converted in the shader
//! against the CPU reference (`camera_image::Yuv420::to_rgba8`), and new frames, sizes and
//! kinds going into the same renderer through [`EffectsHandle::set_backdrop`]. Without an
//! adapter they skip, unless `REGATTA_REQUIRE_GPU=true`.

use glam::DVec3;

use super::backdrop::{Backdrop, CameraImage, DISPLAY_IDENTITY, StridedYuv420, Yuv420, YuvRange};
use super::passes::{ArConfig, EffectsHandle, add_effect_passes};
use super::{Effect, EffectSet};
use render::gpu::Gpu;
use render::{Camera, OFFSCREEN_FORMAT, RenderOptions, Renderer, Scene};

/// The screen, and every camera image that fills it pixel for pixel.
const SIZE: [u32; 2] = [64, 48];

/// The effects' table scene seen from above the water looking almost straight up: no water,
/// boat or mark in view, so the background fills every pixel.
fn sky_scene() -> Scene {
    let mut s = super::demo_table_scene(40.0);
    s.camera = Camera::look_at(
        DVec3::new(0.0, 10.0, 0.0),
        DVec3::new(0.0, 30.0, -2.0),
        500.0,
    );
    s
}

/// A deterministic byte sequence (64-bit LCG), for image content.
fn bytes(seed: u64, n: usize) -> Vec<u8> {
    let mut x = seed;
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 56) as u8
        })
        .collect()
}

/// A `size` YUV image as ARCore hands it over (NV21: V U interleaved, padded rows), normalised.
/// Luma is a gradient plus noise; the chroma is noise, so saturated colours clamp too.
fn yuv_image(size: [u32; 2], seed: u64) -> CameraImage {
    let (w, h) = (size[0] as usize, size[1] as usize);
    let [cw, ch] = Yuv420::chroma_size(size[0], size[1]).map(|v| v as usize);
    let (y_stride, c_stride) = (w + 7, 2 * cw + 5);
    let noise = bytes(seed, w * h);
    let mut y = vec![0u8; y_stride * h];
    for j in 0..h {
        for i in 0..w {
            let ramp = (i * 255 / w.max(2)) as u8 / 2 + (j * 255 / h.max(2)) as u8 / 4;
            y[j * y_stride + i] = ramp.wrapping_add(noise[j * w + i] / 4);
        }
    }
    let vu = bytes(seed + 1, c_stride * ch);
    let planes = StridedYuv420 {
        width: size[0],
        height: size[1],
        y: &y,
        y_row_stride: y_stride as u32,
        u: &vu[1..],
        v: &vu,
        uv_row_stride: c_stride as u32,
        uv_pixel_stride: 2,
    };
    CameraImage::Yuv420(Yuv420::from_strided(&planes, YuvRange::Full).expect("fits"))
}

/// An RGBA image of `size`: noise.
fn rgba_image(size: [u32; 2], seed: u64) -> CameraImage {
    let mut px = bytes(seed, (size[0] * size[1] * 4) as usize);
    px.chunks_exact_mut(4).for_each(|p| p[3] = 255);
    CameraImage::Rgba(image::RgbaImage::from_raw(size[0], size[1], px).expect("size"))
}

fn frame(image: CameraImage, display: [[f64; 3]; 2]) -> Backdrop<CameraImage> {
    let scene = sky_scene();
    Backdrop {
        camera: Backdrop::pinhole(&scene.camera, image.size()),
        image,
        display,
    }
}

/// A renderer with only the background effect over `image`, and its handle.
fn background_renderer(gpu: &Gpu, image: CameraImage) -> (Renderer, EffectsHandle) {
    let mut r = Renderer::new(
        gpu,
        OFFSCREEN_FORMAT,
        RenderOptions {
            keep_still_frames: true,
            ..RenderOptions::default()
        },
    );
    let cfg = ArConfig {
        effects: EffectSet::only(Effect::Background),
        ..ArConfig::default()
    };
    let handle = add_effect_passes(&mut r, gpu, cfg, frame(image, DISPLAY_IDENTITY));
    (r, handle)
}

/// One frame into a target the renderer may keep still frames of (it can copy to and from
/// it), read back.
fn draw(gpu: &Gpu, r: &mut Renderer, scene: &Scene) -> image::RgbaImage {
    let tex = render::gpu::texture_2d(
        &gpu.device,
        "camera test target",
        SIZE,
        OFFSCREEN_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
    );
    r.render(gpu, &tex.create_view(&Default::default()), SIZE, scene)
        .expect("render");
    gpu.read_texture(&tex).expect("read back")
}

/// Largest difference in any colour channel between `got` and the sRGB RGBA `want`.
fn worst(got: &image::RgbaImage, want: &image::RgbaImage) -> u8 {
    assert_eq!(got.dimensions(), want.dimensions());
    got.pixels()
        .zip(want.pixels())
        .flat_map(|(a, b)| (0..3).map(move |c| a[c].abs_diff(b[c])))
        .max()
        .unwrap_or(0)
}

/// The CPU reference converts to 8-bit R'G'B' (one rounding); the GPU converts in f32, decodes
/// to linear, and the sRGB target encodes back to 8 bits (a second rounding): at most one code
/// apart.
const TOLERANCE: u8 = 1;

#[test]
fn a_yuv_frame_draws_as_the_cpu_reference_converts_it() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let image = yuv_image(SIZE, 7);
    let want = image.to_rgba_image();
    let (mut r, _) = background_renderer(&gpu, image);
    let got = draw(&gpu, &mut r, &sky_scene());
    let err = worst(&got, &want);
    assert!(
        err <= TOLERANCE,
        "YUV background differs from the CPU conversion by {err} codes"
    );
    // And an RGBA frame through the same pass is the image itself.
    let image = rgba_image(SIZE, 3);
    let want = image.to_rgba_image();
    let (mut r, _) = background_renderer(&gpu, image);
    let err = worst(&draw(&gpu, &mut r, &sky_scene()), &want);
    assert!(err <= TOLERANCE, "RGBA background off by {err} codes");
}

#[test]
fn set_backdrop_redraws_the_same_renderer_over_the_new_image() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let scene = sky_scene();
    let first = yuv_image(SIZE, 11);
    let second = yuv_image(SIZE, 12);
    let (want1, want2) = (first.to_rgba_image(), second.to_rgba_image());
    assert!(worst(&want1, &want2) > 100, "the two images differ");
    let (mut r, handle) = background_renderer(&gpu, first);
    // Three frames of a still scene: the third is the kept copy.
    for _ in 0..3 {
        assert!(worst(&draw(&gpu, &mut r, &scene), &want1) <= TOLERANCE);
    }
    handle.set_backdrop(&gpu, frame(second, DISPLAY_IDENTITY));
    let got = draw(&gpu, &mut r, &scene);
    assert!(
        worst(&got, &want2) <= TOLERANCE,
        "after set_backdrop the background shows the new image (the scene stood still)"
    );
    // The display transform comes with the frame: mirrored left to right.
    let mirror = [[-1.0, 0.0, 1.0], [0.0, 1.0, 0.0]];
    handle.set_backdrop(&gpu, frame(yuv_image(SIZE, 12), mirror));
    let got = draw(&gpu, &mut r, &scene);
    let flipped = image::imageops::flip_horizontal(&want2);
    assert!(worst(&got, &flipped) <= TOLERANCE, "mirrored display");
}

#[test]
fn set_backdrop_takes_new_sizes_and_kinds() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let scene = sky_scene();
    // Start with a small RGBA frame, then YUV at the screen's size, then RGBA at it.
    let (mut r, handle) = background_renderer(&gpu, rgba_image([16, 12], 5));
    assert_eq!(handle.camera_image_size(), [16, 12]);
    draw(&gpu, &mut r, &scene);
    let yuv = yuv_image(SIZE, 21);
    let want = yuv.to_rgba_image();
    handle.set_backdrop(&gpu, frame(yuv, DISPLAY_IDENTITY));
    assert_eq!(handle.camera_image_size(), SIZE);
    let err = worst(&draw(&gpu, &mut r, &scene), &want);
    assert!(err <= TOLERANCE, "YUV after resize off by {err} codes");
    let rgba = rgba_image(SIZE, 22);
    let want = rgba.to_rgba_image();
    handle.set_backdrop(&gpu, frame(rgba, DISPLAY_IDENTITY));
    let err = worst(&draw(&gpu, &mut r, &scene), &want);
    assert!(err <= TOLERANCE, "RGBA after YUV off by {err} codes");
    // An odd-sized YUV frame (chroma 3×2 for 5×3 pixels) shown 1:1 in the top-left corner
    // (display maps the screen onto 64/5 × 48/3 image widths).
    let odd = yuv_image([5, 3], 23);
    let want = odd.to_rgba_image();
    let scale = [[64.0 / 5.0, 0.0, 0.0], [0.0, 48.0 / 3.0, 0.0]];
    handle.set_backdrop(&gpu, frame(odd, scale));
    let got = draw(&gpu, &mut r, &scene);
    let corner = image::imageops::crop_imm(&got, 0, 0, 5, 3).to_image();
    let err = worst(&corner, &want);
    assert!(err <= TOLERANCE, "odd-sized YUV off by {err} codes");
}
