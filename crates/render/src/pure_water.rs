//! Pure water's absorption (Pope & Fry 1997) and the RGB bands every water calculation
//! averages over: what both the clear-water look (`water_look`) and the Jerlov water types
//! (`water_types`) build on, in a module of its own so neither imports the other's data.

/// Pure-water absorption coefficient, 1/m, every 10 nm from 380 to 700 nm: Pope & Fry
/// (1997), "Absorption spectrum (380–700 nm) of pure water. II. Integrating cavity
/// measurements", Applied Optics 36(33), 8710–8723, Table 3 (at 10 nm, rounded).
pub const POPE_FRY_1997: [(f64, f64); 33] = [
    (380.0, 0.01137),
    (390.0, 0.00851),
    (400.0, 0.00663),
    (410.0, 0.00473),
    (420.0, 0.00454),
    (430.0, 0.00495),
    (440.0, 0.00635),
    (450.0, 0.00922),
    (460.0, 0.00979),
    (470.0, 0.01060),
    (480.0, 0.01270),
    (490.0, 0.01500),
    (500.0, 0.02040),
    (510.0, 0.03250),
    (520.0, 0.04090),
    (530.0, 0.04340),
    (540.0, 0.04740),
    (550.0, 0.05650),
    (560.0, 0.06190),
    (570.0, 0.06950),
    (580.0, 0.08960),
    (590.0, 0.13510),
    (600.0, 0.22240),
    (610.0, 0.26440),
    (620.0, 0.27550),
    (630.0, 0.29160),
    (640.0, 0.31080),
    (650.0, 0.34000),
    (660.0, 0.41000),
    (670.0, 0.43900),
    (680.0, 0.46500),
    (690.0, 0.51600),
    (700.0, 0.62400),
];

/// The RGB bands, nm (box bands: a camera's channels, approximately).
pub const BANDS_NM: [(f64, f64); 3] = [(600.0, 700.0), (500.0, 600.0), (400.0, 500.0)];

/// Mean of [`POPE_FRY_1997`] over `[lo, hi]` nm (trapezoids on its 10 nm grid; `lo`, `hi` on
/// the grid).
pub fn band_mean_absorption(lo: f64, hi: f64) -> f64 {
    let inside: Vec<(f64, f64)> = POPE_FRY_1997
        .iter()
        .copied()
        .filter(|(l, _)| *l >= lo && *l <= hi)
        .collect();
    let area: f64 = inside
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum();
    area / (hi - lo)
}

/// Pure-water absorption per RGB band, 1/m (R ≈ 0.374, G ≈ 0.070, B ≈ 0.0092).
pub fn pure_water_absorption() -> [f64; 3] {
    BANDS_NM.map(|(lo, hi)| band_mean_absorption(lo, hi))
}
