//! `regatta run --scene pool`: the pool under the orbiting camera. A left press on the green
//! (or any moving) ball grabs it and the ball follows the pointer over the water, leaving
//! ripples; elsewhere a left drag orbits as in the race.

use render::OrbitCamera;
use render::pool::{PoolFrame, PoolRenderer, PoolSettings, PoolView};

use super::State;
use crate::pool_play::PoolPlay;

pub struct PoolMode {
    /// The scene and the grab and drag the phone's finger uses too.
    play: PoolPlay,
    renderer: Option<PoolRenderer>,
}

impl PoolMode {
    /// The default pool, its waves replaced by `sea` when one was given.
    pub fn new(sea: Option<ocean::WaveSet>) -> PoolMode {
        PoolMode {
            play: PoolPlay::new(sea),
            renderer: None,
        }
    }

    /// The starting camera: above the pool's south-east corner.
    pub fn orbit() -> OrbitCamera {
        PoolPlay::orbit()
    }

    pub(super) fn draw(&mut self, st: &State, t: f64, orbit: &OrbitCamera) {
        let frame_tex = match st.surface.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            _ => return,
        };
        let size = [st.surface.config.width, st.surface.config.height];
        let target = frame_tex.texture.create_view(&Default::default());
        self.render(&st.gpu, st.surface.config.format, &target, size, t, orbit);
        st.window.pre_present_notify();
        st.gpu.queue.present(frame_tex);
        st.window
            .set_title(&format!("Regatta: the pool at t = {t:.1} s"));
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
