//! Measuring a wake field: the envelope's half-angle and the transverse wavelength. Used by the
//! tests and by `regatta bench`, on any model (Kelvin, the wave-model thesis's rings, 003 in docs/sources.md, the reference).
//!
//! Fields are given in the boat frame: `f(ξ, y)`, the boat at the origin moving in +ξ.

/// Ai(0) / max Ai(−x) = 0.35503 / 0.53566: near the cusp line the Kelvin wake's amplitude is an
/// Airy function of the distance across it (two stationary phases merge there), so the cusp
/// line itself lies outside the outermost amplitude peak where the envelope has fallen to this
/// fraction of that peak.
pub const AIRY_EDGE_FRACTION: f64 = 0.662_8;

/// The envelope E(φ) = max |f| over a radial window of ±0.4 λ₀ around `radius` (a window of
/// 0.8 λ₀ spans a full crest-to-crest of the cusp waves, λ₀/1.5), on the arc behind the boat,
/// for polar angles `phi_deg` from the track.
pub fn envelope(
    f: &dyn Fn(f64, f64) -> f64,
    lambda0: f64,
    radius: f64,
    phi_deg: &[f64],
) -> Vec<f64> {
    phi_deg
        .iter()
        .map(|ph| {
            let (s, c) = ph.to_radians().sin_cos();
            (0..17)
                .map(|i| {
                    let r = radius + (i as f64 / 16.0 - 0.5) * 0.8 * lambda0;
                    f(-r * c, r * s).abs()
                })
                .fold(0.0, f64::max)
        })
        .collect()
}

/// The envelope's half-angle, degrees: the outermost local maximum of E(φ) above 30 % of the
/// largest, then the angle beyond it where E falls to [`AIRY_EDGE_FRACTION`] of that peak
/// (linear interpolation). Scans φ from 8° to 60° in 0.1° steps; `None` if no edge is found.
pub fn cusp_half_angle_deg(f: &dyn Fn(f64, f64) -> f64, lambda0: f64, radius: f64) -> Option<f64> {
    let phis: Vec<f64> = (0..=520).map(|i| 8.0 + 0.1 * i as f64).collect();
    edge_of(&phis, &envelope(f, lambda0, radius, &phis))
}

/// Same, over a narrower window [lo, hi] degrees (cheaper, for slow fields).
pub fn cusp_half_angle_deg_in(
    f: &dyn Fn(f64, f64) -> f64,
    lambda0: f64,
    radius: f64,
    lo: f64,
    hi: f64,
) -> Option<f64> {
    let n = ((hi - lo) / 0.1).round() as usize;
    let phis: Vec<f64> = (0..=n).map(|i| lo + 0.1 * i as f64).collect();
    edge_of(&phis, &envelope(f, lambda0, radius, &phis))
}

fn edge_of(phis: &[f64], e: &[f64]) -> Option<f64> {
    let emax = e.iter().copied().fold(0.0, f64::max);
    if emax.is_nan() || emax <= 0.0 {
        return None;
    }
    let mut peak = None;
    for i in 1..e.len() - 1 {
        if e[i] >= e[i - 1] && e[i] >= e[i + 1] && e[i] > 0.3 * emax {
            peak = Some(i);
        }
    }
    let ip = peak?;
    let target = AIRY_EDGE_FRACTION * e[ip];
    (ip..e.len() - 1).find(|&i| e[i + 1] < target).map(|i| {
        let f = (e[i] - target) / (e[i] - e[i + 1]);
        phis[i] + f * (phis[i + 1] - phis[i])
    })
}

/// The transverse wavelength on the track: twice the mean distance between zero crossings of
/// f(ξ, 0) for ξ from −`from` to −`to` metres, sampled every `step` metres. `None` with fewer
/// than two crossings.
pub fn transverse_wavelength(
    f: &dyn Fn(f64, f64) -> f64,
    from: f64,
    to: f64,
    step: f64,
) -> Option<f64> {
    let n = ((to - from) / step).ceil() as usize;
    let mut crossings = Vec::new();
    let mut prev = (-from, f(-from, 0.0));
    for i in 1..=n {
        let xi = -from - step * i as f64;
        let v = f(xi, 0.0);
        if prev.1 != 0.0 && v != 0.0 && (prev.1 > 0.0) != (v > 0.0) {
            crossings.push(prev.0 + (xi - prev.0) * prev.1 / (prev.1 - v));
        }
        prev = (xi, v);
    }
    if crossings.len() < 2 {
        return None;
    }
    let span = (crossings[0] - crossings[crossings.len() - 1]).abs();
    Some(2.0 * span / (crossings.len() - 1) as f64)
}
