//! `regatta run --scene pool`: the pool under the orbiting camera. A left press on the green
//! (or any moving) ball grabs it and the ball follows the pointer over the water, leaving
//! ripples; elsewhere a left drag orbits as in the race.

use pool::{PoolFrame, PoolRenderer, PoolSettings, PoolView};
use render::OrbitCamera;

use crate::pool_play::PoolPlay;

pub struct PoolMode {
    /// The scene and the grab and drag the phone's finger uses too.
    play: PoolPlay,
    renderer: Option<PoolRenderer>,
    /// When the app exits by itself (`REGATTA_EXIT_AFTER_FRAMES`, for the smoke test).
    exit_after: super::smoke::ExitAfter,
}

impl PoolMode {
    /// The default pool, its waves replaced by `sea` when one was given.
    pub fn new(sea: Option<ocean::WaveSet>) -> PoolMode {
        PoolMode {
            play: PoolPlay::new(sea),
            renderer: None,
            exit_after: super::smoke::ExitAfter::from_env(),
        }
    }

    /// The starting camera: above the pool's south-east corner.
    pub fn orbit() -> OrbitCamera {
        PoolPlay::orbit()
    }

    /// Draws a frame; `Ok(true)` when the app should exit (`REGATTA_EXIT_AFTER_FRAMES`, after
    /// writing `REGATTA_SCREENSHOT`), `Err` when the screenshot could not be written.
    pub(super) fn draw(
        &mut self,
        gpu: &render::Gpu,
        target: &mut crate::core::gfx::Window,
        window: &winit::window::Window,
        t: f64,
        orbit: &OrbitCamera,
    ) -> Result<bool, String> {
        let frame_tex = match target.acquire(gpu) {
            crate::core::gfx::Acquired::Frame(f) => f,
            _ => return Ok(false),
        };
        let size = target.size();
        let view = frame_tex.texture().create_view(&Default::default());
        let format = target.format().unwrap_or(render::OFFSCREEN_FORMAT);
        let frame = self.render(gpu, format, &view, size, t, orbit);
        window.pre_present_notify();
        target.present(gpu, frame_tex);
        window.set_title(&format!("Regatta: the pool at t = {t:.1} s"));
        let exit = self.exit_after.frame_done();
        if exit
            && let Some(path) = super::smoke::screenshot_path()
            && let Some(renderer) = self.renderer.as_mut()
        {
            let (img, _) = gpu
                .render_offscreen(size, format, |v| renderer.render(gpu, v, &frame))
                .map_err(|e| format!("{}: {e}", input::show_path(&path)))?;
            super::smoke::write_screenshot(img, format, &path)?;
        }
        Ok(exit)
    }

    /// The window's per-frame work: the frame at `t` under `orbit` drawn into `target` by the
    /// mode's renderer (made on the first frame), the view kept for the pointer.
    pub fn render(
        &mut self,
        gpu: &render::Gpu,
        format: wgpu::TextureFormat,
        target: &wgpu::TextureView,
        size: [u32; 2],
        t: f64,
        orbit: &OrbitCamera,
    ) -> PoolFrame {
        let settings = PoolSettings::default();
        let renderer = self
            .renderer
            .get_or_insert_with(|| PoolRenderer::new(gpu, format, settings));
        let view = PoolView {
            camera: orbit.camera(),
            ..PoolView::default_desktop(size)
        };
        let frame = PoolFrame::new(&self.play.scene, t, &view, &settings);
        renderer.render(gpu, target, &frame);
        self.play.view = Some(view);
        frame
    }

    /// A left press or release at `cursor`; true when the press grabbed a ball.
    pub fn press(&mut self, pressed: bool, cursor: (f64, f64), t: f64) -> bool {
        self.play.press(pressed, [cursor.0, cursor.1], t)
    }

    pub fn pointer_moved(&mut self, cursor: (f64, f64), t: f64) {
        self.play.pointer_moved([cursor.0, cursor.1], t);
    }
}
