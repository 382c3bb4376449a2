//! GPU tests on lavapipe (CI) or any adapter: device setup on two backends and a frame that
//! shows a sea with boats (the WGSL's parity with ocean's f64 reference: `tests/parity.rs`).
//! Without an adapter they print "skipped: no GPU adapter", unless REGATTA_REQUIRE_GPU=true,
//! where they fail.

use glam::{DVec2, DVec3};
use ocean::WaveSet;
use render::gpu::{test_gpu, test_gpu_on};
use render::{Boat, Camera, RenderOptions, Renderer, Scene};

fn scene(t: f64) -> Scene {
    let boats = vec![
        Boat {
            position: DVec2::new(0.0, 0.0),
            heading: 0.6,
            colour: [0.8, 0.05, 0.05],
            length: 10.0,
        },
        Boat {
            position: DVec2::new(-18.0, 12.0),
            heading: 0.9,
            colour: [0.05, 0.1, 0.7],
            length: 10.0,
        },
    ];
    render::golden::test_scene(t, boats)
}

#[test]
fn a_frame_shows_sky_above_water_and_runs_every_pass() {
    let Some(gpu) = test_gpu() else { return };
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let (img, report) = render::render_image(&gpu, &mut r, &scene(100.0), [128, 96]).unwrap();
    for p in &report.passes {
        assert!(p.ran, "{} skipped: {}", p.name, p.reason);
        assert!(p.triangles > 0, "{}", p.name);
    }
    // The water's triangles, as the GPU counted them (pipeline statistics, where the adapter
    // has them; lavapipe does), are the clip-map's triangles counted on the CPU.
    let water = report.passes.iter().find(|p| p.name == "water").unwrap();
    let mesh: u64 = report
        .clipmap
        .per_level
        .iter()
        .map(|l| l.stats.triangles)
        .sum();
    if report.triangles_source == "pipeline_statistics" {
        assert_eq!(water.triangles, mesh);
    } else {
        eprintln!("no pipeline statistics on {}", report.adapter);
    }
    // Top row is sky (bright, bluish); bottom row is water (darker than the sky).
    let lum = |y: u32| {
        (0..img.width())
            .map(|x| {
                let p = img.get_pixel(x, y);
                f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2])
            })
            .sum::<f64>()
            / f64::from(img.width())
    };
    let (top, bottom) = (lum(0), lum(img.height() - 1));
    assert!(top > bottom + 60.0, "sky {top} vs water {bottom}");
    let sky = img.get_pixel(64, 0);
    assert!(sky[2] > sky[0], "sky should be blue: {sky:?}");
}

#[test]
fn gl_backend_sets_up_and_renders_too() {
    // The second path: OpenGL (EGL on Mesa). Phones without Vulkan use it.
    let Some(gpu) = test_gpu_on(wgpu::Backends::GL) else {
        return;
    };
    assert_eq!(gpu.adapter.get_info().backend, wgpu::Backend::Gl);
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let (img, report) = render::render_image(&gpu, &mut r, &scene(5.0), [64, 48]).unwrap();
    assert!(report.passes.iter().any(|p| p.name == "water" && p.ran));
    assert_ne!(img.get_pixel(32, 0), img.get_pixel(32, 47));
}

#[test]
fn every_phase_a_frame_sends_is_reduced_to_zero_two_pi() {
    // Phones' sin() is only accurate near [−π, π]: the guard is that θ0 ∈ [0, 2π) always, for
    // long races and far origins, as the frame hands them to the GPU.
    let sea = WaveSet::default_sea();
    for t in [0.0, 1e3, 1e6, 3.6e4 * 10.0, 9.9e6] {
        let mut s = scene(t);
        s.sea = sea.clone().into();
        s.camera.eye += DVec3::new(9000.0, 0.0, -8000.0);
        s.camera.target += DVec3::new(9000.0, 0.0, -8000.0);
        s.play_area = [-1e5, -1e5, 1e5, 1e5];
        let f = render::frame::FrameContext::new(&s, [64, 64], 1.0);
        assert_eq!(f.waves.len(), sea.waves.len());
        for w in &f.waves {
            assert!(
                w.phase0 >= 0.0 && w.phase0 < std::f32::consts::TAU,
                "t = {t}: phase {}",
                w.phase0
            );
        }
        // The local eye and every vertex stay small: no large coordinate reaches the GPU.
        assert!(f.uniform.eye[0].abs() < 1e3 && f.uniform.eye[2].abs() < 1e3);
        let far = f
            .mesh
            .vertices
            .iter()
            .map(|v| v.rest[0].abs().max(v.rest[1].abs()))
            .fold(0.0f32, f32::max);
        assert!(f64::from(far) <= 2.0 * f.clipmap.half_extent(f.clipmap.levels() - 1));
    }
}

#[test]
fn wakes_draw_foam_behind_a_boat_and_are_recorded() {
    use ocean::wake::{TrackSample, Wake, WakeParams};
    let Some(gpu) = test_gpu() else { return };
    // A boat sailing east at 5 m/s for a minute, ending at the origin.
    let track: Vec<TrackSample> = (0..=60)
        .map(|i| TrackSample {
            t: f64::from(i),
            x: 5.0 * f64::from(i) - 300.0,
            z: 0.0,
        })
        .collect();
    let wake = Wake::new(&[&track], WakeParams::default()).unwrap();
    let mut s = scene(60.0);
    std::sync::Arc::make_mut(&mut s.sea).waves.truncate(1);
    s.boats.truncate(1);
    s.boats[0].heading = std::f64::consts::FRAC_PI_2;
    s.marks.clear();
    s.camera = Camera::look_at(
        DVec3::new(-20.0, 25.0, 30.0),
        DVec3::new(-25.0, 0.0, 0.0),
        5000.0,
    );
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let (plain, report) = render::render_image(&gpu, &mut r, &s, [96, 64]).unwrap();
    assert!(report.wakes.is_none());
    r.set_wake(Some(std::sync::Arc::new(wake)));
    let (waked, report) = render::render_image(&gpu, &mut r, &s, [96, 64]).unwrap();
    let w = report.wakes.expect("the frame records its wakes");
    assert!(w.sources > 10, "{w:?}");
    let water = report.passes.iter().find(|p| p.name == "water").unwrap();
    assert!(water.reason.contains("wake sources"), "{}", water.reason);
    // The wake whitens the water behind the boat: pixels brighter by > 40 levels (of 765).
    let lum = |p: &image::Rgba<u8>| i32::from(p[0]) + i32::from(p[1]) + i32::from(p[2]);
    let whiter = plain
        .pixels()
        .zip(waked.pixels())
        .filter(|(a, b)| lum(b) > lum(a) + 40)
        .count();
    assert!(whiter > 30, "only {whiter} pixels whiter with the wake");
}

/// A paused timeline under a still camera: the second identical frame is kept, the third is a
/// copy of it (nothing drawn, every pass recorded as skipped with the reason), and any change
/// of race time draws again.
#[test]
fn a_still_frame_is_re_presented_not_drawn_again() {
    let Some(gpu) = test_gpu() else { return };
    let size = [96, 64];
    let copy = wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST;
    let (mut renderer, target, view) = keeping_renderer(&gpu, size, copy);
    let paused = scene(120.0);
    let first = renderer.render(&gpu, &view, size, &paused).unwrap();
    let drawn = gpu.read_texture(&target).unwrap();
    let second = renderer.render(&gpu, &view, size, &paused).unwrap();
    assert!(!first.reused_last_frame && !second.reused_last_frame);
    assert!(second.passes.iter().any(|p| p.ran));
    // Spoil the target: a re-presented frame must put the kept pixels back.
    gpu.queue.write_texture(
        target.as_image_copy(),
        &vec![255u8; (size[0] * size[1] * 4) as usize],
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * size[0]),
            rows_per_image: Some(size[1]),
        },
        target.size(),
    );
    let third = renderer.render(&gpu, &view, size, &paused).unwrap();
    assert!(third.reused_last_frame);
    assert!(
        third
            .passes
            .iter()
            .all(|p| !p.ran && p.reason == render::FRAME_REUSED)
    );
    assert_eq!(third.triangles, 0);
    assert_eq!(gpu.read_texture(&target).unwrap(), drawn);
    // The timeline moves on: drawn again, and it looks different.
    let moved = renderer.render(&gpu, &view, size, &scene(121.0)).unwrap();
    assert!(!moved.reused_last_frame && moved.passes.iter().any(|p| p.ran));
    assert_ne!(gpu.read_texture(&target).unwrap(), drawn);
    // A changed input outside the scene (here: invalidate) is drawn too.
    renderer.render(&gpu, &view, size, &scene(121.0)).unwrap();
    renderer.invalidate();
    let after = renderer.render(&gpu, &view, size, &scene(121.0)).unwrap();
    assert!(!after.reused_last_frame);
}

/// Without copy usages on the target (or without the option) every frame is drawn.
#[test]
fn frames_are_always_drawn_when_they_cannot_be_kept() {
    let Some(gpu) = test_gpu() else { return };
    let size = [32, 32];
    let (mut renderer, _target, view) = keeping_renderer(&gpu, size, wgpu::TextureUsages::empty());
    for _ in 0..3 {
        let r = renderer.render(&gpu, &view, size, &scene(5.0)).unwrap();
        assert!(!r.reused_last_frame && r.passes.iter().any(|p| p.ran));
    }
}

/// A renderer that keeps still frames, and a `size` target with `usage` besides rendering.
fn keeping_renderer(
    gpu: &render::Gpu,
    size: [u32; 2],
    usage: wgpu::TextureUsages,
) -> (Renderer, wgpu::Texture, wgpu::TextureView) {
    let renderer = Renderer::new(
        gpu,
        render::OFFSCREEN_FORMAT,
        RenderOptions {
            keep_still_frames: true,
            ..Default::default()
        },
    );
    let target = render::gpu::texture_2d(
        &gpu.device,
        "target",
        size,
        render::OFFSCREEN_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
    );
    let view = target.create_view(&Default::default());
    (renderer, target, view)
}

/// A frame drawn at half scale and stretched onto the target: the record gives the drawn size,
/// and the stretched picture, averaged back over 2×2 pixels, is the frame drawn directly at
/// that size (within bilinear filtering's blur).
#[test]
fn a_frame_drawn_at_half_scale_is_stretched_onto_the_target() {
    let Some(gpu) = test_gpu() else { return };
    let scene = scene(300.0);
    let mut half = Renderer::new(
        &gpu,
        render::OFFSCREEN_FORMAT,
        RenderOptions {
            render_scale: 0.5,
            ..Default::default()
        },
    );
    let (big, report) = render::render_image(&gpu, &mut half, &scene, [128, 96]).unwrap();
    assert_eq!(report.size, [64, 48]);
    assert!(report.passes.iter().any(|p| p.ran));
    let mut direct = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let (small, _) = render::render_image(&gpu, &mut direct, &scene, [64, 48]).unwrap();
    let mut diff = 0.0f64;
    for y in 0..48 {
        for x in 0..64 {
            for c in 0..3 {
                let avg: f64 = [(0, 0), (1, 0), (0, 1), (1, 1)]
                    .iter()
                    .map(|(dx, dy)| f64::from(big.get_pixel(2 * x + dx, 2 * y + dy)[c]))
                    .sum::<f64>()
                    / 4.0;
                diff += (avg - f64::from(small.get_pixel(x, y)[c])).abs();
            }
        }
    }
    let mean = diff / (64.0 * 48.0 * 3.0);
    assert!(mean < 6.0, "mean difference {mean} levels");
}

/// A camera under the sea surface, looking slightly down: the frame is drawn from just above
/// the surface instead (sky above, water below), and the record says by how much it rose.
/// Before, the surface's underside filled the top of the picture and sky the bottom.
#[test]
fn a_camera_under_the_water_is_raised_above_the_surface() {
    let Some(gpu) = test_gpu() else { return };
    let mut s = scene(100.0);
    s.camera = Camera::look_at(
        DVec3::new(0.0, -5.0, 40.0),
        DVec3::new(0.0, -9.0, -60.0),
        5000.0,
    );
    let surface = s.sea.height_at([0.0, 40.0], s.t).unwrap();
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let (img, report) = render::render_image(&gpu, &mut r, &s, [96, 64]).unwrap();
    let raised = report
        .camera_raised_m
        .expect("the record says the camera was raised");
    let want = surface + render::scene::CAMERA_CLEARANCE_M + 5.0;
    assert!((raised - want).abs() < 1e-9, "{raised} vs {want}");
    let lum = |y: u32| {
        (0..img.width())
            .map(|x| {
                img.get_pixel(x, y).0[..3]
                    .iter()
                    .map(|&c| f64::from(c))
                    .sum::<f64>()
            })
            .sum::<f64>()
            / f64::from(img.width())
    };
    let (top, bottom) = (lum(0), lum(img.height() - 1));
    assert!(top > bottom + 60.0, "sky {top} vs water {bottom}");
    // A camera above the water is left where it is.
    let (_, report) = render::render_image(&gpu, &mut r, &scene(100.0), [96, 64]).unwrap();
    assert_eq!(report.camera_raised_m, None);
}
