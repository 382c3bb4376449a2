//! How the effects are set up ([`ArConfig`]).

use glam::DVec2;

use crate::EffectSet;

/// How the effects are set up.
#[derive(Debug, Clone, PartialEq)]
pub struct ArConfig {
    /// Effects asked for.
    pub effects: EffectSet,
    /// Depth of the water over the table, metres of the scene (table units × scale).
    pub table_depth: f64,
    /// The water's optics: the real sea's type, depth and turbidity (`render::water_look`);
    /// real metres per scene metre are `water.depth_m / table_depth`.
    pub water: render::water_look::WaterLook,
    /// Radius of the ring the camera image is reflected on; `None`: 1.05 × half the play
    /// area's diagonal (the AR water thesis, 000 in docs/sources.md: at least half the water's diagonal).
    pub ring_radius: Option<f64>,
    /// Reflection texture size as a fraction of the screen's (000 uses a quarter).
    pub reflection_fraction: f64,
    /// Far tidal current, m/s (x, z).
    pub current: DVec2,
    /// Radius of a course mark in the current, metres.
    pub mark_radius: f64,
    /// Flow-map restart period, seconds.
    pub flow_period: f64,
    /// Side of one tile of the flow-distorted detail texture, metres.
    pub detail_tile: f64,
    /// Use the cheap overhead-sun caustics instead of the area-ratio map.
    pub cheap_caustics: bool,
    /// Surface grid and output cells per side of the area-ratio caustic map.
    pub caustic_resolution: (usize, usize),
    /// Test hook, 0 in use: these effects' bits (`1 << Effect as u8`) are left out of the AR
    /// water shader's `FX_MASK` while every pass still runs, so the effect's term is dead (the
    /// golden tests prove they catch that).
    #[doc(hidden)]
    pub shader_knockout: u8,
    /// Test hook, false in use: draw the camera background over the whole screen, as before
    /// it left out the part the water certainly covers (`passes::cover`), so a test can show
    /// that the two frames are the same.
    #[doc(hidden)]
    pub background_whole: bool,
}

impl Default for ArConfig {
    fn default() -> Self {
        ArConfig {
            effects: EffectSet::ALL,
            table_depth: 3.0,
            // The scene at full size: 3 m of pure water (turbidity over metres would veil the
            // table and every effect under it).
            water: render::water_look::WaterLook {
                water_type: render::water_look::WaterType::Pure,
                depth_m: 3.0,
                turbidity_ntu: 0.0,
            },
            ring_radius: None,
            reflection_fraction: 0.25,
            current: DVec2::new(0.6, 0.2),
            mark_radius: 4.0,
            flow_period: 2.0,
            detail_tile: 12.0,
            cheap_caustics: false,
            caustic_resolution: (48, 64),
            shader_knockout: 0,
            background_whole: false,
        }
    }
}

impl ArConfig {
    /// The effects over a table scene in race metres showing the real sea `water`: the table
    /// lies the sea's depth down (optical similarity: on the table the water is depth × scale
    /// deep with the real sea's optics, docs/water-look.md); the rest as [`ArConfig::default`].
    pub fn on_table(water: render::water_look::WaterLook) -> Self {
        ArConfig {
            table_depth: water.depth_m,
            water,
            ..ArConfig::default()
        }
    }

    /// The ring radius for a scene's play area.
    pub fn ring_radius_for(&self, play_area: [f64; 4]) -> f64 {
        let [ax, az, bx, bz] = play_area;
        self.ring_radius
            .unwrap_or_else(|| 1.05 * 0.5 * DVec2::new(bx - ax, bz - az).length())
    }
}
