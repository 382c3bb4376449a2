//! A fleet at scale and device errors: 1,000 boats bunched at a start line draw (the wake
//! buffers stay within the device's limits and the budget, the least visible sources dropped
//! with the bound stated), and a device error fails one frame, never the app. Lavapipe in CI;
//! skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::{DVec2, DVec3};
use ocean::wake::{TrackSample, Wake, WakeParams};
use render::frame::{FrameContext, Pass};
use render::gpu::test_gpu;
use render::{Boat, Camera, Gpu, RenderOptions, Renderer};

/// 1,000 boats in four rows of 250, 2 m apart, behind a start line at z = 0, each sailing
/// north at 3 m/s for the 30 s before the start.
fn bunched_fleet() -> (Vec<Vec<TrackSample>>, Vec<Boat>) {
    let mut tracks = Vec::new();
    let mut boats = Vec::new();
    for k in 0..1000 {
        let x = -250.0 + 2.0 * f64::from(k % 250);
        let z = 6.0 * f64::from(k / 250);
        tracks.push(
            (0..=30)
                .map(|i| TrackSample {
                    t: f64::from(i - 30),
                    x,
                    z: z - 3.0 * f64::from(i - 30),
                })
                .collect(),
        );
        boats.push(Boat {
            position: DVec2::new(x, z),
            heading: 0.0,
            colour: [0.9, 0.9, 0.9],
            length: 4.0,
        });
    }
    (tracks, boats)
}

#[test]
fn a_thousand_boats_bunched_at_a_start_draw_within_the_wake_buffer_cap() {
    let Some(gpu) = test_gpu() else { return };
    let (tracks, boats) = bunched_fleet();
    let refs: Vec<&[TrackSample]> = tracks.iter().map(Vec::as_slice).collect();
    let wake = Wake::new(&refs, WakeParams::default()).unwrap();
    let mut scene = render::golden::test_scene(0.0, boats);
    scene.marks.clear();
    scene.camera = Camera::look_at(
        DVec3::new(0.0, 40.0, 120.0),
        DVec3::new(0.0, 0.0, 0.0),
        5000.0,
    );
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    r.set_wake(Some(Arc::new(wake)));
    // A phone tier's budget (the band limit lets the whole fleet fit the desktop's 64 MiB).
    let budget = 4 << 20;
    r.set_wake_buffer_budget(budget);
    let (img, report) = render::render_image(&gpu, &mut r, &scene, [64, 48]).expect("drawn");
    let water = report.passes.iter().find(|p| p.name == "water").unwrap();
    assert!(water.ran, "{}", water.reason);
    let w = report.wakes.expect("the frame records its wakes");
    eprintln!("{w:?}\n{}", water.reason);
    let limits = gpu.device.limits();
    let cap = budget
        .min(limits.max_storage_buffer_binding_size)
        .min(limits.max_buffer_size);
    assert_eq!(w.buffer_cap_bytes, cap);
    // The least visible sources were dropped, counted, and the error they cause bounded.
    assert!(w.dropped > 0 && w.sources > 0, "{w:?}");
    assert!(w.drop_bound_m > 0.0 && w.drop_bound_m.is_finite(), "{w:?}");
    assert!(
        water.reason.contains(&format!("{} dropped", w.dropped))
            && water.reason.contains("height error ≤"),
        "{}",
        water.reason
    );
    // The frame is a picture: sky above, water below.
    let (top, bottom) = (img.get_pixel(32, 0), img.get_pixel(32, 47));
    assert_ne!(top, bottom);
    // Without the budget, only the device's limits: this fleet once needed more than they
    // allow (the frame that panicked before); with each clip-map level's band limit its bins
    // list few enough pairs to fit whole, and the frame draws every source.
    r.set_wake_buffer_budget(u64::MAX);
    let (_, report) = render::render_image(&gpu, &mut r, &scene, [64, 48]).expect("drawn");
    let w = report.wakes.expect("the frame records its wakes");
    eprintln!("{w:?}");
    assert_eq!(
        w.buffer_cap_bytes,
        limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size)
    );
    assert_eq!((w.dropped, w.sources), (0, 120_000), "{w:?}");
}

/// A pass that asks the device for a buffer larger than it allows, once.
struct BrokenOnce(Arc<AtomicBool>);

impl Pass for BrokenOnce {
    fn name(&self) -> &'static str {
        "broken"
    }
    fn condition(&self) -> &'static str {
        "always"
    }
    fn plan(&self, _: &FrameContext) -> Result<String, String> {
        Ok("always".into())
    }
    fn prepare(&mut self, gpu: &Gpu, _: &FrameContext) {
        if self.0.swap(false, Ordering::SeqCst) {
            too_large_buffer(gpu);
        }
    }
    fn draw(&self, _: &mut wgpu::RenderPass<'_>) -> u64 {
        0
    }
}

fn too_large_buffer(gpu: &Gpu) -> wgpu::Buffer {
    let size = gpu.device.limits().max_buffer_size.next_multiple_of(4) + 4;
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("too large"),
        size,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    })
}

#[test]
fn a_device_error_fails_one_frame_not_the_app() {
    let Some(gpu) = test_gpu() else { return };
    // Outside a frame: logged by the device's handler (wgpu's default one panics).
    drop(too_large_buffer(&gpu));
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    r.add_pass(Box::new(BrokenOnce(Arc::new(AtomicBool::new(true)))));
    let scene = render::golden::test_scene(10.0, Vec::new());
    let err = render::render_image(&gpu, &mut r, &scene, [32, 24]).unwrap_err();
    assert!(err.0.starts_with("the GPU refused this frame"), "{err}");
    assert!(!err.0.contains('\n'), "{err}");
    // The next frame draws.
    let (_, report) = render::render_image(&gpu, &mut r, &scene, [32, 24]).expect("next frame");
    assert!(report.passes.iter().any(|p| p.name == "water" && p.ran));
}
