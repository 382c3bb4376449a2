use super::*;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// f64 (sin 2πu, cos 2πu): the reference.
fn exact(u: f64) -> [f64; 2] {
    let (s, c) = (TAU * u).sin_cos();
    [s, c]
}

fn f16(bits: u16) -> f64 {
    half::f16::from_bits(bits).to_f64()
}

#[test]
fn each_texel_is_sin_and_cos_at_its_centre_rounded_to_the_nearest_half_float() {
    let table = turn_table();
    assert_eq!(table.len(), TURN_TABLE_TEXELS as usize);
    let n = f64::from(TURN_TABLE_TEXELS);
    for (i, t) in table.iter().enumerate() {
        let want = exact((i as f64 + 0.5) / n);
        for c in 0..2 {
            let got = f16(t[c]);
            assert!(
                (got - want[c]).abs() <= HALF_FLOAT_ROUNDING_BELOW_ONE,
                "texel {i} component {c}: {got} vs {}",
                want[c]
            );
            // The nearest: neither neighbouring half float is closer.
            for step in [-1i32, 1] {
                let other = f16((i32::from(t[c]) + step) as u16);
                if other.is_finite() {
                    assert!(
                        (other - want[c]).abs() >= (got - want[c]).abs(),
                        "texel {i}"
                    );
                }
            }
        }
    }
    // Texel 0 is a quarter texel past u = 0: sin π/N, cos π/N.
    assert_eq!(f16(table[0][1]), 1.0);
    assert!((f16(table[0][0]) - (std::f64::consts::PI / n)).abs() < 1e-6);
    // The bytes the renderer uploads: the same texels, little-endian f16 pairs.
    let bytes = turn_table_bytes();
    assert_eq!(bytes.len(), 4 * TURN_TABLE_TEXELS as usize);
    assert_eq!(u16::from_le_bytes([bytes[4], bytes[5]]), table[1][0]);
    assert_eq!(u16::from_le_bytes([bytes[6], bytes[7]]), table[1][1]);
}

/// The phases the mirror is checked at: seeded random turns in [0, 1), every point halfway
/// between texel centres (where the chord errs most), the centres themselves, the wrap from
/// the last texel to the first, and phases of many turns (the kernels' u reaches hundreds).
fn phases() -> Vec<f32> {
    let n = TURN_TABLE_TEXELS;
    let mut rng = SmallRng::seed_from_u64(0x7e_a5e);
    let mut u: Vec<f32> = (0..200_000).map(|_| rng.random::<f32>()).collect();
    u.extend((0..n).map(|i| i as f32 / n as f32));
    u.extend((0..n).map(|i| (i as f32 + 0.5) / n as f32));
    u.extend([0.0, 1e-7, 0.5 / n as f32, 1.0 - 1e-7, 1.0 - 0.25 / n as f32]);
    u.extend((0..20_000).map(|_| rng.random_range(1.0f32..800.0)));
    u
}

#[test]
fn the_mirror_is_within_its_bound_of_sin_and_cos() {
    let bound = turn_table_error(TURN_TABLE_TEXELS).exact_filter();
    let (mut worst, mut worst_mid) = (0.0f64, 0.0f64);
    let n = TURN_TABLE_TEXELS as usize;
    for (k, u) in phases().into_iter().enumerate() {
        // The reference at the turn the shader looks up: fract(u) in f32 (exact for u ≥ 0).
        let f = f64::from(u - u.floor());
        let want = exact(f);
        let got = turn_sin_cos_f32(u);
        for c in 0..2 {
            let err = (f64::from(got[c]) - want[c]).abs();
            assert!(
                err <= bound,
                "u {u}: component {c} {} vs {}",
                got[c],
                want[c]
            );
            worst = worst.max(err);
            if (200_000..200_000 + n).contains(&k) {
                worst_mid = worst_mid.max(err);
            }
        }
    }
    eprintln!("turn table (exact filter): worst {worst:.3e}, bound {bound:.3e}");
    // The bound is reached to within a factor 2 (the texels' rounding dominates it).
    assert!(worst > 0.5 * bound, "{worst} vs {bound}");
    assert!(worst_mid > 0.0);
    // A table built at the texel corners instead of their centres is off by half a texel
    // (π/N radians times a slope up to 1): far past the bound.
    let wrong = turn_table_texels_at(TURN_TABLE_TEXELS, 0.0);
    let missed = phases()
        .iter()
        .map(|&u| {
            let f = f64::from(u - u.floor());
            let (got, want) = (sample(&wrong, f), exact(f));
            (got[0] - want[0]).abs().max((got[1] - want[1]).abs())
        })
        .fold(0.0, f64::max);
    assert!(missed > 4.0 * bound, "{missed}");
}

/// A filter as loose as the bound allows: the texel coordinate off by 2⁻²¹ turns, the weight
/// truncated (or rounded) to 1/16, the products and the sum rounded to half floats. Such a
/// GPU's samples stay within [`TurnTableError::total`], and the snap alone takes them past
/// the exact filter's bound (so its term is needed).
#[test]
fn a_filter_as_loose_as_vulkan_allows_is_within_the_total() {
    let e = turn_table_error(TURN_TABLE_TEXELS);
    let table = turn_table();
    let n = TURN_TABLE_TEXELS as i64;
    let half = |x: f64| half::f16::from_f64(x).to_f64();
    let loose = |f: f64, truncate: bool, nudge: f64| -> [f64; 2] {
        let x = (f + nudge) * n as f64 - 0.5;
        let base = x.floor();
        let w = if truncate {
            ((x - base) * 16.0).floor() / 16.0
        } else {
            ((x - base) * 16.0).round() / 16.0
        };
        let a = table[(base as i64).rem_euclid(n) as usize].map(f16);
        let b = table[(base as i64 + 1).rem_euclid(n) as usize].map(f16);
        [0, 1].map(|c| half(half((1.0 - w) * a[c]) + half(w * b[c])))
    };
    let (mut worst, mut worst_snap) = (0.0f64, 0.0f64);
    for u in phases() {
        let f = f64::from(u - u.floor());
        let want = exact(f);
        for (truncate, nudge) in [(true, 0.0), (false, 0.0), (true, 2f64.powi(-21))] {
            let got = loose(f, truncate, nudge);
            for c in 0..2 {
                let err = (got[c] - want[c]).abs();
                assert!(err <= e.total(), "u {u} component {c}: {err:.3e}");
                worst = worst.max(err);
            }
        }
        let snapped = {
            let x = f * n as f64 - 0.5;
            let base = x.floor();
            let w = ((x - base) * 16.0).floor() / 16.0;
            let a = table[(base as i64).rem_euclid(n) as usize].map(f16);
            let b = table[(base as i64 + 1).rem_euclid(n) as usize].map(f16);
            [0, 1].map(|c| a[c] + w * (b[c] - a[c]))
        };
        for c in 0..2 {
            worst_snap = worst_snap.max((snapped[c] - want[c]).abs());
        }
    }
    eprintln!(
        "turn table (loosest filter): worst {worst:.3e}, bound {:.3e}; snapped weights alone {worst_snap:.3e}",
        e.total()
    );
    assert!(worst_snap > e.exact_filter(), "{worst_snap}");
    assert!(worst_snap <= e.f32_filter(), "{worst_snap}");
}

#[test]
fn the_table_is_the_smallest_within_wgsl_sin_and_cos_when_filtered_in_f32() {
    assert_eq!(
        texels_within(WGSL_SIN_COS_ABSOLUTE),
        Some(TURN_TABLE_TEXELS)
    );
    let e = turn_table_error(TURN_TABLE_TEXELS);
    assert!(turn_table_error(TURN_TABLE_TEXELS / 2).f32_filter() > WGSL_SIN_COS_ABSOLUTE);
    // The figures the module docs state.
    for (got, want) in [
        (e.interpolation, 1.18e-6),
        (e.filtering, 2.22e-4),
        (e.total(), 9.59e-4),
        (e.f32_filter(), 4.71e-4),
        (e.exact_filter(), 2.45e-4),
        (turn_table_error(1024).f32_filter(), 6.66e-4),
    ] {
        assert!(
            (got - want).abs() <= 0.005 * want,
            "{got:.4e} vs {want:.4e}"
        );
    }
    // The half-float format alone (texels and filter) is past WGSL's bound at any size.
    assert!(e.texel_rounding + e.filter_rounding > WGSL_SIN_COS_ABSOLUTE);
    // The chord's h²/8: the f64 linear interpolant of sin halfway between two points h apart.
    let h = TAU / f64::from(TURN_TABLE_TEXELS);
    let chord = 1.0 - (h / 2.0).cos();
    assert!((chord - e.interpolation).abs() <= 1e-3 * e.interpolation);
}
