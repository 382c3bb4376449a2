//! The parity bounds of the water pass's sea: `gerstner`, `sea_displaced` and the foam of
//! `surface_frame` evaluated again with `render::wgsl_accuracy::Inexact` numbers, so every
//! point gets the most a conforming GPU may differ from ocean's f64 sea by WGSL's accuracy of
//! each operation. The phases reach well beyond [−π, π] (k·D·p over hundreds of metres), where
//! WGSL states nothing for sin and cos: the bound uses the argument-reduction assumption of
//! `render::wgsl_accuracy` (2 ULP of the argument).

use ocean::{Wave, WaveSet};
use render::wgsl_accuracy::{Inexact, dot, sum};

/// One wave as the GPU gets it (`ocean::GpuWave`), each input the f32 of the f64 value the
/// reference uses (the products formed in f64 on the CPU, rounded once).
pub struct WaveBound {
    /// k D.
    wavevector: [Inexact; 2],
    phase0: Inexact,
    /// A D and A.
    amplitude_direction: [Inexact; 2],
    amplitude: Inexact,
    /// k A D_x², k A D_x D_z, k A D_z².
    slope_xx: Inexact,
    slope_xz: Inexact,
    slope_zz: Inexact,
}

/// The waves of `sea` at race time `t` for the local origin `origin`, as `gpu_waves` gives
/// them.
pub fn waves(sea: &WaveSet, t: f64, origin: [f64; 2]) -> Vec<WaveBound> {
    sea.waves
        .iter()
        .zip(sea.gpu_waves(t, origin))
        .map(|(w, g): (&Wave, _)| {
            let (k, a) = (w.k(), w.amplitude());
            let [dx, dz] = w.direction;
            WaveBound {
                wavevector: [
                    Inexact::input(k * dx, g.wavevector[0]),
                    Inexact::input(k * dz, g.wavevector[1]),
                ],
                phase0: Inexact::input(ocean::reduce_phase(sea.phase_at(w, origin, t)), g.phase0),
                amplitude_direction: [
                    Inexact::input(a * dx, g.amplitude_direction[0]),
                    Inexact::input(a * dz, g.amplitude_direction[1]),
                ],
                amplitude: Inexact::input(a, g.amplitude),
                slope_xx: Inexact::input(k * a * dx * dx, g.slope_xx),
                slope_xz: Inexact::input(k * a * dx * dz, g.slope_xz),
                slope_zz: Inexact::input(k * a * dz * dz, g.slope_zz),
            }
        })
        .collect()
}

/// The local point `p` the GPU gets (f32) for the reference's local point `exact`.
pub fn point(exact: [f64; 2], gpu: [f32; 2]) -> [Inexact; 2] {
    [
        Inexact::input(exact[0], gpu[0]),
        Inexact::input(exact[1], gpu[1]),
    ]
}

/// `wave_phase(w, p)` of `common.wgsl`: dot(k D, p) + θ0.
fn phase(w: &WaveBound, p: [Inexact; 2]) -> Inexact {
    dot(&w.wavevector, &p) + w.phase0
}

/// `gerstner(w, p)` of `common.wgsl`: ((A D)x·cos θ, A·sin θ, (A D)z·cos θ).
pub fn gerstner(w: &WaveBound, p: [Inexact; 2]) -> [Inexact; 3] {
    let theta = phase(w, p);
    let c = theta.cos();
    [
        w.amplitude_direction[0] * c,
        w.amplitude * theta.sin(),
        w.amplitude_direction[1] * c,
    ]
}

/// The sum of `terms` per component, added to `start` (the loops of `cs_main` and
/// `sea_displaced`; bounded for any order of the additions).
pub fn accumulate(start: [Inexact; 3], terms: &[[Inexact; 3]]) -> [Inexact; 3] {
    [0, 1, 2].map(|c| {
        let all: Vec<Inexact> = std::iter::once(start[c])
            .chain(terms.iter().map(|t| t[c]))
            .collect();
        sum(&all)
    })
}

/// The foam `cs_foam` draws at `p` (footprint 0: every wave kept, fade exactly 1) with wake
/// foam `wake` (the reference's f64, the GPU's f32): `surface_frame`'s Jacobian determinant,
/// `foam_from_jacobian` and `foam_coverage`.
pub fn foam(waves: &[WaveBound], p: [Inexact; 2], wake: (f64, f32)) -> Inexact {
    let one = Inexact::exact(1.0);
    let mut xx = vec![one];
    let mut xz = vec![Inexact::exact(0.0)];
    let mut zz = vec![one];
    for w in waves {
        // `resolved_waves` (fade exactly 1): the CPU's k A·direction products times sin θ.
        let s = phase(w, p).sin();
        xx.push(-(w.slope_xx * s));
        xz.push(-(w.slope_xz * s));
        zz.push(-(w.slope_zz * s));
    }
    let (xx, xz, zz) = (sum(&xx), sum(&xz), sum(&zz));
    let jacobian = xx * zz - xz * xz;
    let onset = Inexact::input(
        ocean::FOAM_ONSET_JACOBIAN,
        ocean::FOAM_ONSET_JACOBIAN as f32,
    );
    let sea = ((onset - jacobian) / onset).clamp(0.0, 1.0);
    let wake = Inexact::input(wake.0, wake.1).clamp(0.0, 1.0);
    one - (one - sea) * (one - wake)
}
