//! The parity bounds of `shaders/ocean/wake.wgsl`: `wake_source_height`,
//! `wake_source_height_grad` and the foam evaluated again with `render::wgsl_accuracy::Inexact`
//! numbers over the frame's own (f32) sources, so every point gets the most a conforming GPU
//! may differ from the exact value of the shader's formula at its inputs, by WGSL's accuracy
//! of each operation (exp 3 + 2|x| ULP, sqrt inherited from 1.0/inverseSqrt, division 2.5 ULP,
//! sin and cos 2^-11 absolute on the phase reduced to [−π, π]).

use ocean::wake::GpuWakeSource;
use render::wgsl_accuracy::{Inexact, dot, sum};

/// The wake constants of the prelude, as the GPU gets them.
pub struct Constants {
    pub min_r2: f32,
    pub gauss_cutoff: f32,
    pub tau: f32,
}

/// One source's (height, ∂h/∂x, ∂h/∂z) at `p`, or its height, gradient and foam zero when a
/// branch skips it. A branch a conforming GPU may take either way widens each output's bound
/// to cover both ways.
fn source(s: &GpuWakeSource, p: [f32; 2], c: &Constants) -> [Inexact; 3] {
    let of = Inexact::of;
    let d = [of(p[0]) - of(s.pos[0]), of(p[1]) - of(s.pos[1])];
    let r2 = dot(&d, &d);
    let k = of(s.q) / r2;
    let g = k * k * of(s.gauss);
    let zero = [Inexact::exact(0.0); 3];
    // The shader's skips: beyond the cull radius, nearer than WAKE_MIN_R2, past the cutoff.
    let skips = [
        r2.above(f64::from(s.cull_r2)),
        r2.above(f64::from(c.min_r2)).map(|far| !far),
        g.above(f64::from(c.gauss_cutoff)),
    ];
    if skips.contains(&Some(true)) {
        return zero;
    }
    let undecided = skips.contains(&None);
    let r = r2.sqrt();
    let phi = of(s.q) / r;
    // phi − WAKE_TAU·round(phi / WAKE_TAU): round picks the nearest whole turn; at a half
    // turn either neighbour (sin and cos then differ only by the turn's error).
    let turns = (phi.value / std::f64::consts::TAU).round();
    let tau = Inexact::input(std::f64::consts::TAU, c.tau);
    let phi_r = phi - tau * Inexact::exact(turns);
    let phi_r = Inexact {
        value: phi_r.value,
        error: phi_r.error + tau.error,
    };
    let (sn, cs) = (phi_r.sin(), phi_r.cos());
    let e = (-g).exp();
    let four_g = Inexact::exact(4.0) * g;
    let bracket = sn + (four_g - Inexact::exact(3.0)) / phi * cs;
    let amp = of(s.strength) * k * k / r * e;
    let dx = [of(s.dx[0]), of(s.dx[1])];
    let proj = dot(&d, &dx);
    let height = -(amp * bracket) * proj / r;
    let cc = -of(s.strength) * k * k / r2 * e;
    let f = cc * bracket;
    let df = cc / r
        * ((four_g - Inexact::exact(6.0)) * bracket
            - phi * cs
            - (Inexact::exact(12.0) * g + Inexact::exact(3.0)) / phi * cs
            + (four_g - Inexact::exact(3.0)) * sn);
    let grad = [0, 1].map(|i| df * proj * d[i] / r + f * dx[i]);
    let out = [height, grad[0], grad[1]];
    if undecided {
        out.map(|o| Inexact {
            value: o.value,
            error: o.value.abs() + 2.0 * o.error,
        })
    } else {
        out
    }
}

/// The height, ∂h/∂x and ∂h/∂z the test kernel sums at `p` over `sources`.
pub fn height_and_gradient(sources: &[GpuWakeSource], p: [f32; 2], c: &Constants) -> [Inexact; 3] {
    let terms: Vec<[Inexact; 3]> = sources.iter().map(|s| source(s, p, c)).collect();
    [0, 1, 2].map(|i| sum(&terms.iter().map(|t| t[i]).collect::<Vec<_>>()))
}

/// `wake_foam_from_density` of the summed `wake_source_foam` at `p`.
pub fn foam(sources: &[GpuWakeSource], p: [f32; 2]) -> Inexact {
    let of = Inexact::of;
    let terms: Vec<Inexact> = sources
        .iter()
        .map(|s| {
            let d = [of(p[0]) - of(s.pos[0]), of(p[1]) - of(s.pos[1])];
            of(s.foam) * (-(dot(&d, &d) / of(s.foam_w2))).exp()
        })
        .collect();
    (Inexact::exact(1.0) - (-sum(&terms)).exp()).clamp(0.0, 1.0)
}
