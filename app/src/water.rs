//! The real sea on the table: `--water-type NAME`, `--water-depth M` and `--turbidity NTU` for
//! `regatta render` and the window, checked into a [`render::water_look::WaterLook`]
//! (docs/water-look.md: optical similarity, the table's water shows the real sea's optics).

use clap::Args;
use render::water_look::{MAX_DEPTH_M, MAX_TURBIDITY_NTU, MIN_DEPTH_M, WaterLook, WaterType};

use crate::error::{AppError, AppResult};

/// The water settings of the command line.
#[derive(Debug, Args, Default, Clone)]
pub struct WaterArgs {
    /// The real sea's water: Jerlov's type `I`, `IA`, `IB`, `II`, `III` (oceanic), `1C`, `3C`,
    /// `5C`, `7C`, `9C` (coastal), or `pure` (pure water, the clear look); default `IB`.
    #[arg(long, value_name = "NAME")]
    pub water_type: Option<String>,
    /// Depth of the real sea, metres (0.5 to 100; default 5): on a table the water is this
    /// times the table's scale deep, with the real sea's optics; with `--effects` at full
    /// size, the optical depth over the scene's table.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub water_depth: Option<f64>,
    /// Turbidity added to the water type's own particles, NTU (0 to 100; default 0).
    #[arg(long, value_name = "NTU", allow_negative_numbers = true)]
    pub turbidity: Option<f64>,
}

/// The names `--water-type` takes, for its error message.
fn type_names() -> String {
    WaterType::ALL.map(WaterType::name).join(", ")
}

impl WaterArgs {
    /// The look asked for over `base` (what the scene uses without the flags); a one-line
    /// error naming the flag when out of range or unknown.
    pub fn look(&self, base: WaterLook) -> AppResult<WaterLook> {
        let water_type = match &self.water_type {
            None => base.water_type,
            Some(name) => WaterType::from_name(name).ok_or_else(|| {
                AppError::new(format!(
                    "--water-type {} is not a water type: {}",
                    input::quote(name),
                    type_names()
                ))
            })?,
        };
        if let Some(d) = self.water_depth
            && !(d.is_finite() && (MIN_DEPTH_M..=MAX_DEPTH_M).contains(&d))
        {
            return Err(AppError::new(format!(
                "--water-depth {} is outside {MIN_DEPTH_M} to {MAX_DEPTH_M} metres (the real sea's depth)",
                input::show_number(d)
            )));
        }
        if let Some(t) = self.turbidity
            && !(t.is_finite() && (0.0..=MAX_TURBIDITY_NTU).contains(&t))
        {
            return Err(AppError::new(format!(
                "--turbidity {} is outside 0 to {MAX_TURBIDITY_NTU} NTU",
                input::show_number(t)
            )));
        }
        Ok(WaterLook {
            water_type,
            depth_m: self.water_depth.unwrap_or(base.depth_m),
            turbidity_ntu: self.turbidity.unwrap_or(base.turbidity_ntu),
        })
    }

    /// Whether any of the flags was given.
    pub fn given(&self) -> bool {
        self.water_type.is_some() || self.water_depth.is_some() || self.turbidity.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_settings_name_their_flag() {
        let a = |w: Option<&str>, d: Option<f64>, t: Option<f64>| WaterArgs {
            water_type: w.map(str::to_string),
            water_depth: d,
            turbidity: t,
        };
        for d in [0.0, -1.0, 0.3, 100.5, f64::NAN, f64::INFINITY] {
            let e = a(None, Some(d), None)
                .look(WaterLook::default())
                .unwrap_err();
            let e = e.to_string();
            assert!(e.starts_with("--water-depth") && !e.contains('\n'), "{e}");
        }
        for t in [-0.1, 100.5, f64::NAN] {
            let e = a(None, None, Some(t))
                .look(WaterLook::default())
                .unwrap_err();
            assert!(e.to_string().starts_with("--turbidity"), "{e}");
        }
        for w in ["IV", "", "coastal\u{1b}[31m"] {
            let e = a(Some(w), None, None)
                .look(WaterLook::default())
                .unwrap_err();
            let e = e.to_string();
            assert!(e.starts_with("--water-type") && e.contains("1C, 3C"), "{e}");
            assert!(!e.contains('\u{1b}'), "{e}");
        }
        let ok = a(Some("ii"), Some(40.0), Some(3.0))
            .look(WaterLook::default())
            .unwrap();
        assert_eq!(
            (ok.water_type, ok.depth_m, ok.turbidity_ntu),
            (WaterType::OceanicII, 40.0, 3.0)
        );
        assert_eq!(
            a(None, None, None).look(WaterLook::default()).unwrap(),
            WaterLook::default()
        );
        // What the flags allow is what the renderer's own check allows.
        assert!(ok.check().is_ok());
    }
}
