//! One picture of the race on a feed's table, headless, as the window draws it for that feed
//! frame: `regatta render --replay` and the tests that look at the table.

use crate::error::{AppError, AppResult};

/// One picture of the table scene, as `run` draws it: `race` at race time `t` over feed frame
/// `frame`, `size` pixels.
pub struct TableFrame<'a> {
    pub world: &'a crate::world::RaceWorld,
    pub t: f64,
    pub size: [u32; 2],
    pub frame: usize,
    /// The scene overlays drawn over it (labels through egui), or none.
    pub overlays: Option<&'a crate::scene_overlay::OverlaySettings>,
}

impl TableFrame<'_> {
    /// Draws it through `feed` with `renderer` (built anew by `setup` on the feed's first
    /// frame) and `wake` (the boats' own: the feed scales it for the table); `edit` changes the
    /// scene last (tests leave boats out).
    pub fn draw(
        &self,
        feed: &mut super::FeedView,
        gpu: &render::Gpu,
        renderer: &mut render::Renderer,
        setup: &crate::setup::RaceSetup,
        wake: Option<std::sync::Arc<ocean::wake::Wake>>,
        edit: impl FnOnce(&mut render::Scene),
    ) -> AppResult<(image::RgbaImage, render::FrameReport)> {
        let mut orbit = crate::world::race_orbit();
        let mut scene = self.world.orbit_scene(self.t, &mut orbit);
        feed.prepare_frame(
            gpu,
            renderer,
            render::OFFSCREEN_FORMAT,
            setup,
            wake,
            self.world.race_bounds,
            self.size,
            self.frame,
        )?;
        feed.apply(&mut scene);
        edit(&mut scene);
        match self.overlays {
            Some(overlays) => crate::scene_overlay::render_headless(
                gpu,
                renderer,
                (
                    &self.world.race,
                    crate::scene_overlay::manoeuvres::debrief_if_shown(&self.world.race, overlays)
                        .as_ref(),
                ),
                &scene,
                self.size,
                overlays,
            ),
            None => render::render_image(gpu, renderer, &scene, self.size),
        }
        .map_err(|e| AppError::new(format!("cannot render: {e}")))
    }
}
