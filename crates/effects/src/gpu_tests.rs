//! GPU tests of the effects on lavapipe: the WGSL optics against the f64 reference, and golden
//! images of each effect. Without an adapter they skip, unless `REGATTA_REQUIRE_GPU=true`.
//!
//! Regenerate the golden images after an intended change of the picture:
//! `REGATTA_UPDATE_GOLDEN=1 cargo test -p effects --lib gpu_tests`, then look at them.

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use wgpu::util::DeviceExt;

use super::backdrop::Backdrop;
use super::passes::{ArConfig, OFFSCREEN_REUSED, add_effect_passes};
use super::{Effect, EffectSet};
use render::golden::{Region, compare, differing, verify};
use render::gpu::{Gpu, test_gpu};
use render::optics::{N_AIR, N_WATER, fresnel, refract, schlick};
use render::{OFFSCREEN_FORMAT, RenderOptions, Renderer, Scene, render_image};

pub(super) const SIZE: [u32; 2] = [128, 96];

pub(super) fn table_scene(t: f64) -> Scene {
    super::demo_table_scene(t)
}

pub(super) fn config(effects: EffectSet) -> ArConfig {
    ArConfig {
        effects,
        table_depth: 3.0,
        ..ArConfig::default()
    }
}

pub(super) fn frame_for(scene: &Scene, cfg: &ArConfig) -> Backdrop {
    let [ax, az, bx, bz] = scene.play_area;
    let centre = DVec2::new(ax + bx, az + bz) / 2.0;
    Backdrop::synthetic(
        &scene.camera,
        SIZE,
        cfg.table_depth,
        centre,
        cfg.ring_radius_for(scene.play_area),
        4.0,
    )
}

fn render_with(gpu: &Gpu, scene: &Scene, effects: Option<EffectSet>) -> image::RgbaImage {
    render_knocked_out(gpu, scene, effects, None)
}

/// [`render_with`], with the AR water shader compiled without `dead`'s term (its FX bit off).
fn render_knocked_out(
    gpu: &Gpu,
    scene: &Scene,
    effects: Option<EffectSet>,
    dead: Option<Effect>,
) -> image::RgbaImage {
    let mut r = Renderer::new(gpu, OFFSCREEN_FORMAT, RenderOptions::default());
    if let Some(effects) = effects {
        let cfg = ArConfig {
            shader_knockout: dead.map_or(0, |e| 1 << e as u8),
            ..config(effects)
        };
        let frame = frame_for(scene, &cfg);
        add_effect_passes(&mut r, gpu, cfg, frame);
    }
    render_image(gpu, &mut r, scene, SIZE).expect("render").0
}

/// Each water effect's golden and the largest mean difference (levels per channel) allowed
/// where it acts (the water the AR shader draws: where its golden differs from
/// fx_background's): at most a third of the mean change that killing its term makes there
/// (measured on lavapipe: reflection 3.2, refraction 20.7, caustics 5.1, flow map 0.49 levels;
/// a rerun changes 0; docs/render-reliability.md), so a dead term fails and rounding passes.
const EFFECT_LIMITS: [(Effect, &str, f64); 4] = [
    (Effect::Reflection, "fx_reflection", 1.0),
    (Effect::Refraction, "fx_refraction", 5.0),
    (Effect::Caustics, "fx_caustics", 1.5),
    (Effect::FlowMap, "fx_flowmap", 0.15),
];

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(format!("{name}.png"))
}

fn read_golden(name: &str) -> Option<image::RgbaImage> {
    image::open(golden_path(name)).ok().map(|i| i.to_rgba8())
}

/// The regions of a golden showing `effects`: for each water effect among them, the pixels
/// where its golden differs from `fx_background`'s, with its limit.
fn regions(effects: EffectSet) -> Vec<Region> {
    let Some(base) = read_golden("fx_background") else {
        return Vec::new();
    };
    EFFECT_LIMITS
        .iter()
        .filter(|(e, _, _)| effects.contains(*e))
        .filter_map(|&(e, name, limit)| {
            Some(Region {
                name: e.name().to_string(),
                mask: differing(&read_golden(name)?, &base),
                mean_tolerance: limit,
            })
        })
        .collect()
}

fn golden(name: &str, effects: EffectSet) {
    let Some(gpu) = test_gpu() else { return };
    let img = render_with(&gpu, &table_scene(40.0), Some(effects));
    render::golden::check_regions(&golden_path(name), &img, &regions(effects))
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn no_effect_golden_passes_for_another() {
    // Before per-effect regions, fx_reflection passed as fx_flowmap (mean 0.79 levels).
    let names = [
        "fx_background",
        "fx_reflection",
        "fx_refraction",
        "fx_caustics",
    ];
    let names = names.iter().chain(&["fx_flowmap", "fx_all"]);
    let set = |name: &str| match EFFECT_LIMITS.iter().find(|l| l.1 == name) {
        Some(&(e, _, _)) => EffectSet::only(Effect::Background).with(e),
        None if name == "fx_all" => EffectSet::ALL,
        None => EffectSet::only(Effect::Background),
    };
    for a in names.clone() {
        for b in names.clone().filter(|&b| b != a) {
            let (Some(img), true) = (read_golden(b), golden_path(a).exists()) else {
                panic!("golden {a} or {b} missing");
            };
            let ok = verify(&golden_path(a), &img, &regions(set(a)));
            assert!(ok.is_err(), "{b} passes as {a}");
        }
    }
}

#[test]
fn a_dead_effect_term_fails_its_golden_and_fx_all() {
    let Some(gpu) = test_gpu() else { return };
    let scene = table_scene(40.0);
    for (e, name, _) in EFFECT_LIMITS {
        let fx = EffectSet::only(Effect::Background).with(e);
        let img = render_knocked_out(&gpu, &scene, Some(fx), Some(e));
        let err = verify(&golden_path(name), &img, &regions(fx)).unwrap_err();
        assert!(err.contains(e.name()), "{name} without {e:?}: {err}");
        let all = render_knocked_out(&gpu, &scene, Some(EffectSet::ALL), Some(e));
        let err = verify(&golden_path("fx_all"), &all, &regions(EffectSet::ALL)).unwrap_err();
        assert!(err.contains("fx_all"), "fx_all without {e:?}: {err}");
    }
    // The background (its own pass, not a water term): the water-only frame fails it.
    let water_only = render_with(&gpu, &scene, None);
    assert!(verify(&golden_path("fx_background"), &water_only, &[]).is_err());
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
        "{}{}\n{}",
        render::shader::prelude(),
        render::shader::OPTICS,
        r#"
@group(0) @binding(0) var<storage, read> input: array<f32>;
@group(0) @binding(1) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
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
    let group = render::gpu::buffer_group(
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
fn the_water_entry_is_the_refraction_and_the_fresnel_reflectance() {
    // `water_entry` (the AR water's one dot product and square root for both) against the f64
    // references and against `refract_dir` and `fresnel_reflectance` as the AR water called
    // them before, on views from overhead to grazing through normals tilted every way, some
    // turned away from the eye (a wave's back face): R = 1 there and the ray refracts about
    // the turned normal.
    let Some(gpu) = test_gpu() else { return };
    let mut cases: Vec<[[f32; 4]; 2]> = Vec::new();
    let mut refs = Vec::new();
    for k in 0..400 {
        let k = f64::from(k);
        let (pitch, yaw) = (
            0.02 + 1.5 * (k * 0.618).fract(),
            std::f64::consts::TAU * (k * 0.754).fract(),
        );
        let d = DVec3::new(
            pitch.sin() * yaw.cos(),
            -pitch.cos(),
            pitch.sin() * yaw.sin(),
        );
        let (tilt, az) = (
            1.4 * (k * 0.377).fract(),
            std::f64::consts::TAU * (k * 0.291).fract(),
        );
        let n = DVec3::new(tilt.sin() * az.cos(), tilt.cos(), tilt.sin() * az.sin());
        let f32s = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
        cases.push([f32s(d), f32s(n)]);
        // The reference at the f32 inputs the GPU gets.
        let (d, n) = (dvec3(f32s(d)), dvec3(f32s(n)));
        let t = refract(d, n, N_AIR, N_WATER).expect("air to water");
        refs.push((
            t,
            fresnel((-d.dot(n)).max(0.0), N_AIR, N_WATER).r,
            d.dot(n) > 0.0,
        ));
    }
    let src = format!(
        "{}{}\n{}",
        render::shader::prelude(),
        render::shader::OPTICS,
        r#"
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 2>>;
@group(0) @binding(11) var<storage, read_write> output: array<array<vec4<f32>, 2>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let d = input[id.x][0].xyz;
        let n = input[id.x][1].xyz;
        let t = refract_dir(d, n, N_AIR, N_WATER);
        let r = fresnel_reflectance(max(dot(n, -d), 0.0), N_AIR, N_WATER);
        output[id.x] = array<vec4<f32>, 2>(water_entry(d, n), vec4<f32>(t.xyz, r));
    }
}
"#
    );
    let bytes = render::compute::run_kernel(&gpu, "water entry", &src, &cases, 32)
        .expect("the kernel runs");
    let got: &[[[f32; 4]; 2]] = bytemuck::cast_slice(&bytes);
    let (mut worst_ref, mut worst_old, mut back) = (0.0f64, 0.0f64, 0);
    for (g, (t, r, away)) in got.iter().zip(&refs) {
        let [entry, old] = g.map(|v| v.map(f64::from));
        let want = [t.x, t.y, t.z, *r];
        for i in 0..4 {
            worst_ref = worst_ref.max((entry[i] - want[i]).abs());
            worst_old = worst_old.max((entry[i] - old[i]).abs());
        }
        if *away {
            back += 1;
            assert_eq!(entry[3], 1.0, "a face turned away reflects everything");
        }
    }
    eprintln!("water_entry: worst against f64 {worst_ref:e}, against the two calls {worst_old:e}");
    // f32 with a few roundings, as wgsl_optics_match_the_f64_reference allows; the two calls
    // compute the same expressions (only the cosine's clamp at 1 differs).
    assert!(worst_ref < 2e-5, "{worst_ref:e}");
    assert!(worst_old < 1e-6, "{worst_old:e}");
    assert!(back > 20, "{back} faces turned away");
}

#[test]
fn the_room_texels_sky_is_the_rough_sky_at_the_texel_roughness() {
    // `sky_colour_texel` (its lobes' powers and weights folded when the shader is compiled)
    // against `sky_colour_rough(dir, TEXEL_ROUGHNESS)`, on directions over the whole sphere
    // and close around the sun (its disc and glow), the sun 35° up; and `sky_colour_rising`
    // against `sky_colour_texel` above the horizon.
    let Some(gpu) = test_gpu() else { return };
    let sun = DVec3::new(0.3, 0.574, -0.76).normalize();
    let mut dirs: Vec<[f32; 4]> = Vec::new();
    for k in 0..2000 {
        let k = f64::from(k);
        let (y, az) = (
            2.0 * (k * 0.618).fract() - 1.0,
            std::f64::consts::TAU * (k * 0.754).fract(),
        );
        let r = (1.0 - y * y).sqrt();
        let mut d = DVec3::new(r * az.cos(), y, r * az.sin());
        if k < 600.0 {
            // Within about 3° of the sun.
            d = (sun + 0.05 * (d - sun.dot(d) * sun)).normalize();
        }
        dirs.push([d.x as f32, d.y as f32, d.z as f32, 0.0]);
    }
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<array<vec4<f32>, 3>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let d = input[id.x].xyz;
        output[id.x] = array<vec4<f32>, 3>(vec4<f32>(sky_colour_texel(d), 0.0),
            vec4<f32>(sky_colour_rough(d, TEXEL_ROUGHNESS), 0.0),
            vec4<f32>(sky_colour_rising(d), 0.0));
    }
}
"#;
    let src = crate::wgsl::source(&[
        super::passes::EFFECTS_COMMON,
        super::passes::REFLECTION,
        super::passes::REFLECTION_ROOM,
        kernel,
    ]);
    let mut frame: render::frame::FrameUniform = bytemuck::Zeroable::zeroed();
    frame.sun = [sun.x as f32, sun.y as f32, sun.z as f32, 1.0];
    let frame_buffer = crate::fixtures::frame_buffer(&gpu, &frame);
    let bytes = render::compute::run_kernel_in(
        &gpu,
        "room sky",
        &src,
        &dirs,
        48,
        &[wgpu::BindGroupEntry {
            binding: 0,
            resource: frame_buffer.as_entire_binding(),
        }],
        &[],
    )
    .expect("the kernel runs");
    let got: &[[[f32; 4]; 3]] = bytemuck::cast_slice(&bytes);
    let (mut worst, mut brightest, mut rising) = (0.0f32, 0.0f32, 0);
    for ([texel, rough, above], d) in got.iter().zip(&dirs) {
        for i in 0..3 {
            // Relative to the value: the disc reaches ~30 (the sun), the sky ~1.
            worst = worst.max((texel[i] - rough[i]).abs() / rough[i].abs().max(1.0));
            brightest = brightest.max(rough[i]);
        }
        // The rising sky the grid pass draws is the texel sky itself above the horizon (the
        // same operations, sky_gradient's lower half and select left out).
        if d[1] >= 0.0 {
            rising += 1;
            for i in 0..3 {
                // A compiler may round the two the same or a few ULP apart.
                assert!(
                    (above[i] - texel[i]).abs() <= 1e-6 * texel[i].abs().max(1.0),
                    "{d:?}"
                );
            }
        }
    }
    assert!(rising > 1000, "{rising}");
    eprintln!("room sky: worst relative difference {worst:e}, brightest {brightest}");
    // A few f32 roundings of the folded constants and of pow (exp2 · log2): WGSL's pow is
    // good to 3 ULP of exp2(y log2 x); well under a thousandth.
    assert!(worst < 1e-4, "{worst:e}");
    assert!(
        brightest > 10.0,
        "the directions reach the sun's disc: {brightest}"
    );
}

fn dvec3(v: [f32; 4]) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}

#[test]
fn wakes_shape_the_effect_shaded_water_near_the_boat() {
    use ocean::wake::{TrackSample, Wake, WakeParams};
    let Some(gpu) = test_gpu() else { return };
    // Three times the other tests' size: at 128×96 the clip-map's cells near the boat are
    // longer than a third of this 3 m/s wake's waves (transverse 5.8 m), which the wake's
    // band limit leaves out as each level leaves out the sea's waves it cannot carry.
    const WAKE_SIZE: [u32; 2] = [3 * SIZE[0], 3 * SIZE[1]];
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
        render_image(&gpu, &mut r, &scene, WAKE_SIZE).expect("render")
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
    let aspect = f64::from(WAKE_SIZE[0]) / f64::from(WAKE_SIZE[1]);
    let view_proj =
        glam::dcamera::rh::proj::directx::perspective(cam.fov_y, aspect, cam.near, cam.far)
            * glam::dcamera::rh::view::look_at_mat4(cam.eye, cam.target, DVec3::Y);
    let pixel = |p: DVec2| {
        let c = view_proj * glam::DVec4::new(p.x, 0.0, p.y, 1.0);
        DVec2::new(
            (c.x / c.w * 0.5 + 0.5) * f64::from(WAKE_SIZE[0]),
            (0.5 - c.y / c.w * 0.5) * f64::from(WAKE_SIZE[1]),
        )
    };
    // The last 10 s of the track (30 m behind the boat), as pixels.
    let trail: Vec<DVec2> = (0..=20)
        .map(|k| pixel(at(t - 0.5 * f64::from(k))))
        .collect();
    let near_trail = |x: u32, y: u32| {
        let q = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
        trail.iter().any(|p| p.distance(q) < 36.0)
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
    let reason = |report: &render::FrameReport| {
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

/// The camera image switched off and on live (the Scene panel's switch) lights the boats as a
/// renderer built with that set of effects does: by the sun and sky without the image, by the
/// room's light over it. (The room's light was set once, when the passes were added, so
/// switching the image off left the boats in the room's light over the sky.)
#[test]
fn switching_the_camera_image_live_relights_the_boats_as_a_fresh_build_does() {
    let Some(gpu) = test_gpu() else { return };
    let scene = table_scene(40.0);
    assert!(!scene.boats.is_empty(), "the demo table has boats");
    let without_image = EffectSet::ALL
        .iter()
        .filter(|&e| e != Effect::Background)
        .fold(EffectSet::NONE, EffectSet::with);
    let mut r = Renderer::new(&gpu, OFFSCREEN_FORMAT, RenderOptions::default());
    let cfg = config(EffectSet::ALL);
    let frame = frame_for(&scene, &cfg);
    let handle = add_effect_passes(&mut r, &gpu, cfg, frame);
    handle.set_effects(without_image);
    let (off, _) = render_image(&gpu, &mut r, &scene, SIZE).expect("render");
    assert_eq!(
        compare(&off, &render_with(&gpu, &scene, Some(without_image))),
        (0.0, 0.0),
        "the image switched off live"
    );
    handle.set_effects(EffectSet::ALL);
    let (on, _) = render_image(&gpu, &mut r, &scene, SIZE).expect("render");
    assert_eq!(
        compare(&on, &render_with(&gpu, &scene, Some(EffectSet::ALL))),
        (0.0, 0.0),
        "the image switched on again"
    );
    // Built without the image and switched on: the room's light.
    let mut r = Renderer::new(&gpu, OFFSCREEN_FORMAT, RenderOptions::default());
    let cfg = config(without_image);
    let frame = frame_for(&scene, &cfg);
    add_effect_passes(&mut r, &gpu, cfg, frame).set_effects(EffectSet::ALL);
    let (on, _) = render_image(&gpu, &mut r, &scene, SIZE).expect("render");
    assert_eq!(
        compare(&on, &render_with(&gpu, &scene, Some(EffectSet::ALL))),
        (0.0, 0.0),
        "the image switched on in a set built without it"
    );
}

#[test]
fn every_set_of_water_effects_draws_and_each_effect_shows() {
    // The AR water compiles one pipeline per set of effects (FX_MASK a constant): all 16 sets
    // draw (lavapipe once crashed on some), and in each set every effect changes the picture
    // against the same set without it, so each constant really switches its effect.
    let Some(gpu) = test_gpu() else { return };
    let scene = table_scene(40.0);
    let water = [
        Effect::Reflection,
        Effect::Refraction,
        Effect::Caustics,
        Effect::FlowMap,
    ];
    let set_of = |bits: usize| {
        water
            .iter()
            .enumerate()
            .filter(|(i, _)| bits & (1 << i) != 0)
            .fold(EffectSet::only(Effect::Background), |s, (_, &e)| s.with(e))
    };
    let images: Vec<image::RgbaImage> = (0..16)
        .map(|bits| render_with(&gpu, &scene, Some(set_of(bits))))
        .collect();
    for (bits, img) in images.iter().enumerate() {
        for (i, e) in water.iter().enumerate() {
            if bits & (1 << i) != 0 {
                // A mean of at least 0.05 levels (0 would be the same picture): the flow map
                // only moves the detail where the current runs, and under the reflection it
                // only moves the mirrored texture's distortion (measured 0.08 there).
                let (mean, _) = compare(img, &images[bits & !(1 << i)]);
                assert!(
                    mean > 0.05,
                    "{e} in {}: mean change {mean:.3}",
                    set_of(bits)
                );
            }
        }
    }
}

#[test]
fn wgsl_current_matches_the_f64_potential_flow() {
    // flowmap.wgsl's current_at (complex form, branch-free) against effects::flowmap's f64
    // field, for two marks in a current across the grid, inside the marks included.
    use super::flowmap::{MarkObstacle, current_at};
    use super::passes::EffectsUniform;
    let Some(gpu) = test_gpu() else { return };
    let device = &gpu.device;
    let (current, radius) = (DVec2::new(0.6, -0.25), 4.0);
    let marks = [DVec2::new(2.0, 10.0), DVec2::new(-15.0, -3.0)];
    let mut fx: EffectsUniform = bytemuck::Zeroable::zeroed();
    fx.current = [current.x as f32, current.y as f32, radius as f32, 12.0];
    fx.flags[1] = marks.len() as u32;
    for (slot, m) in fx.marks.iter_mut().zip(&marks) {
        *slot = [m.x as f32, m.y as f32, 0.0, 0.0];
    }
    let points: Vec<[f32; 2]> = (0..41 * 41)
        .map(|k| [(k % 41) as f32 - 20.0, (k / 41) as f32 - 15.0 + 0.37])
        .collect();
    let src = crate::wgsl::source(&[
        super::passes::EFFECTS_COMMON,
        super::passes::FLOWMAP,
        r#"
@group(0) @binding(10) var<storage, read> points: array<vec2<f32>>;
@group(0) @binding(11) var<storage, read_write> velocity: array<vec2<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&points) {
        velocity[id.x] = current_at(points[id.x]);
    }
}
"#,
    ]);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("current parity"),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("current parity"),
        layout: None,
        module: &module,
        entry_point: Some("cs_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let buffer = |label, contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    let input = buffer(
        "points",
        bytemuck::cast_slice(&points),
        wgpu::BufferUsages::STORAGE,
    );
    let output = buffer(
        "velocity",
        &vec![0u8; points.len() * 8],
        wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    );
    let uniform = buffer(
        "effects",
        bytemuck::bytes_of(&fx),
        wgpu::BufferUsages::UNIFORM,
    );
    let group = |index: u32, entries: &[(u32, &wgpu::Buffer)]| {
        let entries: Vec<wgpu::BindGroupEntry> = entries
            .iter()
            .map(|(binding, b)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: b.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(index),
            entries: &entries,
        })
    };
    let groups = [
        group(0, &[(10, &input), (11, &output)]),
        group(1, &[]),
        group(2, &[(0, &uniform)]),
    ];
    let bytes = gpu
        .dispatch_and_read(&pipeline, &groups.each_ref(), points.len(), &output)
        .expect("read back");
    let got: &[[f32; 2]] = bytemuck::cast_slice(&bytes);
    let obstacles: Vec<MarkObstacle> = marks
        .iter()
        .map(|&centre| MarkObstacle { centre, radius })
        .collect();
    let mut worst = 0.0f64;
    let mut inside = 0;
    for (p, g) in points.iter().zip(got) {
        let p = DVec2::new(f64::from(p[0]), f64::from(p[1]));
        let want = current_at(p, current, &obstacles);
        inside += usize::from(want == DVec2::ZERO);
        worst = worst.max((DVec2::new(f64::from(g[0]), f64::from(g[1])) - want).length());
    }
    assert!(
        inside > 10,
        "the grid reaches into the marks: {inside} points"
    );
    // f32 arithmetic on metre-sized offsets: a millionth of the 0.65 m/s current.
    assert!(worst < 1e-5, "worst WGSL vs f64 difference {worst:e} m/s");
}

/// The camera image fills every pixel behind the scene, so the sky is not drawn under it: the
/// sky pass is skipped with the reason while the background runs, and runs without it (the
/// picture is the same either way: the golden images cover that).
#[test]
fn the_sky_is_skipped_under_the_camera_background_only() {
    let Some(gpu) = test_gpu() else { return };
    let scene = table_scene(40.0);
    let report = |effects: EffectSet| {
        let mut r = Renderer::new(&gpu, OFFSCREEN_FORMAT, RenderOptions::default());
        let cfg = config(effects);
        let frame = frame_for(&scene, &cfg);
        add_effect_passes(&mut r, &gpu, cfg, frame);
        let (_, report) = render_image(&gpu, &mut r, &scene, SIZE).expect("render");
        let pass = |name: &str| {
            report
                .passes
                .iter()
                .find(|p| p.name == name)
                .cloned()
                .expect("the pass is recorded")
        };
        (pass("sky"), pass("background"))
    };
    let (sky, background) = report(EffectSet::ALL);
    assert!(background.ran);
    assert!(
        !sky.ran && sky.reason.contains("background"),
        "{}",
        sky.reason
    );
    let (sky, background) = report(EffectSet::only(Effect::Reflection));
    assert!(!background.ran);
    assert!(sky.ran, "{}", sky.reason);
}

/// An IEEE half-float's bits as f32.
fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = i32::from((h >> 10) & 0x1f);
    let frac = f32::from(h & 0x3ff);
    match exp {
        0 => sign * frac * 2f32.powi(-24),
        31 => sign * f32::INFINITY,
        _ => sign * (1.0 + frac / 1024.0) * 2f32.powi(exp - 15),
    }
}

/// The caustic map the GPU draws (shaders/caustic_map.wgsl, both methods) against the f64
/// area-ratio reference on the same surface grid, region and sun, at two race times: the same
/// triangles land on the same cell centres, so cells agree but for f32 positions (a centre on
/// the other side of an edge) and half-float rounding.
#[test]
fn gpu_caustic_map_matches_the_f64_area_ratio() {
    use super::caustic_map::CausticMethod;
    let Some(gpu) = test_gpu() else { return };
    // lavapipe runs compute shaders: the scatter is what the renderer uses there.
    assert_eq!(
        CausticMethod::for_adapter(&gpu.adapter),
        CausticMethod::Scatter
    );
    for method in [CausticMethod::Scatter, CausticMethod::Raster] {
        caustic_map_against_the_reference(&gpu, method);
    }
}

fn caustic_map_against_the_reference(gpu: &Gpu, method: super::caustic_map::CausticMethod) {
    use super::caustic_map::{CAUSTIC_MAP_FORMAT, CausticMapPass};
    use super::caustics::{CausticRegion, area_ratio};
    use render::frame::{FrameBindings, FrameContext};
    let (src, out, depth) = (48usize, 64u32, 3.0);
    let mut pass =
        CausticMapPass::with_method(gpu, &FrameBindings::new(&gpu.device).layout, method);
    let bindings = FrameBindings::new(&gpu.device);
    let target = render::gpu::texture_2d(
        &gpu.device,
        "caustic map",
        [out, out],
        CAUSTIC_MAP_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    for t in [40.0, 3.6e4] {
        let scene = table_scene(t);
        let frame = FrameContext::new(&scene, SIZE, 1.0);
        bindings.upload(&gpu.queue, &frame.uniform, &frame.waves);
        let region = CausticRegion {
            min: [-20.0, -25.0],
            size: 40.0,
            periodic: false,
        };
        pass.prepare(gpu, &frame, &region, depth, src, out);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        let view = target.create_view(&Default::default());
        pass.record(&mut enc, &bindings.group, &view, None, 0, pass.passes());
        gpu.queue.submit([enc.finish()]);
        let bytes = gpu.read_texture_bytes(&target, 2).expect("read back");
        let got: Vec<f64> = bytes
            .chunks_exact(2)
            .map(|b| f64::from(f16_to_f32(u16::from_le_bytes([b[0], b[1]]))))
            .collect();
        let reference = area_ratio(&scene.sea, t, -scene.sun, depth, region, src, out as usize);
        let mut diffs: Vec<f64> = got
            .iter()
            .zip(&reference.intensity)
            .map(|(g, r)| (g - r).abs())
            .collect();
        let mean_ref = reference.intensity.iter().sum::<f64>() / diffs.len() as f64;
        let mean_gpu = got.iter().sum::<f64>() / diffs.len() as f64;
        diffs.sort_by(f64::total_cmp);
        let median = diffs[diffs.len() / 2];
        let p95 = diffs[diffs.len() * 95 / 100];
        eprintln!(
            "{method:?}, t = {t}: caustic map GPU vs f64: median |Δ| {median:.2e}, p95 {p95:.2e}, mean light {mean_gpu:.4} vs {mean_ref:.4}"
        );
        // README: median 3e-4 (measured 3.0–3.2e-4 on lavapipe, both methods, t = 40 s and
        // 10 h); asserted at 1.5x that figure. Half-float rounding of a value near 1 is 5e-4
        // at most, so the median sits below it; an edge case moves a cell by a triangle's
        // irradiance (the p95 below).
        assert!(median < 1.5 * 3e-4, "median {median} (README: 3e-4)");
        // README: 95th percentile 1e-3, mean within 0.05 %; both asserted at 1.5x.
        assert!(p95 < 1.5 * 1e-3, "p95 {p95} (README: 1e-3)");
        assert!(
            (mean_gpu - mean_ref).abs() < 1.5 * 5e-4 * mean_ref,
            "{mean_gpu} vs {mean_ref} (README: within 0.05 %)"
        );
        // Not a flat map: the waves focus light.
        let max = got.iter().copied().fold(0.0, f64::max);
        assert!(max > 1.3, "max {max}");
    }
}
