//! GPU tests of the effects on lavapipe: the WGSL optics against the f64 reference, and golden
//! images of each effect. Without an adapter they skip, unless `REGATTA_REQUIRE_GPU=true`.
//!
//! Regenerate the golden images after an intended change of the picture:
//! `REGATTA_UPDATE_GOLDEN=1 cargo test -p render --lib effects::gpu_tests`, then look at them.

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use wgpu::util::DeviceExt;

use super::camera_frame::CameraFrame;
use super::passes::{ArConfig, OFFSCREEN_REUSED, add_effect_passes};
use super::{Effect, EffectSet};
use crate::golden::compare;
use crate::gpu::{Gpu, test_gpu};
use crate::optics::{N_AIR, N_WATER, fresnel, refract, schlick};
use crate::{OFFSCREEN_FORMAT, RenderOptions, Renderer, Scene, render_image};

const SIZE: [u32; 2] = [128, 96];

fn table_scene(t: f64) -> Scene {
    super::demo_table_scene(t)
}

fn config(effects: EffectSet) -> ArConfig {
    ArConfig {
        effects,
        table_depth: 3.0,
        ..ArConfig::default()
    }
}

fn frame_for(scene: &Scene, cfg: &ArConfig) -> CameraFrame {
    let [ax, az, bx, bz] = scene.play_area;
    let centre = DVec2::new(ax + bx, az + bz) / 2.0;
    CameraFrame::synthetic(
        &scene.camera,
        SIZE,
        cfg.table_depth,
        centre,
        cfg.ring_radius_for(scene.play_area),
        4.0,
    )
}

fn render_with(gpu: &Gpu, scene: &Scene, effects: Option<EffectSet>) -> image::RgbaImage {
    let mut r = Renderer::new(gpu, OFFSCREEN_FORMAT, RenderOptions::default());
    if let Some(effects) = effects {
        let cfg = config(effects);
        let frame = frame_for(scene, &cfg);
        add_effect_passes(&mut r, gpu, cfg, frame);
    }
    render_image(gpu, &mut r, scene, SIZE).expect("render").0
}

fn golden(name: &str, effects: EffectSet) {
    let Some(gpu) = test_gpu() else { return };
    let img = render_with(&gpu, &table_scene(40.0), Some(effects));
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("src/effects/golden")
        .join(format!("{name}.png"));
    crate::golden::check(&path, &img).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn golden_effect_background() {
    golden("fx_background", EffectSet::only(Effect::Background));
}
#[test]
fn golden_effect_reflection() {
    golden(
        "fx_reflection",
        EffectSet::only(Effect::Background).with(Effect::Reflection),
    );
}
#[test]
fn golden_effect_refraction() {
    golden(
        "fx_refraction",
        EffectSet::only(Effect::Background).with(Effect::Refraction),
    );
}
#[test]
fn golden_effect_caustics() {
    golden(
        "fx_caustics",
        EffectSet::only(Effect::Background).with(Effect::Caustics),
    );
}
#[test]
fn golden_effect_flowmap() {
    golden(
        "fx_flowmap",
        EffectSet::only(Effect::Background).with(Effect::FlowMap),
    );
}
#[test]
fn golden_effect_all() {
    golden("fx_all", EffectSet::ALL);
}

#[test]
fn each_effect_changes_the_picture_and_none_changes_nothing() {
    let Some(gpu) = test_gpu() else { return };
    let scene = table_scene(40.0);
    let water_only = render_with(&gpu, &scene, None);
    let none = render_with(&gpu, &scene, Some(EffectSet::NONE));
    assert_eq!(
        compare(&water_only, &none),
        (0.0, 0.0),
        "no effect, no change"
    );
    let base = render_with(&gpu, &scene, Some(EffectSet::only(Effect::Background)));
    assert!(
        compare(&base, &water_only).0 > 5.0,
        "the camera frame replaces the sky"
    );
    for e in [
        Effect::Reflection,
        Effect::Refraction,
        Effect::Caustics,
        Effect::FlowMap,
    ] {
        let img = render_with(
            &gpu,
            &scene,
            Some(EffectSet::only(Effect::Background).with(e)),
        );
        let (mean, _) = compare(&img, &base);
        assert!(mean > 0.5, "{e} changes the picture: {mean:.2}");
    }
    // Caustics scrub with race time: a second later the light on the table has moved.
    let fx = Some(EffectSet::only(Effect::Background).with(Effect::Caustics));
    let a = render_with(&gpu, &scene, fx);
    let b = render_with(&gpu, &table_scene(41.0), fx);
    let c = render_with(&gpu, &table_scene(40.0), fx);
    assert!(compare(&a, &b).0 > 0.5);
    assert_eq!(
        compare(&a, &c),
        (0.0, 0.0),
        "the same time gives the same picture"
    );
}

/// Evaluate the WGSL optics on the GPU for `cosines`: (R full, Schlick, refracted x, y) per
/// cosine, air → water, ray in the x–y plane through a level surface.
fn wgsl_optics(gpu: &Gpu, cosines: &[f32]) -> Vec<[f32; 4]> {
    let device = &gpu.device;
    let src = format!(
        "{}\n{}",
        crate::shader::OPTICS,
        r#"
@group(0) @binding(0) var<storage, read> input: array<f32>;
@group(0) @binding(1) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(64)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&input) { return; }
    let c = input[id.x];
    let s = sqrt(max(1.0 - c * c, 0.0));
    let t = refract_dir(vec3<f32>(s, -c, 0.0), vec3<f32>(0.0, 1.0, 0.0), N_AIR, N_WATER);
    output[id.x] = vec4<f32>(fresnel_reflectance(c, N_AIR, N_WATER),
        schlick_reflectance(c, N_AIR, N_WATER), t.x, t.y);
}
"#
    );
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("optics parity"),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("optics parity"),
        layout: None,
        module: &module,
        entry_point: Some("cs_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("cosines"),
        contents: bytemuck::cast_slice(cosines),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (cosines.len() * 16) as u64;
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("optics out"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let group = crate::gpu::buffer_group(
        device,
        "optics parity",
        &pipeline.get_bind_group_layout(0),
        &[&input, &output],
    );
    let bytes = gpu
        .dispatch_and_read(&pipeline, &[&group], cosines.len(), &output)
        .expect("read back");
    bytemuck::cast_slice(&bytes).to_vec()
}

#[test]
fn wgsl_optics_match_the_f64_reference() {
    let Some(gpu) = test_gpu() else { return };
    let cosines: Vec<f32> = (0..=180)
        .map(|i| (f64::from(i) * 0.5).to_radians().cos() as f32)
        .collect();
    let got = wgsl_optics(&gpu, &cosines);
    let mut worst = 0.0f64;
    for (c, g) in cosines.iter().zip(&got) {
        let c = f64::from(*c);
        let full = fresnel(c, N_AIR, N_WATER).r;
        let sch = schlick(c, N_AIR, N_WATER);
        let s = (1.0 - c * c).max(0.0).sqrt();
        let t = refract(DVec3::new(s, -c, 0.0), DVec3::Y, N_AIR, N_WATER).expect("no TIR");
        for (a, b) in [(g[0], full), (g[1], sch), (g[2], t.x), (g[3], t.y)] {
            worst = worst.max((f64::from(a) - b).abs());
        }
    }
    // f32 with a few roundings: well under a thousandth of the 2 % normal reflectance.
    assert!(worst < 2e-5, "worst WGSL vs f64 difference {worst:e}");
}

#[test]
fn wakes_shape_the_effect_shaded_water_near_the_boat() {
    use ocean::wake::{TrackSample, Wake, WakeParams};
    let Some(gpu) = test_gpu() else { return };
    let t = 40.0;
    let scene = table_scene(t);
    // The first boat's track: straight along its heading at 3 m/s, arriving where it is at t
    // (heading 0 is north, −z; π/2 east, +x).
    let boat = &scene.boats[0];
    let dir = DVec2::new(boat.heading.sin(), -boat.heading.cos());
    let at = |s: f64| boat.position - dir * 3.0 * (t - s);
    let track: Vec<TrackSample> = (0..=40)
        .map(|i| {
            let s = f64::from(i);
            TrackSample {
                t: s,
                x: at(s).x,
                z: at(s).y,
            }
        })
        .collect();
    let wake = Wake::new(&[&track], WakeParams::default()).expect("a valid track");
    let render = |with_wake: bool| {
        let mut r = Renderer::new(&gpu, OFFSCREEN_FORMAT, RenderOptions::default());
        if with_wake {
            r.set_wake(Some(std::sync::Arc::new(wake.clone())));
        }
        let cfg = config(EffectSet::ALL);
        let frame = frame_for(&scene, &cfg);
        add_effect_passes(&mut r, &gpu, cfg, frame);
        render_image(&gpu, &mut r, &scene, SIZE).expect("render")
    };
    let (plain, _) = render(false);
    let (waked, report) = render(true);
    let water = report
        .passes
        .iter()
        .find(|p| p.name == "ar_water")
        .expect("the effects shade the water");
    assert!(
        water.ran && water.reason.contains("wake sources"),
        "{water:?}"
    );
    assert!(
        !report.passes.iter().any(|p| p.name == "water"),
        "shaded once"
    );
    // Pixel of a world point on the water through the scene's camera.
    let cam = &scene.camera;
    let aspect = f64::from(SIZE[0]) / f64::from(SIZE[1]);
    let view_proj =
        glam::dcamera::rh::proj::directx::perspective(cam.fov_y, aspect, cam.near, cam.far)
            * glam::dcamera::rh::view::look_at_mat4(cam.eye, cam.target, DVec3::Y);
    let pixel = |p: DVec2| {
        let c = view_proj * glam::DVec4::new(p.x, 0.0, p.y, 1.0);
        DVec2::new(
            (c.x / c.w * 0.5 + 0.5) * f64::from(SIZE[0]),
            (0.5 - c.y / c.w * 0.5) * f64::from(SIZE[1]),
        )
    };
    // The last 10 s of the track (30 m behind the boat), as pixels.
    let trail: Vec<DVec2> = (0..=20)
        .map(|k| pixel(at(t - 0.5 * f64::from(k))))
        .collect();
    let near_trail = |x: u32, y: u32| {
        let q = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
        trail.iter().any(|p| p.distance(q) < 12.0)
    };
    let (mut near, mut far) = (0usize, 0usize);
    for (x, y, a) in plain.enumerate_pixels() {
        let b = waked.get_pixel(x, y);
        let d: u32 = (0..3).map(|c| u32::from(a[c].abs_diff(b[c]))).sum();
        if d > 30 {
            if near_trail(x, y) {
                near += 1;
            } else {
                far += 1;
            }
        }
    }
    // The wake's slope and foam change the shading behind the boat, and only there.
    assert!(
        near > 100,
        "only {near} pixels changed near the boat ({far} elsewhere)"
    );
    assert!(
        far * 10 < near,
        "{far} pixels changed away from the boat, {near} near it"
    );
}

#[test]
fn a_paused_still_frame_reuses_the_reflection_and_caustics_and_looks_the_same() {
    let Some(gpu) = test_gpu() else { return };
    let scene = table_scene(40.0);
    let mut r = Renderer::new(&gpu, OFFSCREEN_FORMAT, RenderOptions::default());
    let cfg = config(EffectSet::ALL);
    let frame = frame_for(&scene, &cfg);
    add_effect_passes(&mut r, &gpu, cfg, frame);
    let reason = |report: &crate::FrameReport| {
        let p = report.passes.iter().find(|p| p.name == "ar_water");
        p.expect("ar_water").reason.clone()
    };
    let (first, report) = render_image(&gpu, &mut r, &scene, SIZE).expect("render");
    assert!(!reason(&report).contains(OFFSCREEN_REUSED));
    // Same time, camera and scene: nothing offscreen is redone, and the picture is the same.
    let (again, report) = render_image(&gpu, &mut r, &scene, SIZE).expect("render");
    assert!(
        reason(&report).contains(OFFSCREEN_REUSED),
        "{}",
        reason(&report)
    );
    assert_eq!(compare(&first, &again), (0.0, 0.0));
    // The timeline moves: the caustics are recomputed (the picture changes).
    let later = table_scene(41.0);
    let (moved, report) = render_image(&gpu, &mut r, &later, SIZE).expect("render");
    assert!(!reason(&report).contains(OFFSCREEN_REUSED));
    assert_eq!(
        compare(&moved, &render_with(&gpu, &later, Some(EffectSet::ALL))),
        (0.0, 0.0)
    );
    // The camera moves while paused: the reflection is redrawn.
    let mut turned = later.clone();
    turned.camera.eye.x += 2.0;
    let (_, report) = render_image(&gpu, &mut r, &turned, SIZE).expect("render");
    assert!(!reason(&report).contains(OFFSCREEN_REUSED));
}
