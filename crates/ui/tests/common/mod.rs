//! Shared helpers of the ui tests: snapshot rendering on the test GPU (lavapipe in CI).
#![allow(dead_code)]

use egui::Vec2;
use egui_kittest::{Harness, HarnessBuilder};

/// A harness builder that renders with the test GPU, or `None` (skip) without one.
pub fn gpu_builder<S>(size: Vec2) -> Option<HarnessBuilder<S>> {
    let gpu = render::gpu::test_gpu()?;
    let setup = egui_wgpu::WgpuSetup::Existing(egui_wgpu::WgpuSetupExisting {
        instance: gpu.instance.clone(),
        adapter: gpu.adapter.clone(),
        device: gpu.device.clone(),
        queue: gpu.queue.clone(),
    });
    Some(Harness::<S>::builder().with_size(size).wgpu_setup(setup))
}

/// Renders `app` at `size` with the test GPU and compares it with `tests/snapshots/<name>.png`;
/// skips without a GPU (see [`gpu_builder`]).
pub fn snapshot(name: &str, size: Vec2, app: impl FnMut(&mut egui::Ui) + 'static) {
    let Some(b) = gpu_builder(size) else {
        return;
    };
    let mut h = b.build_ui(app);
    h.run();
    h.snapshot(name);
}

/// The sample race with its start mark made a 120 m line, skewed 5° off east-west with its west
/// end (the pin, looking upwind into the sample's wind from the north) upwind.
pub fn sample_with_a_start_line() -> race::Race {
    let mut race = race::Race::sample();
    let start = &mut race.marks[race.course[0]];
    let p = start.position;
    let (dx, dz) = (
        60.0 * 5f64.to_radians().cos(),
        60.0 * 5f64.to_radians().sin(),
    );
    start.kind = race::MarkKind::StartLine;
    start.ends = Some([[p[0] - dx, p[1] - dz], [p[0] + dx, p[1] + dz]]);
    race
}

/// Overlay switches as the app gives the Scene panel (its `scene_overlay::OVERLAYS` names and
/// texts): ui keeps no overlay list, so its tests bring one.
#[allow(dead_code)]
pub fn race_overlays() -> Vec<ui::EffectToggle> {
    [
        ("labels", "Boat labels"),
        ("trails", "Trails"),
        ("course", "Course and marks"),
        ("lines", "Ahead/behind lines"),
        ("wind", "Wind"),
    ]
    .iter()
    .map(|(k, l)| ui::EffectToggle::new(k, l, true))
    .collect()
}
