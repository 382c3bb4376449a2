//! The parity bounds of `refracted_table`, `edge_weight`, `overhead_sun` and `ring_hit`:
//! each shader function evaluated again with `render::wgsl_accuracy::Inexact` numbers, so
//! every case gets the most a conforming GPU may differ from the f64 reference by WGSL's
//! accuracy of each operation and the case's own condition.

use glam::DVec3;
use render::optics::{N_AIR, N_WATER, PinholeCamera};
use render::wgsl_accuracy::{Inexact, add3, dot, mix, scale3};

/// What a case's bound decided: the value (f64) and bound of each output, or `Undecided` when
/// one of the function's branches may go either way on a conforming GPU (the case is not
/// bounded; the tests count these and require few).
pub enum Bounded<T> {
    Decided(T),
    Undecided,
}

/// `ex` as the GPU gets it (its f32) against the reference's f64.
fn input(reference: f64) -> Inexact {
    Inexact::input(reference, reference as f32)
}

fn vec3(v: [f32; 4]) -> [Inexact; 3] {
    [Inexact::of(v[0]), Inexact::of(v[1]), Inexact::of(v[2])]
}

/// The effects' uniform as the GPU holds it: the camera's image projection (columns), each
/// entry the f32 of the reference's f64.
pub struct CameraBound {
    projection: [[Inexact; 4]; 4],
    /// The same projection in f64, for `table_image`'s column.
    exact: glam::DMat4,
    /// The render camera's projection to the screen's uv, f64 (`straight_image`'s screen),
    /// and its eye's height.
    screen: glam::DMat4,
    eye_y: f64,
}

impl CameraBound {
    /// The physical `camera`, the screen drawn by the pinhole camera `render`.
    pub fn seen_by(camera: &PinholeCamera, render: &PinholeCamera) -> Self {
        let exact = camera.image_projection(camera.pose.inverse());
        Self {
            projection: exact.to_cols_array_2d().map(|col| col.map(input)),
            exact,
            screen: render.image_projection(render.pose.inverse()),
            eye_y: render.position().y,
        }
    }

    /// `straight_through`'s uv (`refraction.wgsl`) for a table `depth` deep at screen uv `screen`:
    /// the map formed in f64 on the CPU (`effects::passes::straight_image`) reaches the GPU
    /// as its f32 (all zero without one: w = 0, the image's centre).
    fn straight_uv(&self, screen: [Inexact; 2], depth: f64) -> Bounded<Option<[Inexact; 2]>> {
        let Some(m) = effects::passes::straight_image(self.screen, self.exact, depth, self.eye_y)
        else {
            return Bounded::Decided(None);
        };
        let cols = [m.x_axis, m.y_axis, m.z_axis].map(|c| [c.x, c.y, c.z].map(input));
        let row = |i: usize| {
            render::wgsl_accuracy::sum(&[
                cols[0][i] * screen[0],
                cols[1][i] * screen[1],
                cols[2][i],
            ])
        };
        in_front([row(0), row(1), row(2)])
    }

    /// `table_uv` of `effects_common.wgsl` for a table `depth` deep: the uv of the table
    /// point (x, z), or `None` behind the camera. The constant column is formed in f64 on the
    /// CPU (`effects::passes::table_column`) and reaches the GPU as its f32.
    fn table_uv(&self, xz: [Inexact; 2], depth: f64) -> Bounded<Option<[Inexact; 2]>> {
        let c = effects::passes::table_column(self.exact, depth);
        let constant = [c.x, c.y, c.z].map(input);
        let row = |i: usize| {
            let terms = [
                self.projection[0][i] * xz[0],
                self.projection[2][i] * xz[1],
                constant[i],
            ];
            render::wgsl_accuracy::sum(&terms)
        };
        in_front([row(0), row(1), row(2)])
    }
}

/// (u w, v w, w) → the uv, or `None` behind the camera (w ≤ 0): the division and the select
/// that `table_uv` and `straight_through` end with.
fn in_front(h: [Inexact; 3]) -> Bounded<Option<[Inexact; 2]>> {
    match h[2].above(0.0) {
        None => Bounded::Undecided,
        Some(false) => Bounded::Decided(None),
        Some(true) => Bounded::Decided(Some([h[0] / h[2], h[1] / h[2]])),
    }
}

/// `edge_weight` of `effects_common.wgsl`: 1 − (max-norm distance outside the image) /
/// EDGE_FADE, clamped to [0, 1].
pub fn edge_weight(uv: [Inexact; 2]) -> Inexact {
    let one = Inexact::exact(1.0);
    let outside = uv.map(|c| (-c).max(c - one));
    let fade = input(effects::refraction::EDGE_FADE);
    (one - outside[0].max(outside[1]) / fade).clamp(0.0, 1.0)
}

/// `ray_plane(o, d, (0, 1, 0, depth))` of `optics.wgsl`: the hit and its distance along the
/// ray (negative: none). dot((0, 1, 0), x) is x.y exactly.
fn ray_table(o: [Inexact; 3], d: [Inexact; 3], depth: Inexact) -> Bounded<([Inexact; 3], Inexact)> {
    if d[1].abs().above(1e-12) != Some(true) {
        return Bounded::Undecided;
    }
    let s = -(o[1] + depth) / d[1];
    Bounded::Decided((add3(o, scale3(s, d)), s))
}

/// `refract_dir(view, n, N_AIR, N_WATER)` of `optics.wgsl` (air to water: never total
/// internal reflection).
fn refract(d: [Inexact; 3], n_in: [Inexact; 3]) -> Bounded<[Inexact; 3]> {
    let facing = dot(&d, &n_in);
    let n = match facing.above(0.0) {
        None => return Bounded::Undecided,
        Some(true) => n_in.map(|c| -c),
        Some(false) => n_in,
    };
    let eta = input(N_AIR) / input(N_WATER);
    let cos_i = -dot(&n, &d);
    let one = Inexact::exact(1.0);
    let k = one - eta * eta * (one - cos_i * cos_i);
    Bounded::Decided(add3(scale3(eta, d), scale3(eta * cos_i - k.sqrt(), n)))
}

/// One case of `refracted_table`: the uv it samples (before `sample_camera`'s clamp) and the
/// path in the water, each with its bound.
pub struct TableBound {
    pub at: [Inexact; 2],
    pub path: Inexact,
}

/// `refracted_table(p, view, screen, n)` of `refraction.wgsl` over a table `depth` deep, seen
/// by `camera`; `view_ref` is the reference's view direction (the GPU gets its f32 `view`),
/// `screen_ref` the pixel's screen uv (the GPU gets its f32, in p.w and view.w).
pub fn refracted_table(
    camera: &CameraBound,
    depth: f64,
    p: [f32; 4],
    view: [f32; 4],
    view_ref: DVec3,
    screen_ref: glam::DVec2,
    n: [f32; 4],
) -> Bounded<TableBound> {
    let screen = [
        Inexact::input(screen_ref.x, p[3]),
        Inexact::input(screen_ref.y, view[3]),
    ];
    let p = vec3(p);
    let view = [
        Inexact::input(view_ref.x, view[0]),
        Inexact::input(view_ref.y, view[1]),
        Inexact::input(view_ref.z, view[2]),
    ];
    let n = vec3(n);
    let depth = input(depth);
    let centre = [Inexact::exact(0.5); 2];
    // `straight_through`: the straight uv where the view runs down (y ≤ −1e-12), the path
    // from p along the view down to the table, max(s, 0); else the centre and 0.
    let (straight, straight_path) = match view[1].above(-1e-12) {
        None => return Bounded::Undecided,
        Some(true) => (centre, Inexact::exact(0.0)),
        Some(false) => {
            let uv = match camera.straight_uv(screen, depth.value) {
                Bounded::Undecided => return Bounded::Undecided,
                Bounded::Decided(uv) => uv.unwrap_or(centre),
            };
            let s = -(p[1] + depth) / view[1];
            (uv, s.max(Inexact::exact(0.0)))
        }
    };
    let Bounded::Decided(t) = refract(view, n) else {
        return Bounded::Undecided;
    };
    let (hit, s) = match ray_table(p, t, depth) {
        Bounded::Decided(h) => h,
        Bounded::Undecided => return Bounded::Undecided,
    };
    let Some(found) = s.above(0.0) else {
        return Bounded::Undecided;
    };
    let uv = match camera.table_uv([hit[0], hit[2]], depth.value) {
        Bounded::Undecided => return Bounded::Undecided,
        Bounded::Decided(uv) => uv,
    };
    let w = match (found, uv) {
        (true, Some(uv)) => edge_weight(uv),
        _ => Inexact::exact(0.0),
    };
    let path = if found { s } else { straight_path };
    // mix(straight, clamp(uv), w) where w > 0; mix at w = 0 is `straight` itself, so the
    // select is continuous and needs no decision.
    let at = match uv {
        Some(uv) if w.value > 0.0 || w.error > 0.0 => {
            let refracted = uv.map(|c| c.clamp(0.0, 1.0));
            [0, 1].map(|i| mix(straight[i], refracted[i], w))
        }
        _ => straight,
    };
    Bounded::Decided(TableBound { at, path })
}

/// `overhead_sun(n)` of `caustics.wgsl` with its radius `radius` (the reference's f64; the
/// GPU gets its f32): the upward ray refracted out of the water, the Gaussian of its angle
/// from the zenith; 0 under total internal reflection.
pub fn overhead_sun(n: [f32; 4], radius: f64) -> Bounded<Inexact> {
    let d = [
        Inexact::exact(0.0),
        Inexact::exact(1.0),
        Inexact::exact(0.0),
    ];
    let n_in = vec3(n);
    let facing = dot(&d, &n_in);
    let n = match facing.above(0.0) {
        None => return Bounded::Undecided,
        Some(true) => n_in.map(|c| -c),
        Some(false) => n_in,
    };
    let eta = input(N_WATER) / input(N_AIR);
    let cos_i = -dot(&n, &d);
    let one = Inexact::exact(1.0);
    let k = one - eta * eta * (one - cos_i * cos_i);
    match k.above(0.0) {
        None => Bounded::Undecided,
        // Total internal reflection (k < 0; at k = 0 exactly the GPU refracts, grazing).
        // The shader returns 0 there, the reference e^{−(π/2)²/ρ²} (acos of 0): allowed.
        Some(false) if k.value < 0.0 => Bounded::Decided(Inexact {
            value: 0.0,
            error: (-(std::f64::consts::FRAC_PI_2 / radius).powi(2)).exp(),
        }),
        Some(false) => Bounded::Undecided,
        Some(true) => {
            let up_y = eta * d[1] + (eta * cos_i - k.sqrt()) * n[1];
            let angle = up_y.clamp(-1.0, 1.0).acos();
            let x = angle / input(radius);
            Bounded::Decided((-(x * x)).exp())
        }
    }
}

/// `ring_hit(p, r)` of `reflection.wgsl` for a ring of `radius` about `centre` (the
/// reference's f64; the GPU gets their f32): the exit point of the upward ray from inside the
/// ring, or `None` when the shader returns 0 (downwards, level, vertical or missing).
pub fn ring_hit(
    p: [f32; 4],
    r: [f32; 4],
    centre: [f64; 2],
    radius: f64,
) -> Bounded<Option<[Inexact; 3]>> {
    let (p, r) = (vec3(p), vec3(r));
    let o = [p[0] - input(centre[0]), p[2] - input(centre[1])];
    let d = [r[0], r[2]];
    let a = dot(&d, &d);
    let b = dot(&o, &d);
    let radius = input(radius);
    let k = b * b - a * (dot(&o, &o) - radius * radius);
    let decisions = [
        a.above(1e-8 - f64::MIN_POSITIVE),
        r[1].above(0.0),
        k.above(-f64::MIN_POSITIVE),
    ];
    let [Some(wide), Some(up), Some(meets)] = decisions else {
        return Bounded::Undecided;
    };
    if !(wide && up && meets) {
        return Bounded::Decided(None);
    }
    let s = (-b + k.max(Inexact::exact(0.0)).sqrt()) / a.max(Inexact::exact(1e-8));
    match s.above(0.0) {
        None => Bounded::Undecided,
        Some(false) => Bounded::Decided(None),
        Some(true) => Bounded::Decided(Some(add3(p, scale3(s, r)))),
    }
}
