// Shared structs and functions of every Regatta pass. Each pass's WGSL file is appended to this
// one in Rust (crates/render/src/shader.rs), so a pass file uses these names directly.
//
// Coordinates: "local" metres, world minus the frame's origin (the clip-map centre), so no
// large coordinate reaches a shader. Race time never does either: each wave comes with its
// phase θ0 = (k D·o − ω t + φ) mod 2π reduced in f64 on the CPU (ocean::WaveSet::gpu_waves).

const PI: f32 = 3.14159265358979;

// One Gerstner wave (ocean::GpuWave, 32 bytes).
struct Wave {
    direction: vec2<f32>,
    k: f32,
    amplitude: f32,
    phase0: f32,
    // k·a, and (k·a)²/2 (a cos wave's mean square slope), formed on the CPU.
    slope: f32,
    half_slope2: f32,
    // Σ half_slope2 of this wave and every later one (ocean::GpuWave::tail_half_slope2).
    tail_half_slope2: f32,
    // D_x², D_x D_z, D_z² (formed on the CPU).
    direction_xx: f32,
    direction_xz: f32,
    direction_zz: f32,
    _pad: f32,
}

// Per-frame values (render::frame::FrameUniform).
struct Frame {
    view_proj: mat4x4<f32>,
    inv_view_proj: mat4x4<f32>,
    // Camera position in local metres; w = seconds of the reduced sun/foam animation (< 1 h).
    eye: vec4<f32>,
    // Unit vector towards the sun; w = sun irradiance scale.
    sun: vec4<f32>,
    // Play area in local metres: min x, min z, max x, max z. Water outside is not drawn.
    play_area: vec4<f32>,
    // Viewport width, height in pixels, 1/width, 1/height.
    viewport: vec4<f32>,
    // x = number of waves (for shading normals), y = clip-map levels, z = live wake sources.
    counts: vec4<u32>,
    // Which waves the vertices of clip-map level l evaluate (ocean's error-bounded culling for
    // that level): bit i of the 64-bit mask (lo, hi) = level_masks[l / 2][2 (l % 2) + 0/1].
    // Level l + 1's mask is always a subset of level l's.
    level_masks: array<vec4<u32>, 8>,
    // The sun's and sky's diffuse radiance that the open sea's body takes (rgb). view_light.rs.
    light: vec4<f32>,
    // Over the camera image (w = 1): the room's radiance the AR water takes, the boats' light.
    room_light: vec4<f32>,
    // R∞ of the chosen water type (rgb) and the open sea's exposure (w).
    water_body: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> waves: array<Wave, MAX_WAVES>;

// True when clip-map level `level` evaluates wave `i`.
fn wave_in_level(i: u32, level: u32) -> bool {
    if level >= frame.counts.y {
        return false;
    }
    let m = frame.level_masks[level / 2u];
    let lo = select(m.x, m.z, (level % 2u) == 1u);
    let hi = select(m.y, m.w, (level % 2u) == 1u);
    let word = select(hi, lo, i < 32u);
    return ((word >> (i % 32u)) & 1u) == 1u;
}

// θ of one wave at local rest point p.
fn wave_phase(w: Wave, p: vec2<f32>) -> f32 {
    return w.k * dot(w.direction, p) + w.phase0;
}

// Displacement (dx, y, dz) of one wave at local rest point p (Gerstner, as eqs. 1-2 of the Sailing+ wave-model thesis: docs/sources.md).
fn gerstner(w: Wave, p: vec2<f32>) -> vec3<f32> {
    let theta = wave_phase(w, p);
    let c = cos(theta);
    return vec3<f32>(w.direction.x * w.amplitude * c, w.amplitude * sin(theta), w.direction.y * w.amplitude * c);
}

// The surface's analytic derivatives at a rest point, summed over waves 0..n, each wave
// weighted by weight(i) (used to fade out waves finer than a pixel).
struct SurfaceFrame {
    // The surface's upward normal, not normalised: cross(∂X/∂z, ∂X/∂x); its y is the Jacobian.
    // Callers that need the unit normal normalise it; slopes are up.xz / up.y.
    up: vec3<f32>,
    // Determinant of the horizontal map's Jacobian: < 1 where crests bunch up (foam).
    jacobian: f32,
    // Slope variance of the faded-out waves, Σ (1 − fade²)·(k a)²/2 (LEAN/Toksvig): the
    // roughness the pixel still covers, to blur the reflection instead of losing it.
    slope_variance: f32,
}

// Foam coverage in [0, 1] from the Jacobian determinant J: ocean::foam_from_jacobian, with
// FOAM_ONSET_JACOBIAN generated from ocean's value (render::shader::prelude).
fn foam_from_jacobian(j: f32) -> f32 {
    return clamp((FOAM_ONSET_JACOBIAN - j) / FOAM_ONSET_JACOBIAN, 0.0, 1.0);
}

// Two foam coverages on the same water (the sea's and the wake's): ocean::foam_coverage.
fn foam_coverage(a: f32, b: f32) -> f32 {
    return 1.0 - (1.0 - clamp(a, 0.0, 1.0)) * (1.0 - clamp(b, 0.0, 1.0));
}

fn surface_frame(p: vec2<f32>, n: u32, footprint: f32) -> SurfaceFrame {
    var dxdx = 1.0;
    var dxdz = 0.0;
    var dzdz = 1.0;
    var dydx = 0.0;
    var dydz = 0.0;
    var variance = 0.0;
    for (var i = 0u; i < n; i = i + 1u) {
        let w = waves[i];
        // Band-limit: a wave whose phase changes by more than π/2 across the pixel's footprint
        // (wavelength under four footprints) aliases into moiré; fade it out from k·footprint
        // = π/4 to π/2 and keep its slope variance (a cos wave's mean square slope is (ka)²/2).
        // The frame's waves are sorted by k (render::frame): from the first one faded out
        // entirely, every later one is too, and adds its variance and nothing else (the
        // same sums as running on, to the rounding of the variance).
        if w.k * footprint >= 0.5 * PI {
            variance += w.tail_half_slope2;
            break;
        }
        let fade = 1.0 - smoothstep(0.25 * PI, 0.5 * PI, w.k * footprint);
        variance += (1.0 - fade * fade) * w.half_slope2;
        let theta = wave_phase(w, p);
        // The faded slope k·a·fade scales sin and cos once, not each of the five sums.
        let fka = fade * w.slope;
        let s = sin(theta) * fka;
        let c = cos(theta) * fka;
        dxdx -= w.direction_xx * s;
        dxdz -= w.direction_xz * s;
        dzdz -= w.direction_zz * s;
        dydx += w.direction.x * c;
        dydz += w.direction.y * c;
    }
    let tx = vec3<f32>(dxdx, dydx, dxdz);
    let tz = vec3<f32>(dxdz, dydz, dzdz);
    var out: SurfaceFrame;
    out.up = cross(tz, tx);
    out.jacobian = dxdx * dzdz - dxdz * dxdz;
    out.slope_variance = variance;
    return out;
}

// The sky seen along unit direction dir: a gradient from horizon haze to zenith blue, and the
// sun's disc and glow. Linear colour.
fn sky_colour(dir: vec3<f32>) -> vec3<f32> {
    return sky_colour_rough(dir, 0.0);
}

// The sky reflected by a facet whose normal varies with slope variance `variance` inside the
// pixel (the band-limited waves' lost slopes): the sun's lobes widen as in Toksvig's filtered
// Phong, power n → n / (1 + n·2σ²) (a reflected ray turns twice the normal's angle), with
// their energy kept by the (n' + 1)/(n + 1) normalisation; the disc spreads into a glint.
fn sky_colour_rough(dir: vec3<f32>, variance: f32) -> vec3<f32> {
    let up = clamp(dir.y, -1.0, 1.0);
    let zenith = vec3<f32>(0.10, 0.28, 0.62);
    let horizon = vec3<f32>(0.62, 0.74, 0.86);
    var c = mix(horizon, zenith, pow(max(up, 0.0), 0.45));
    // Below the horizon (beyond the play area, or in reflections of steep facets): distant
    // sea under haze, darkening towards the nadir.
    let below = mix(horizon * 0.85, vec3<f32>(0.05, 0.2, 0.27), clamp(-up * 3.0, 0.0, 1.0));
    c = select(c, below, up < 0.0);
    let s = max(dot(dir, frame.sun.xyz), 0.0);
    let v2 = 2.0 * variance;
    let n64 = 64.0 / (1.0 + 64.0 * v2);
    let n8 = 8.0 / (1.0 + 8.0 * v2);
    let glow = pow(s, n64) * 0.6 * (n64 + 1.0) / 65.0 + pow(s, n8) * 0.15 * (n8 + 1.0) / 9.0;
    // The disc (solid angle ≈ 2π·3e-4 sr at the smoothstep's edge) spreads over the lobe.
    let n_disc = 1.0 / (3e-4 + v2);
    let disc = select(smoothstep(0.9995, 0.9998, s) * 30.0, pow(s, n_disc) * 30.0 * 3e-4 * (n_disc + 1.0), variance > 1e-6);
    return c + vec3<f32>(1.0, 0.92, 0.78) * (glow + disc) * frame.sun.w;
}

// NDC corner i (0, 1, 2) of a triangle that covers the screen: (-1,-1), (3,-1), (-1,3).
// (upscale.wgsl, which has no shared files, spells it out.)
fn full_screen_xy(i: u32) -> vec2<f32> {
    return vec2<f32>(f32((i << 1u) & 2u) * 2.0 - 1.0, f32(i & 2u) * 2.0 - 1.0);
}

// World direction of the ray through a pixel (NDC xy), from the inverse view-projection.
fn ray_dir(ndc: vec2<f32>) -> vec3<f32> {
    let far = frame.inv_view_proj * vec4<f32>(ndc, 0.5, 1.0);
    return normalize(far.xyz / far.w - frame.eye.xyz);
}

// A clip-map vertex's rest point displaced by the sea (local metres): the waves its level
// evaluates, those the next coarser level drops faded by `fade` (0 on the level's outer
// border, so border vertices land exactly where the coarser level's do).
fn sea_displaced(rest: vec2<f32>, fade: f32, level: u32) -> vec3<f32> {
    var pos = vec3<f32>(rest.x, 0.0, rest.y);
    for (var i = 0u; i < frame.counts.x; i = i + 1u) {
        if wave_in_level(i, level) {
            let weight = select(fade, 1.0, wave_in_level(i, level + 1u));
            pos += gerstner(waves[i], rest) * weight;
        }
    }
    return pos;
}
