//! The water's look on the table: `--water-depth M` and `--turbidity NTU` for `regatta render`
//! and the window, checked into a [`render::water_look::WaterLook`] (docs/water-look.md).

use clap::Args;
use render::water_look::{MAX_DEPTH_M, MAX_TURBIDITY_NTU, MIN_DEPTH_M, WaterLook};

use crate::error::{CliError, CliResult};

/// The water settings of the command line.
#[derive(Debug, Args, Default, Clone, Copy)]
pub struct WaterArgs {
    /// Depth of the water over the table, real metres (0.0001 to 0.1; default 0.01 on a
    /// table; with `--effects` at full size, the optical depth over the scene's table).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub water_depth: Option<f64>,
    /// Turbidity of the water, NTU (0 pure water to 100 muddy; default 0.5, tap water).
    #[arg(long, value_name = "NTU", allow_negative_numbers = true)]
    pub turbidity: Option<f64>,
}

impl WaterArgs {
    /// The look asked for over `base` (what the scene uses without the flags); a one-line
    /// error naming the flag when out of range.
    pub fn look(&self, base: WaterLook) -> CliResult<WaterLook> {
        if let Some(d) = self.water_depth
            && !(d.is_finite() && (MIN_DEPTH_M..=MAX_DEPTH_M).contains(&d))
        {
            return Err(CliError::new(format!(
                "--water-depth {} is outside {MIN_DEPTH_M} to {MAX_DEPTH_M} metres",
                input::show_number(d)
            )));
        }
        if let Some(t) = self.turbidity
            && !(t.is_finite() && (0.0..=MAX_TURBIDITY_NTU).contains(&t))
        {
            return Err(CliError::new(format!(
                "--turbidity {} is outside 0 to {MAX_TURBIDITY_NTU} NTU",
                input::show_number(t)
            )));
        }
        Ok(WaterLook {
            depth_m: self.water_depth.unwrap_or(base.depth_m),
            turbidity_ntu: self.turbidity.unwrap_or(base.turbidity_ntu),
        })
    }

    /// Whether either flag was given.
    pub fn given(&self) -> bool {
        self.water_depth.is_some() || self.turbidity.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_settings_name_their_flag() {
        let a = |d: Option<f64>, t: Option<f64>| WaterArgs {
            water_depth: d,
            turbidity: t,
        };
        for d in [0.0, -1.0, 0.3, f64::NAN, f64::INFINITY] {
            let e = a(Some(d), None).look(WaterLook::default()).unwrap_err();
            let e = e.to_string();
            assert!(e.starts_with("--water-depth") && !e.contains('\n'), "{e}");
        }
        for t in [-0.1, 100.5, f64::NAN] {
            let e = a(None, Some(t)).look(WaterLook::default()).unwrap_err();
            assert!(e.to_string().starts_with("--turbidity"), "{e}");
        }
        let ok = a(Some(0.08), Some(3.0)).look(WaterLook::default()).unwrap();
        assert_eq!((ok.depth_m, ok.turbidity_ntu), (0.08, 3.0));
        assert_eq!(
            a(None, None).look(WaterLook::default()).unwrap(),
            WaterLook::default()
        );
        // What the flags allow is what the renderer's own check allows.
        assert!(ok.check().is_ok());
    }
}
