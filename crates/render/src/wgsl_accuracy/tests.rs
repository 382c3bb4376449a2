//! The bounds against f32 arithmetic: the CPU's own (correctly rounded) and a simulated
//! conforming GPU that errs by as much as the specification allows at every operation, in a
//! direction drawn from a fixed-seed generator.

use super::*;

/// A fixed-seed generator (64-bit LCG, top bits): uniform in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn sign(&mut self) -> f64 {
        if self.next() < 0.5 { -1.0 } else { 1.0 }
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

#[test]
fn ulp_is_the_spacing_of_f32_values() {
    let mut rng = Lcg(7);
    let mut values: Vec<f32> = (-30..30).map(|e| 2f32.powi(e)).collect();
    values.extend((0..2000).map(|_| (rng.range(-40.0, 40.0).exp2() * rng.sign()) as f32));
    for x in values {
        let above = f32::from_bits(x.abs().to_bits() + 1);
        assert_eq!(ulp(f64::from(x)), f64::from(above - x.abs()), "{x:e}");
    }
    assert_eq!(ulp(0.0), 0.0);
    assert_eq!(ulp(1e-40), 2f64.powi(-149));
    // The same for half floats: 1 has 2^-10 above it, 0.75 has 2^-11.
    assert_eq!(half_float_ulp(1.0), 2f64.powi(-10));
    assert_eq!(half_float_ulp(0.75), 2f64.powi(-11));
    assert_eq!(to_half_float(0.5 + 2f64.powi(-13)), 0.5);
}

#[test]
fn the_bounds_state_the_specifications_numbers() {
    // An exact argument: each built-in's own allowance and nothing more.
    let x = Inexact::of(0.75);
    assert_eq!(x.sin().error, 2f64.powi(-11));
    assert_eq!(
        (Inexact::of(1.0) / Inexact::of(3.0)).error,
        2.5 * ulp(1.0 / 3.0)
    );
    assert_eq!(x.inverse_sqrt().error, 2.0 * ulp(1.0 / 0.75f64.sqrt()));
    assert_eq!(Inexact::of(2.0).exp().error, 7.0 * ulp(2f64.exp()));
    assert_eq!(x.log2().error, 2f64.powi(-21));
    assert_eq!(Inexact::of(8.0).log2().error, 3.0 * ulp(3.0));
    assert_eq!((x * x).error, UNIT_ROUNDOFF * 0.5625);
    // Beyond [−π, π], the reduction assumption adds 2 ULP of the argument.
    let far = Inexact::of(300.0).cos();
    assert_eq!(far.error, 2f64.powi(-11) + 2.0 * ulp(300.0));
    // A division by what may be 0 is not bounded.
    let zero = Inexact {
        value: 1e-3,
        error: 2e-3,
    };
    assert!((x / zero).error.is_infinite());
}

/// An f32 computed as a conforming GPU may: each operation's f32 result moved by up to the
/// specification's allowance, in a random direction.
#[derive(Clone, Copy)]
struct Gpu32(f32);

struct Adversary(Lcg);

impl Adversary {
    /// `exact` rounded to f32, then moved by a random fraction of `ulps` ULP.
    fn ulps(&mut self, exact: f64, ulps: f64) -> Gpu32 {
        let allowed = ulps * ulp(exact);
        self.within(exact, allowed)
    }
    fn abs(&mut self, exact: f64, absolute: f64) -> Gpu32 {
        self.within(exact, absolute)
    }
    /// An f32 within `allowed` of `exact`, a random way and distance off.
    fn within(&mut self, exact: f64, allowed: f64) -> Gpu32 {
        let mut got = (exact + self.0.sign() * self.0.next() * allowed) as f32;
        // Rounding to f32 may step past the allowance: step back towards `exact`.
        while (f64::from(got) - exact).abs() > allowed {
            let bits = got.to_bits();
            let towards_zero = f32::from_bits(bits - 1);
            let away = f32::from_bits(bits + 1);
            got = if (f64::from(towards_zero) - exact).abs() < (f64::from(away) - exact).abs() {
                towards_zero
            } else {
                away
            };
        }
        Gpu32(got)
    }
    fn add(&mut self, a: Gpu32, b: Gpu32) -> Gpu32 {
        Gpu32(a.0 + b.0)
    }
    fn sub(&mut self, a: Gpu32, b: Gpu32) -> Gpu32 {
        Gpu32(a.0 - b.0)
    }
    fn mul(&mut self, a: Gpu32, b: Gpu32) -> Gpu32 {
        Gpu32(a.0 * b.0)
    }
    fn div(&mut self, a: Gpu32, b: Gpu32) -> Gpu32 {
        self.ulps(f64::from(a.0) / f64::from(b.0), DIVISION_ULP)
    }
    fn sqrt(&mut self, a: Gpu32) -> Gpu32 {
        let inverse = self.ulps(1.0 / f64::from(a.0).sqrt(), INVERSE_SQRT_ULP);
        self.div(Gpu32(1.0), inverse)
    }
    fn sin(&mut self, a: Gpu32) -> Gpu32 {
        let x = f64::from(a.0);
        // The reduction assumption: the argument moved by 2 ULP, then 2^-11 absolute.
        let reduced = if x.abs() > PI {
            x + self.0.sign() * self.0.next() * ARGUMENT_REDUCTION_ULP * ulp(x) * 0.999
        } else {
            x
        };
        self.abs(reduced.sin(), SIN_COS_ABSOLUTE)
    }
    fn exp(&mut self, a: Gpu32) -> Gpu32 {
        let x = f64::from(a.0);
        self.ulps(x.exp(), exp_ulp(x))
    }
    fn atan2(&mut self, y: Gpu32, x: Gpu32) -> Gpu32 {
        self.ulps(f64::from(y.0).atan2(f64::from(x.0)), ATAN_ULP)
    }
}

/// One refraction and plane hit as `refract_dir` and `ray_plane` compute them, with both
/// arithmetics: returns (exact, bound) and the adversary's f32 result, per component.
fn refract_to_plane(
    d: [f32; 3],
    n: [f32; 3],
    o: [f32; 3],
    depth: f32,
    adv: &mut Adversary,
) -> ([Inexact; 3], [f32; 3]) {
    // The bound.
    let di = d.map(Inexact::of);
    let ni = n.map(Inexact::of);
    let eta = Inexact::of(1.0) / Inexact::of(1.333);
    let cos_i = -dot(&ni, &di);
    let k = Inexact::exact(1.0) - eta * eta * (Inexact::exact(1.0) - cos_i * cos_i);
    let t = add3(scale3(eta, di), scale3(eta * cos_i - k.sqrt(), ni));
    let s = -(Inexact::of(o[1]) + Inexact::of(depth)) / t[1];
    let hit = add3(o.map(Inexact::of), scale3(s, t));
    // The adversary.
    let g = |v: f32| Gpu32(v);
    let eta_g = adv.div(g(1.0), g(1.333));
    let mut dn = adv.mul(g(n[0]), g(d[0]));
    for i in 1..3 {
        let p = adv.mul(g(n[i]), g(d[i]));
        dn = adv.add(dn, p);
    }
    let cos_g = Gpu32(-dn.0);
    let c2 = adv.mul(cos_g, cos_g);
    let one_minus = adv.sub(g(1.0), c2);
    let e2 = adv.mul(eta_g, eta_g);
    let e2s = adv.mul(e2, one_minus);
    let k_g = adv.sub(g(1.0), e2s);
    let root = adv.sqrt(k_g);
    let ec = adv.mul(eta_g, cos_g);
    let coef = adv.sub(ec, root);
    let t_g: Vec<Gpu32> = (0..3)
        .map(|i| {
            let a = adv.mul(eta_g, g(d[i]));
            let b = adv.mul(coef, g(n[i]));
            adv.add(a, b)
        })
        .collect();
    let num = adv.add(g(o[1]), g(depth));
    let s_g = adv.div(Gpu32(-num.0), t_g[1]);
    let hit_g = [0, 1, 2].map(|i| {
        let step = adv.mul(s_g, t_g[i]);
        adv.add(g(o[i]), step).0
    });
    (hit, hit_g)
}

#[test]
fn a_refracted_plane_hit_stays_within_its_bound_on_a_worst_case_gpu() {
    // Unit view directions down at 1° to 89° below the horizon through normals tilted up to
    // 60°, to a plane 0.01–10 m down: the adversary's hit always lies within the bound, and
    // the bound is not vacuous (a well-conditioned vertical ray: a few dozen ULP of the depth).
    let mut rng = Lcg(11);
    let mut adv = Adversary(Lcg(12));
    let mut worst_ratio = 0.0f64;
    for _ in 0..20_000 {
        let (el, az) = (rng.range(0.0175, 1.553), rng.range(0.0, 2.0 * PI));
        let d = [el.cos() * az.cos(), -el.sin(), el.cos() * az.sin()];
        let (tilt, naz) = (rng.range(0.0, 1.05), rng.range(0.0, 2.0 * PI));
        let n = [tilt.sin() * naz.cos(), tilt.cos(), tilt.sin() * naz.sin()];
        let o = [
            rng.range(-5.0, 5.0),
            rng.range(-0.3, 0.3),
            rng.range(-5.0, 5.0),
        ];
        let depth = rng.range(0.01, 10.0) as f32;
        let (bound, got) = refract_to_plane(
            d.map(|c| c as f32),
            n.map(|c| c as f32),
            o.map(|c| c as f32),
            depth,
            &mut adv,
        );
        for (b, g) in bound.iter().zip(got) {
            if b.error.is_finite() {
                let ratio = (f64::from(g) - b.value).abs() / b.error;
                worst_ratio = worst_ratio.max(ratio);
                assert!(ratio <= 1.0, "{g} against {b:?}");
            }
        }
    }
    eprintln!("worst adversary error / bound: {worst_ratio:.3}");
    // The bound is reached within a factor of ten, not loose by orders of magnitude.
    assert!(worst_ratio > 0.1, "{worst_ratio}");
    let (steep, _) = refract_to_plane([0.0, -1.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3], 1.0, &mut adv);
    assert!(steep.iter().all(|c| c.error < 40.0 * ulp(1.0)), "{steep:?}");
}

#[test]
fn a_wave_sum_stays_within_its_bound_on_a_worst_case_gpu() {
    // Σ a_i sin(k_i x + φ_i) with phases out to 600 rad (beyond [−π, π]: the reduction
    // assumption) and exp(−x) of a path: the adversary's result within the bound.
    let mut rng = Lcg(21);
    let mut adv = Adversary(Lcg(22));
    for _ in 0..2_000 {
        let x = rng.range(-200.0, 200.0) as f32;
        let mut sum = Inexact::exact(0.0);
        let mut sum_g = Gpu32(0.0);
        for _ in 0..16 {
            let (a, k, phi) = (
                rng.range(0.01, 1.0) as f32,
                rng.range(0.01, 3.0) as f32,
                rng.range(0.0, std::f64::consts::TAU) as f32,
            );
            let theta = Inexact::of(k) * Inexact::of(x) + Inexact::of(phi);
            sum = sum + Inexact::of(a) * theta.sin();
            let kx = adv.mul(Gpu32(k), Gpu32(x));
            let theta_g = adv.add(kx, Gpu32(phi));
            let s = adv.sin(theta_g);
            let term = adv.mul(Gpu32(a), s);
            sum_g = adv.add(sum_g, term);
        }
        assert!(
            (f64::from(sum_g.0) - sum.value).abs() <= sum.error,
            "{} {sum:?}",
            sum_g.0
        );
        let path = rng.range(0.0, 20.0) as f32;
        let e = (-Inexact::of(path)).exp();
        let e_g = adv.exp(Gpu32(-path));
        assert!((f64::from(e_g.0) - e.value).abs() <= e.error);
        let (y, z) = (rng.range(-1.0, 1.0) as f32, rng.range(-1.0, 1.0) as f32);
        let a = Inexact::of(y).atan2(Inexact::of(z));
        let a_g = adv.atan2(Gpu32(y), Gpu32(z));
        assert!((f64::from(a_g.0) - a.value).abs() <= a.error);
    }
}

#[test]
fn the_cpus_own_f32_lies_within_the_bounds() {
    // Rust's f32 arithmetic is correctly rounded and its acos, exp and powf within an ULP or
    // two: far inside what WGSL allows.
    let mut rng = Lcg(31);
    for _ in 0..5_000 {
        let x = rng.range(-1.0, 1.0) as f32;
        let b = Inexact::of(x).acos();
        assert!((f64::from(x.acos()) - b.value).abs() <= b.error, "acos {x}");
        let (base, e) = (rng.range(0.01, 4.0) as f32, rng.range(-3.0, 3.0) as f32);
        let p = Inexact::of(base).pow(Inexact::of(e));
        assert!(
            (f64::from(base.powf(e)) - p.value).abs() <= p.error,
            "pow {base} {e}"
        );
        let v = [
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        ]
        .map(|c| c as f32);
        let n = normalize(v.map(Inexact::of));
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        for i in 0..3 {
            assert!((f64::from(v[i] / l) - n[i].value).abs() <= n[i].error);
            // A unit vector's components: within about ten roundings.
            assert!(n[i].error < 24.0 * UNIT_ROUNDOFF, "{:?}", n[i]);
        }
        let t = rng.range(-0.5, 1.5) as f32;
        let s = smoothstep(Inexact::of(0.2), Inexact::of(0.9), Inexact::of(t));
        let tc = ((t - 0.2) / (0.9 - 0.2)).clamp(0.0, 1.0);
        assert!((f64::from(tc * tc * (3.0 - 2.0 * tc)) - s.value).abs() <= s.error);
    }
}
