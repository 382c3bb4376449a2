//! Parity bounds of the optics (`optics.wgsl`) and of the current around the marks
//! (`flowmap.wgsl`'s `current_at`): each function evaluated again with
//! `render::wgsl_accuracy::Inexact` numbers, so every case gets the most a conforming GPU may
//! differ from the f64 reference by WGSL's accuracy of each operation.

use glam::DVec2;
use render::optics::{N_AIR, N_WATER};
use render::wgsl_accuracy::{Inexact, dot};

fn input(v: f64) -> Inexact {
    Inexact::input(v, v as f32)
}

/// The optics kernel's outputs for an incidence cosine `c` (f32, the reference's too): full
/// Fresnel reflectance, Schlick's, and the refracted direction's x and y, air into water,
/// through a level surface, the ray in the x–y plane with s = sqrt(max(1 − c², 0)).
pub fn optics(c: f32) -> [Inexact; 4] {
    let one = Inexact::exact(1.0);
    let (n1, n2) = (input(N_AIR), input(N_WATER));
    let c = Inexact::of(c);
    // fresnel_reflectance(c, n1, n2)
    let cos_i = c.abs().min(one);
    let eta = n1 / n2;
    let sin2_t = eta * eta * (one - cos_i * cos_i);
    let cos_t = (one - sin2_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    let full = Inexact::exact(0.5) * (rs * rs + rp * rp);
    // schlick_reflectance(c, n1, n2): n1 < n2, no total reflection branch.
    let q = (n1 - n2) / (n1 + n2);
    let r0 = q * q;
    let schlick = r0 + (one - r0) * (one - cos_i).pow(Inexact::exact(5.0));
    // refract_dir((s, −c, 0), (0, 1, 0), n1, n2)
    let s = (one - c * c).max(Inexact::exact(0.0)).sqrt();
    let d = [s, -c, Inexact::exact(0.0)];
    let n = [Inexact::exact(0.0), one, Inexact::exact(0.0)];
    let cos_d = -dot(&n, &d);
    let k = one - eta * eta * (one - cos_d * cos_d);
    let coefficient = eta * cos_d - k.sqrt();
    let t = [eta * d[0] + coefficient * n[0], eta * d[1] + coefficient * n[1]];
    [full, schlick, t[0], t[1]]
}

/// `current_at(p)` of `flowmap.wgsl` for the current `u`, the marks' radius `radius` and
/// their centres `marks` (the reference's f64; the GPU gets their f32), at the f32 point `p`.
/// `None` when a conforming GPU may put `p` inside a mark or not (on its rim).
pub fn current_at(p: [f32; 2], u: DVec2, radius: f64, marks: &[DVec2]) -> Option<[Inexact; 2]> {
    let u = [input(u.x), input(u.y)];
    let radius = input(radius);
    let a2 = radius * radius;
    let mut v = u;
    let mut inside = false;
    for m in marks {
        let d = [
            Inexact::of(p[0]) - input(m.x),
            Inexact::of(p[1]) - input(m.y),
        ];
        let r2 = dot(&d, &d);
        let rim = r2 - a2;
        match rim.above(0.0) {
            None => return None,
            Some(false) => inside = true,
            Some(true) => {}
        }
        let d2 = [d[0] * d[0] - d[1] * d[1], Inexact::exact(2.0) * d[0] * d[1]];
        let scale = a2 / (r2 * r2);
        let w = [u[0] * d2[0] + u[1] * d2[1], u[0] * d2[1] - u[1] * d2[0]];
        v = [v[0] - scale * w[0], v[1] - scale * w[1]];
    }
    Some(if inside {
        [Inexact::exact(0.0); 2]
    } else {
        v
    })
}
