// Shared structs and functions of every Regatta pass. Each pass's WGSL file is appended to this
// one in Rust (crates/render/src/shader.rs), so a pass file uses these names directly.
//
// Coordinates: "local" metres, world minus the frame's origin (the clip-map centre), so no
// large coordinate reaches a shader. Race time never does either: each wave comes with its
// phase θ0 = (k D·o − ω t + φ) mod 2π reduced in f64 on the CPU (ocean::WaveSet::gpu_waves).

const PI: f32 = 3.14159265358979;

// One Gerstner wave (ocean::GpuWave, 64 bytes: the uniform array's stride). Every product of
// the wave's constants is formed in f64 on the CPU and rounded once, so no shader forms it per
// pixel or per vertex.
struct Wave {
    // k D (x, z), rad/m: θ = dot(wavevector, p) + phase0.
    wavevector: vec2<f32>,
    phase0: f32,
    // k, rad/m (compared with the pixel filter's cut-off wavenumbers).
    k: f32,
    // A D (x, z) and A, metres: the displacement's amplitudes.
    amplitude_direction: vec2<f32>,
    amplitude: f32,
    // (k·A)²/2, a cos wave's mean square slope.
    half_slope2: f32,
    // Σ half_slope2 of this wave and every later one (ocean::GpuWave::tail_half_slope2).
    tail_half_slope2: f32,
    // k A D_x², k A D_x D_z, k A D_z² (the horizontal map's Jacobian terms, × −sin θ) and
    // k A D_x, k A D_z (the height's gradient, × cos θ).
    slope_xx: f32,
    slope_xz: f32,
    slope_zz: f32,
    slope_x: f32,
    slope_z: f32,
    _pad0: f32,
    _pad1: f32,
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
    // Per clip-map level, how many of the first waves its vertices sum for the pixels
    // (render::vertex_slopes): level l's at [l / 4][l % 4].
    vertex_waves: array<vec4<u32>, 4>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> waves: array<Wave, MAX_WAVES>;

// The waves clip-map level `level` evaluates: bit i of the 64-bit mask (lo, hi) for wave i
// (none past the frame's levels).
fn level_mask(level: u32) -> vec2<u32> {
    if level >= frame.counts.y {
        return vec2<u32>(0u);
    }
    let m = frame.level_masks[level / 2u];
    return select(m.xy, m.zw, (level % 2u) == 1u);
}

// True when wave `i`'s bit is set in the 64-bit mask (lo, hi).
fn wave_in_mask(i: u32, mask: vec2<u32>) -> bool {
    let word = select(mask.y, mask.x, i < 32u);
    return ((word >> (i % 32u)) & 1u) == 1u;
}

// θ of one wave at local rest point p: k D·p + θ0, with k D formed on the CPU.
fn wave_phase(w: Wave, p: vec2<f32>) -> f32 {
    return dot(w.wavevector, p) + w.phase0;
}

// Displacement (dx, y, dz) of one wave at local rest point p (Gerstner, as eqs. 1-2 of the Sailing+ wave-model thesis: docs/sources.md).
fn gerstner(w: Wave, p: vec2<f32>) -> vec3<f32> {
    let theta = wave_phase(w, p);
    let c = cos(theta);
    return vec3<f32>(w.amplitude_direction.x * c, w.amplitude * sin(theta), w.amplitude_direction.y * c);
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

// The running sums of surface_frame over a prefix of the frame's waves (sorted by k), and the
// index of the first wave not yet summed.
struct WaveSums {
    dxdx: f32,
    dxdz: f32,
    dzdz: f32,
    dydx: f32,
    dydz: f32,
    variance: f32,
    next: u32,
}

// The sums of no wave: the flat surface's frame (∂x/∂x = ∂z/∂z = 1), the next wave the first.
const NO_WAVES: WaveSums = WaveSums(1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0u);

// The band-limited sums of every wave at rest point p for a pixel `footprint` metres across
// (0: no band limit). Band-limit: a wave whose phase changes by more than π/2 across the
// footprint (wavelength under four footprints) aliases into moiré; it fades out from
// k·footprint = π/4 to π/2 and keeps its slope variance (a cos wave's mean square slope is
// (ka)²/2). The frame's waves are sorted by k (render::frame), so the sums run in two loops:
// the waves the pixel resolves whole (k·footprint < π/4: fade 1, no variance), then the few
// the filter fades, up to the first faded out entirely, from which every later wave adds its
// variance and nothing else. The same sums as one loop over every wave with its fade (the
// fade is exactly 1 below π/4, and every wave past π/2 adds exactly 0 slope), to the
// rounding of the variance's tail.
fn surface_frame(p: vec2<f32>, n: u32, footprint: f32) -> SurfaceFrame {
    return surface_frame_from(p, n, footprint, NO_WAVES);
}

// surface_frame with the sums of the waves before `start.next` already in `start` (whole, no
// variance): the interpolated sums of the waves a water pixel's vertices carry
// (vertex_slope_sums; render::vertex_slopes states their error bound).
fn surface_frame_from(p: vec2<f32>, n: u32, footprint: f32, start: WaveSums) -> SurfaceFrame {
    let sums = fading_waves(p, n, footprint, resolved_waves(p, n, footprint, start));
    var out: SurfaceFrame;
    out.jacobian = sums.dxdx * sums.dzdz - sums.dxdz * sums.dxdz;
    // cross(tz, tx) of the tangents tx = (dxdx, dydx, dxdz), tz = (dxdz, dydz, dzdz), written
    // out: its y is the Jacobian's own products, so it is the Jacobian.
    out.up = vec3<f32>(
        sums.dydz * sums.dxdz - sums.dzdz * sums.dydx,
        out.jacobian,
        sums.dxdz * sums.dydx - sums.dydz * sums.dxdx,
    );
    out.slope_variance = sums.variance;
    return out;
}

// The waves from `start.next` up to the first the pixel filter fades (k·footprint ≥ π/4),
// whole, added to `start`.
// The test is k ≥ π/(4·footprint), the cut-off wavenumber formed once per pixel (a footprint
// of 0, no band limit, is taken as 1e-30 m: a cut-off no wave reaches, as k·0 < π/4). Where
// the rounding of the two tests differs (k·footprint within a few ULP of π/4), the fade of
// the wave is exactly 1 (smoothstep's t is below 1e-6 there, its 3t² rounds away against 1),
// so fading_waves adds sin θ·1 and a variance of 0: the sums are the same either way
// (render/tests/wave_filter.rs checks the rounding).
fn resolved_waves(p: vec2<f32>, n: u32, footprint: f32, start: WaveSums) -> WaveSums {
    let k_fading = 0.25 * PI / max(footprint, 1e-30);
    var s = start;
    var i = start.next;
    for (; i < n; i = i + 1u) {
        let w = waves[i];
        if w.k >= k_fading {
            break;
        }
        let theta = wave_phase(w, p);
        s = with_wave(s, w, sin(theta), cos(theta));
    }
    s.next = i;
    return s;
}

// The waves from `start.next` on, faded by the pixel filter, with their variance; at the first
// faded out entirely, the variance of it and every later wave (its tail) and nothing else.
fn fading_waves(p: vec2<f32>, n: u32, footprint: f32, start: WaveSums) -> WaveSums {
    var s = start;
    for (var i = start.next; i < n; i = i + 1u) {
        let w = waves[i];
        let kf = w.k * footprint;
        if kf >= 0.5 * PI {
            s.variance += w.tail_half_slope2;
            break;
        }
        let fade = 1.0 - smoothstep(0.25 * PI, 0.5 * PI, kf);
        s.variance += (1.0 - fade * fade) * w.half_slope2;
        let theta = wave_phase(w, p);
        s = with_wave(s, w, sin(theta) * fade, cos(theta) * fade);
    }
    return s;
}

// How many of the first waves the vertices of clip-map level `level` sum for the pixels
// (none past the frame's levels).
fn vertex_wave_count(level: u32) -> u32 {
    if level >= frame.counts.y {
        return 0u;
    }
    return min(frame.vertex_waves[level / 4u][level % 4u], frame.counts.x);
}

// The slope sums of the waves a vertex of clip-map level `level` carries to the pixels, whole,
// at its rest point p; `next`: the first wave the pixels sum.
fn vertex_slope_sums(p: vec2<f32>, level: u32) -> WaveSums {
    let n = vertex_wave_count(level);
    var s = NO_WAVES;
    for (var i = 0u; i < n; i = i + 1u) {
        let w = waves[i];
        let theta = wave_phase(w, p);
        s = with_wave(s, w, sin(theta), cos(theta));
    }
    s.next = n;
    return s;
}

// The vertex's slope sums as the vertex stage hands them to the pixels: (∂x/∂x, ∂x/∂z,
// ∂z/∂z, ∂y/∂x) and (∂y/∂z, the first wave the pixels sum). A triangle's three vertices are of
// one level (render::clipmap builds each level's own), so the interpolated index is that
// level's, to rounding.
fn vertex_sums_out(s: WaveSums) -> array<vec4<f32>, 2> {
    return array<vec4<f32>, 2>(
        vec4<f32>(s.dxdx, s.dxdz, s.dzdz, s.dydx),
        vec4<f32>(s.dydz, f32(s.next), 0.0, 0.0),
    );
}

// The WaveSums a pixel starts from: its triangle's vertex sums, interpolated (vertex_sums_out).
fn vertex_sums_in(a: vec4<f32>, b: vec2<f32>) -> WaveSums {
    return WaveSums(a.x, a.y, a.z, a.w, b.x, 0.0, u32(round(b.y)));
}

// `s` with wave `w`'s slope terms added for sin θ and cos θ (each times the pixel filter's
// fade, if any), with its k A·direction products as the CPU formed them.
fn with_wave(sums: WaveSums, w: Wave, sn: f32, cs: f32) -> WaveSums {
    var s = sums;
    s.dxdx -= w.slope_xx * sn;
    s.dxdz -= w.slope_xz * sn;
    s.dzdz -= w.slope_zz * sn;
    s.dydx += w.slope_x * cs;
    s.dydz += w.slope_z * cs;
    return s;
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
    let s = max(dot(dir, frame.sun.xyz), 0.0);
    let v2 = 2.0 * variance;
    let n64 = 64.0 / (1.0 + 64.0 * v2);
    let n8 = 8.0 / (1.0 + 8.0 * v2);
    let glow = pow(s, n64) * 0.6 * (n64 + 1.0) / 65.0 + pow(s, n8) * 0.15 * (n8 + 1.0) / 9.0;
    // The disc (solid angle ≈ 2π·3e-4 sr at the smoothstep's edge) spreads over the lobe.
    let n_disc = 1.0 / (3e-4 + v2);
    let disc = select(smoothstep(0.9995, 0.9998, s) * 30.0, pow(s, n_disc) * 30.0 * 3e-4 * (n_disc + 1.0), variance > 1e-6);
    return sky_gradient(dir) + SUN_COLOUR * (glow + disc) * frame.sun.w;
}

// The sun's colour (linear) in sky_colour_rough's glow and disc.
const SUN_COLOUR: vec3<f32> = vec3<f32>(1.0, 0.92, 0.78);

// The sky's haze at the horizon and its blue at the zenith.
const SKY_HORIZON: vec3<f32> = vec3<f32>(0.62, 0.74, 0.86);
const SKY_ZENITH: vec3<f32> = vec3<f32>(0.10, 0.28, 0.62);

// The sky without the sun above the horizon, at the sine `up` of the elevation (the horizon's
// haze at or below 0): sky_gradient's upper half, alone where every ray rises (the reflected
// room's texels).
fn sky_above(up: f32) -> vec3<f32> {
    return mix(SKY_HORIZON, SKY_ZENITH, pow(max(up, 0.0), 0.45));
}

// The sky without the sun along unit direction dir: horizon haze to zenith blue above the
// horizon, distant sea under haze below it.
fn sky_gradient(dir: vec3<f32>) -> vec3<f32> {
    let up = clamp(dir.y, -1.0, 1.0);
    let above = sky_above(up);
    // Below the horizon (beyond the play area, or in reflections of steep facets): distant
    // sea under haze, darkening towards the nadir.
    let below = mix(SKY_HORIZON * 0.85, vec3<f32>(0.05, 0.2, 0.27), clamp(-up * 3.0, 0.0, 1.0));
    return select(above, below, up < 0.0);
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
    // The two levels' masks once per vertex, not per wave.
    let here = level_mask(level);
    let coarser = level_mask(level + 1u);
    for (var i = 0u; i < frame.counts.x; i = i + 1u) {
        if wave_in_mask(i, here) {
            let weight = select(fade, 1.0, wave_in_mask(i, coarser));
            pos += gerstner(waves[i], rest) * weight;
        }
    }
    return pos;
}
