//! Race → wakes: the boats' cleaned fixes as the plain samples `ocean::wake` takes (ocean
//! knows nothing of the race crate). Used by `regatta probe` and the renderer's wiring.
//!
//! The wake sees each boat's fixes joined by straight lines (the race crate draws them with a
//! shape-preserving cubic; between 1 Hz fixes the two differ by centimetres, far below a
//! wake source's spacing). Every boat gets the default wake boat (`WakeParams::default()`:
//! a 6 m, 1 t keelboat's pressure patch), since race files carry no hull data.

use std::sync::Arc;

use ocean::wake::{TableModel, TrackSample, Wake, WakeParams};

use crate::error::{AppError, AppResult};

/// Each boat's fixes as wake samples, in race order.
pub fn race_tracks(race: &race::Race) -> Vec<Vec<TrackSample>> {
    race.boats
        .iter()
        .map(|b| {
            b.fixes()
                .iter()
                .map(|f| TrackSample {
                    t: f.t,
                    x: f.x,
                    z: f.z,
                })
                .collect()
        })
        .collect()
}

/// The Kelvin wakes of a race's boats.
pub fn race_wake(race: &race::Race, params: WakeParams) -> AppResult<Wake> {
    let tracks = race_tracks(race);
    let refs: Vec<&[TrackSample]> = tracks.iter().map(Vec::as_slice).collect();
    Wake::new(&refs, params).map_err(|e| {
        // Name the boat by its id rather than its index.
        let msg = match &e {
            ocean::wake::WakeError::Track { boat, .. } => race
                .boats
                .get(*boat)
                .map(|b| format!("boat {}: {e}", b.id))
                .unwrap_or_else(|| e.to_string()),
            _ => e.to_string(),
        };
        AppError::new(msg)
    })
}

/// The wake the table scene draws: `wake` (the boats' own, full size) Froude-scaled for boats
/// drawn `drawn_length` race metres long, with `world_per_table` race metres per table metre
/// (docs/wakes.md, "Wakes at table scale"). The boat's own wake when the drawn hull is no
/// longer than the wake boat's waterline (nothing to scale up), or when scaling fails.
pub fn table_wake(wake: &Arc<Wake>, drawn_length: f64, world_per_table: f64) -> Arc<Wake> {
    let model = TableModel {
        boat_length: wake.params.waterline_length(),
        model_length: drawn_length / world_per_table,
        world_per_table,
    };
    let s = model.world_scale();
    if s.is_nan() || s <= 1.0 {
        return wake.clone();
    }
    match wake.froude_scaled(s) {
        Ok(w) => {
            log::info!(
                "table wakes: Froude-scaled ×{s:.1} (a {:.3} m model, λ = {:.5})",
                model.model_length,
                model.length_ratio()
            );
            Arc::new(w)
        }
        Err(e) => {
            log::warn!("{e}; drawing the boats' own wakes");
            wake.clone()
        }
    }
}
