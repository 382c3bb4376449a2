//! WGSL sources: one file per pass in `shaders/`, shared structs in `shaders/common.wgsl`.
//! A pass's module is `common.wgsl` + `optics.wgsl` + its own file(s), concatenated here.

/// Shared structs, bindings and functions (the frame uniform, waves, sky).
pub const COMMON: &str = include_str!("../../../shaders/common.wgsl");
/// Fresnel, Snell, reflection (the effects' optics, mirrored in f64 by `optics.rs`).
pub const OPTICS: &str = include_str!("../../../shaders/optics.wgsl");
pub const SKY: &str = include_str!("../../../shaders/sky.wgsl");
/// The stretch of a frame drawn at a fraction of the screen (no shared files).
pub const UPSCALE: &str = include_str!("../../../shaders/upscale.wgsl");
pub const WATER: &str = include_str!("../../../shaders/water.wgsl");
pub const BOATS: &str = include_str!("../../../shaders/boats.wgsl");
pub const WAVE_HEIGHTS: &str = include_str!("../../../shaders/wave_heights.wgsl");
/// The boats' wake sources (the wakes engineer's file; ocean::wake::gpu mirrors it in f32).
pub const WAKE: &str = include_str!("../../../shaders/wake.wgsl");
/// The water pass's compute stage (sea and wakes per vertex, bind group 1) and the vertex
/// stages that draw its output, or displace by the sea alone without compute.
pub const WATER_VERTICES: &str = include_str!("../../../shaders/water_vertices.wgsl");
pub const WATER_DISPLACED: &str = include_str!("../../../shaders/water_displaced.wgsl");
pub const WATER_NO_WAKES: &str = include_str!("../../../shaders/water_no_wakes.wgsl");

/// The full source of a pass: the shared files then `parts`.
pub fn source(parts: &[&str]) -> String {
    let mut s = String::with_capacity(COMMON.len() + OPTICS.len() + 8192);
    s.push_str(COMMON);
    s.push('\n');
    s.push_str(OPTICS);
    for p in parts {
        s.push('\n');
        s.push_str(p);
    }
    s
}

/// Compile a pass's module (validation errors surface through wgpu's error handler).
pub fn module(device: &wgpu::Device, label: &str, parts: &[&str]) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source(parts).into()),
    })
}
