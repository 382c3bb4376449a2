//! Race → wakes: the boats' cleaned fixes as the plain samples `ocean::wake` takes (ocean
//! knows nothing of the race crate). Used by `regatta probe` and the renderer's wiring.
//!
//! The wake sees each boat's fixes joined by straight lines (the race crate draws them with a
//! shape-preserving cubic; between 1 Hz fixes the two differ by centimetres, far below a
//! wake source's spacing). Every boat gets the default wake boat (`WakeParams::default()`:
//! a 6 m, 1 t keelboat's pressure patch), since race files carry no hull data.

use ocean::wake::{TrackSample, Wake, WakeParams};

use crate::error::{CliError, CliResult};

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
pub fn race_wake(race: &race::Race, params: WakeParams) -> CliResult<Wake> {
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
        CliError::new(msg)
    })
}
