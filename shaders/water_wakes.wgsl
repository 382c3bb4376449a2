// Wake hook of the water pass, with wakes: the boats' wakes of shaders/wake.wgsl summed over
// the frame's sources (bind group 1; frame.counts.z of them are live). Appended after
// wake.wgsl and before water.wgsl.

@group(1) @binding(0) var<storage, read> wake_sources: array<WakeSource>;

// Wake height at local point p (the displaced surface's horizontal position), m.
fn wake_height(p: vec2<f32>) -> f32 {
    var h = 0.0;
    for (var i = 0u; i < frame.counts.z; i = i + 1u) {
        h += wake_source_height(wake_sources[i], p);
    }
    return h;
}

// Wake foam in [0, 1] at local point p.
fn wake_foam(p: vec2<f32>) -> f32 {
    var f = 0.0;
    for (var i = 0u; i < frame.counts.z; i = i + 1u) {
        f += wake_source_foam(wake_sources[i], p);
    }
    return wake_foam_from_density(f);
}
