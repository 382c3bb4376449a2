//! A table of (sin 2πu, cos 2πu) over one turn, u ∈ [0, 1): the sine and cosine of a phase
//! taken on a GPU's texture unit instead of its arithmetic units. On phone GPUs the texture
//! unit runs beside the ALUs, and a shader bound by arithmetic (the water's wake kernel,
//! `shaders/ocean/wake.wgsl`) trades the reduction of its phase to [−π, π] and its `sin` and
//! `cos` (12 operations) for a `fract` and one filtered look-up.
//!
//! The GPU holds the table as an [`TURN_TABLE_TEXELS`] × 1 `Rg16Float` texture (8 KiB: a
//! filterable format without optional features, and within the 2048 texels per side that
//! phones' downlevel limits allow), sampled with linear filtering and repeat addressing at
//! (fract(u), ½), level 0. Texel i holds the value at its centre u_i = (i + ½)/N, so the filter
//! interpolates linearly between the two texel centres around u, wrapping from the last texel
//! to the first. The shader takes `fract` of the phase in turns before the look-up, so the
//! hardware's fixed-point texture coordinates never see a large value.
//!
//! # The bound ([`turn_table_error`], per component, N texels, h = 2π/N radians apart)
//!
//! The terms follow `render::wgsl_accuracy`'s assumptions about texture filtering, which the
//! WGSL and WebGPU specifications leave unstated (that crate cannot be used here: `ocean` sits
//! below `render`; a test there holds the constants below equal to its own):
//!
//! - interpolation: the linear interpolant of f between texel centres h apart errs by at most
//!   h²/8 · max|f''| (the remainder f''(ξ)(x − a)(b − x)/2), and |sin''|, |cos''| ≤ 1 in
//!   radians: (2π/N)²/8;
//! - the texels' rounding: each texel is the f16 nearest its f64 value; for |v| ≤ 1 that errs
//!   by at most 2⁻¹² (half the f16 unit in the last place below 1, 2⁻¹¹; 1.0 itself is exact),
//!   and a convex combination of the texels keeps that bound;
//! - the filter's arithmetic: neither WebGPU nor Vulkan says in what precision a half-float
//!   texture is filtered; taken as `render::wgsl_accuracy` takes it, the weight's product
//!   and the sum each rounded to f16, ½ ULP each: 2⁻¹¹ in all (a filter in f32 adds 2⁻²⁴);
//! - the filter's weights: Vulkan guarantees only `subTexelPrecisionBits` ≥ 4, a weight
//!   snapped to 1/16 of a texel. Whether it snaps to the nearest step (within 2⁻⁵) or down
//!   (Direct3D's reference truncates) is not said, so the bound takes the whole step
//!   (`render::wgsl_accuracy::sub_texel_snap_texels`): a weight off by 1/16 moves the value
//!   by 1/16 of the difference of the two texels, at most (2π/N + 2·2⁻¹²)/16 (|f'| ≤ 2π per
//!   turn, plus the two texels' rounding);
//! - the texel coordinate: fract(u)·N − ½ formed in f32, within 2⁻²² (|u| + 1) ≤ 2⁻²¹ turns
//!   for u ∈ [0, 1) (as `effects::flow_detail` bounds its own), times |f'| ≤ 2π.
//!
//! At N = 2048: 1.2·10⁻⁶ + 2.44·10⁻⁴ + 4.88·10⁻⁴ + 2.22·10⁻⁴ + 3·10⁻⁶ = 9.6·10⁻⁴
//! ([`TurnTableError::total`]). WGSL's own `sin` and `cos` are within 2⁻¹¹ = 4.88·10⁻⁴ on
//! [−π, π]. The f16 format alone (the texels' and the filter's rounding, 3·2⁻¹²) is above that
//! for every N: no half-float table can promise WGSL's bound when its filter may work in half
//! floats. What N does decide is the rest: N = 2048 is the smallest power of two whose table,
//! filtered in f32 ([`TurnTableError::f32_filter`]: 4.70·10⁻⁴), is within 2⁻¹¹
//! ([`texels_within`]; N = 1024 gives 6.66·10⁻⁴), and the largest a phone allows. Parity tests
//! hold a GPU to [`TurnTableError::total`]; the CPU mirror ([`turn_sin_cos_f32`], exact
//! weights in f64) is within [`TurnTableError::exact_filter`] (2.45·10⁻⁴).

use std::f64::consts::TAU;
use std::sync::OnceLock;

/// Texels of the table (one row): [`texels_within`] of WGSL's `sin`/`cos` bound.
pub const TURN_TABLE_TEXELS: u32 = 2048;

/// WGSL's `sin` and `cos`: absolute error ≤ 2⁻¹¹ inside [−π, π] (the specification's
/// "Floating Point Accuracy"; `render::wgsl_accuracy::SIN_COS_ABSOLUTE`).
pub const WGSL_SIN_COS_ABSOLUTE: f64 = 1.0 / 2048.0;

/// Vulkan's least `subTexelPrecisionBits`: a filter weight snaps to 1/16 of a texel
/// (`render::wgsl_accuracy::SUB_TEXEL_PRECISION_BITS_MIN`).
pub const SUB_TEXEL_PRECISION_BITS_MIN: u32 = 4;

/// Half the f16 unit in the last place below 1 (2⁻¹¹): the most rounding a value of magnitude
/// at most 1 to the nearest f16 can move it (1.0 itself is exact).
pub const HALF_FLOAT_ROUNDING_BELOW_ONE: f64 = 1.0 / 4096.0;

/// The table of `texels` texels: texel i holds the f16 bits of (sin 2πu_i, cos 2πu_i) at its
/// centre u_i = (i + ½)/N, formed in f64 and rounded once, as `Rg16Float` lays them out.
pub fn turn_table_texels(texels: u32) -> Vec<[u16; 2]> {
    turn_table_texels_at(texels, 0.5)
}

/// [`turn_table_texels`] with texel i holding the value at (i + o)/N: o = ½ is the table; any
/// other offset is a wrongly built one, for the tests that must catch it.
pub fn turn_table_texels_at(texels: u32, o: f64) -> Vec<[u16; 2]> {
    let n = f64::from(texels);
    (0..texels)
        .map(|i| {
            let (s, c) = (TAU * (f64::from(i) + o) / n).sin_cos();
            [
                half::f16::from_f64(s).to_bits(),
                half::f16::from_f64(c).to_bits(),
            ]
        })
        .collect()
}

/// The table at [`TURN_TABLE_TEXELS`], made once per process (what the renderer uploads and
/// the CPU mirror reads).
pub fn turn_table() -> &'static [[u16; 2]] {
    static TABLE: OnceLock<Vec<[u16; 2]>> = OnceLock::new();
    TABLE.get_or_init(|| turn_table_texels(TURN_TABLE_TEXELS))
}

/// The bytes of [`turn_table`] as a `Rg16Float` texture row (little-endian f16 pairs).
pub fn turn_table_bytes() -> Vec<u8> {
    turn_table()
        .iter()
        .flat_map(|t| t.map(u16::to_le_bytes))
        .flatten()
        .collect()
}

/// `table` sampled at turn `u` as a linear filter with repeat addressing samples it, in
/// exact arithmetic (f64, the weights unsnapped): (sin, cos) of 2π·fract(u).
pub fn sample(table: &[[u16; 2]], u: f64) -> [f64; 2] {
    let n = table.len() as i64;
    let texel = |i: i64| table[i.rem_euclid(n) as usize].map(|b| half::f16::from_bits(b).to_f64());
    let x = (u - u.floor()) * n as f64 - 0.5;
    let base = x.floor();
    let w = x - base;
    let (a, b) = (texel(base as i64), texel(base as i64 + 1));
    [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]
}

/// (sin 2πu, cos 2πu) from the table as the shader takes them (`fract(u)`, then one filtered
/// look-up), f32: the exact filter of [`turn_table`] at the f32 fract(u), rounded once. Within
/// [`TurnTableError::exact_filter`] of the f64 sine and cosine of 2π·fract(u).
pub fn turn_sin_cos_f32(u: f32) -> [f32; 2] {
    // fract in f32 as WGSL defines it, x − floor(x) (exact for the u ≥ 0 the kernels form).
    let f = u - u.floor();
    sample(turn_table(), f64::from(f)).map(|v| v as f32)
}

/// The parts of the bound on a sampled table value against the f64 sine or cosine (module
/// docs), absolute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnTableError {
    /// Linear interpolation of the exact values: (2π/N)²/8.
    pub interpolation: f64,
    /// The texels' f16 rounding: 2⁻¹².
    pub texel_rounding: f64,
    /// The filter's arithmetic in half floats (product and sum, ½ ULP each): 2⁻¹¹.
    pub filter_rounding: f64,
    /// The filter's weights snapped to 1/16 of a texel (whole step).
    pub filtering: f64,
    /// The f32 texel coordinate of fract(u).
    pub coordinate: f64,
}

impl TurnTableError {
    /// What a conforming GPU's sample may err by: every part.
    pub fn total(&self) -> f64 {
        self.interpolation
            + self.texel_rounding
            + self.filter_rounding
            + self.filtering
            + self.coordinate
    }

    /// What a GPU whose filter works in f32 may err by (the weights still snapped).
    pub fn f32_filter(&self) -> f64 {
        self.total() - self.filter_rounding + 2f64.powi(-24)
    }

    /// What the CPU mirror's exact filter ([`turn_sin_cos_f32`]) errs by: interpolation and
    /// the texels' rounding, and its result's rounding to f32 (2⁻²⁵ below 1).
    pub fn exact_filter(&self) -> f64 {
        self.interpolation + self.texel_rounding + 2f64.powi(-25)
    }
}

/// The bound for a table of `texels` texels (module docs).
pub fn turn_table_error(texels: u32) -> TurnTableError {
    let n = f64::from(texels);
    let snap = 1.0 / f64::from(1u32 << SUB_TEXEL_PRECISION_BITS_MIN);
    TurnTableError {
        interpolation: (TAU / n).powi(2) / 8.0,
        texel_rounding: HALF_FLOAT_ROUNDING_BELOW_ONE,
        filter_rounding: 2.0 * HALF_FLOAT_ROUNDING_BELOW_ONE,
        filtering: snap * (TAU / n + 2.0 * HALF_FLOAT_ROUNDING_BELOW_ONE),
        coordinate: TAU * 2f64.powi(-21),
    }
}

/// The smallest power-of-two table whose f32-filtered bound ([`TurnTableError::f32_filter`])
/// is within `bound`, up to the 2048 texels phones allow per side (None past that).
pub fn texels_within(bound: f64) -> Option<u32> {
    (4..=11)
        .map(|b| 1u32 << b)
        .find(|&n| turn_table_error(n).f32_filter() <= bound)
}

#[cfg(test)]
mod tests;
