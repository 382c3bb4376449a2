// Boat wakes: the per-frame wake source buffer (ocean::wake::WakeKernelSource, 48 bytes) and
// the functions that evaluate it at a local point p = world (x, z) − origin, in metres.
// Mirrored exactly, in f32, by ocean::wake::WakeKernelSource::{height, height_grad,
// foam_density} (through ocean::wake::gpu::{source_height_f32, wake_foam_f32, ...}).
//
// Each source is one segment of a boat's path: a Cauchy–Poisson ring-wave packet of the hull's
// pressure patch. No race time and no large coordinate reach this file: q = g s²/4 carries the
// source's age s (reduced on the CPU), positions are local. What is fixed per source (its sign
// and strength, R², the cut-off's radius, the foam's rate, −q, q/2π) the CPU forms once per
// frame, so a (point, source) pair spends nothing on it; what is fixed per point (the band
// limit's edges) the caller forms once per point.
//
// The sine and cosine of a source's phase Φ come from a table of (sin 2πu, cos 2πu) over one
// turn (ocean::turn_table: an Rg16Float texture, linear filtering, repeat addressing) on the
// texture unit, which runs beside the ALUs a pass summing sources is bound by: u = Φ/2π is
// (q/2π)/r, q/2π formed per source on the CPU, and fract(u) keeps the texture coordinate in
// [0, 1) (the hardware's fixed-point coordinates never see Φ's thousands of radians). Its
// error, 9.6e-4 on any conforming GPU (turn_table_error), replaces sin and cos's 2^-11 in the
// wake's bounds (ocean::wake::f32_height_error_bound).
//
// A pass includes this file and declares the buffer and the table, then sums:
//
//   @group(G) @binding(B) var<storage, read> wake_sources: array<WakeSource>;
//   @group(G) @binding(T) var turn_table: texture_2d<f32>;
//   @group(G) @binding(T + 1) var turn_sampler: sampler;
//   var h = 0.0; var foam = 0.0;
//   for (var i = 0u; i < arrayLength(&wake_sources); i++) {
//       h += wake_source_height(wake_sources[i], p);
//       foam += wake_source_foam(wake_sources[i], p);
//   }
//   let wake_foam = wake_foam_from_density(foam);

struct WakeSource {
    // Segment midpoint − origin (x, z), m.
    pos: vec2<f32>,
    // −strength · segment vector (x, z), strength = F/(√2πρg) · age fade: the term's sign and
    // strength folded into ΔX, m⁴.
    dx: vec2<f32>,
    // g s²/4 for the source's age s, m.
    q: f32,
    // R² (pressure-patch radius R), m²: k²R² = 4g.
    hull_r2: f32,
    // Beyond this squared distance the term is below the cull tolerance, m².
    cull_r2: f32,
    // Inside this squared distance the term is nothing (k²R²/4 > 40), never 0, m².
    inner_r2: f32,
    // Foam density at the centre, and −1/w² for the strip's width w, 1/m².
    foam: f32,
    foam_rate: f32,
    // −q, m: the kernel's −k = −q/r² is one division (the band fade's rising variable).
    neg_q: f32,
    // q/2π, m: the phase in turns Φ/2π = q/(2π r) is one product with 1/r.
    q_turns: f32,
}

// From the generated prelude (ocean::wake::wgsl, the values of the f32 mirror): WAKE_BAND_START and WAKE_BAND_END, the k·spacing over which the band limit fades a term out
// (1 to 2: a clip-map level drops the sea's waves from k·cell = 2 on); WAKE_SPACING_MIN, the
// spacing below which a field is not band limited (its fade is exactly 1 for every k a
// source reaches).

// The band limit of a field sampled every `spacing` metres (a clip-map level's vertices): a
// source's local wavenumber k = q/r² is faded out from k·spacing = 1 to 2, as a clip-map level
// drops the sea's waves shorter than π cells (render::clipmap::plan). Height and gradient are
// faded alike: the fade filters the local wavenumber, and the gradient of a component of
// wavenumber k has that wavenumber too. The fade is 1 − smoothstep(1, 2, k·spacing) =
// smoothstep(−2/spacing, −1/spacing, −k) (the Hermite step is symmetric, s(1 − t) = 1 − s(t)):
// these are its edges in −k, formed once per point, so a (point, source) pair pays the
// smoothstep alone, on −k = s.neg_q / r². spacing = 0: no band limit (edges about −10³⁰).
fn wake_band_edges(spacing: f32) -> vec2<f32> {
    let s = max(spacing, WAKE_SPACING_MIN);
    return vec2<f32>(-WAKE_BAND_END / s, -WAKE_BAND_START / s);
}

// (sin 2πu, cos 2πu) from the table: one filtered look-up at fract(u) (explicit level 0, so a
// compute stage may sample). Within turn_table_error's total of the exact values.
fn turn_sin_cos(u: f32) -> vec2<f32> {
    return textureSampleLevel(turn_table, turn_sampler, vec2<f32>(fract(u), 0.5), 0.0).xy;
}

// The height one source adds at p, m: with dx = −strength·ΔX,
// (k²/r²) e^{−k²R²/4} [sin Φ + (k²R² − 3)/Φ cos Φ] (d·dx), k = q/r², Φ = q/r.
fn wake_source_height(s: WakeSource, p: vec2<f32>) -> f32 {
    let d = p - s.pos;
    let r2 = dot(d, d);
    if (r2 > s.cull_r2 || r2 < s.inner_r2) {
        return 0.0;
    }
    let k = s.q / r2;
    let kk = k * k;
    let big_g = kk * s.hull_r2;
    let inv_r = inverseSqrt(r2);
    let phi = s.q * inv_r;
    // Φ reaches thousands of radians: its sine and cosine from the table, at Φ/2π turns.
    let sc = turn_sin_cos(s.q_turns * inv_r);
    let bracket = sc.x + (big_g - 3.0) / phi * sc.y;
    return kk / r2 * exp(-0.25 * big_g) * bracket * dot(d, s.dx);
}

// The height one source adds at p and its gradient, (w, ∂w/∂x, ∂w/∂z) in m and m/m: the
// closed-form derivative of wake_source_height, so a point needs one evaluation, not three.
// With h = F(r)·(d·dx), F = q² e^{−g} bracket / r⁶, bracket = sin Φ + (4g − 3)/Φ cos Φ,
// g = k²R²/4: ∇h = F'(r) (d/r)(d·dx) + F dx, F' = (F/bracket)/r · [(4g − 9)·bracket
// + 4g sin Φ − (Φ + 12/Φ) cos Φ] (the derivative of q² e^{−g}/r⁶, (4g − 6)/r of it, times
// the bracket, plus the bracket's own, regrouped around the bracket).
fn wake_source_height_grad(s: WakeSource, p: vec2<f32>) -> vec3<f32> {
    let d = p - s.pos;
    return wake_source_height_grad_at(s, d, dot(d, d), wake_band_edges(0.0));
}

// wake_source_height_grad with the offset d = p − s.pos and r2 = |d|² already formed, band
// limited by the edges `band` (wake_band_edges of the points' spacing). Inside the band
// limit's radius (k·spacing ≥ 2, −k at or below band.x) the term is nothing and costs no exp
// or look-up.
fn wake_source_height_grad_at(s: WakeSource, d: vec2<f32>, r2: f32, band: vec2<f32>) -> vec3<f32> {
    if (r2 > s.cull_r2 || r2 < s.inner_r2) {
        return vec3<f32>(0.0);
    }
    let neg_k = s.neg_q / r2;
    if (neg_k <= band.x) {
        return vec3<f32>(0.0);
    }
    let kk = neg_k * neg_k;
    let big_g = kk * s.hull_r2;
    let inv_r = inverseSqrt(r2);
    let phi = s.q * inv_r;
    let sc = turn_sin_cos(s.q_turns * inv_r);
    let sn = sc.x;
    let cs = sc.y;
    let c = kk / r2 * exp(-0.25 * big_g) * smoothstep(band.x, band.y, neg_k);
    let bracket = sn + (big_g - 3.0) / phi * cs;
    let radial_bracket = (big_g - 9.0) * bracket + big_g * sn - (phi + 12.0 / phi) * cs;
    let proj = dot(d, s.dx);
    let f = c * bracket;
    // ∇h = F'(r)·(d·dx)·d/r + F·dx: the scalar F'·(d·dx)/r formed once.
    return vec3<f32>(f * proj, (c * radial_bracket * proj / r2) * d + f * s.dx);
}

// The foam density one source adds at p (a Gaussian strip along the segment).
fn wake_source_foam(s: WakeSource, p: vec2<f32>) -> f32 {
    let d = p - s.pos;
    return s.foam * exp(dot(d, d) * s.foam_rate);
}

// One source at p: (w, ∂w/∂x, ∂w/∂z) of wake_source_height_grad band limited for points
// `spacing` metres apart, and the foam density of wake_source_foam (a smooth strip, not
// limited), the offset and its squared length formed once for both (what a point sums over
// its bin's sources).
fn wake_source_grad_foam(s: WakeSource, p: vec2<f32>, spacing: f32) -> vec4<f32> {
    let d = p - s.pos;
    let r2 = dot(d, d);
    let band = wake_band_edges(spacing);
    return vec4<f32>(wake_source_height_grad_at(s, d, r2, band), s.foam * exp(r2 * s.foam_rate));
}

// Summed foam density → foam strength in [0, 1].
fn wake_foam_from_density(sum: f32) -> f32 {
    return clamp(1.0 - exp(-sum), 0.0, 1.0);
}
