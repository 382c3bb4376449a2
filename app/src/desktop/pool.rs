//! `regatta run --scene pool`: the pool under the orbiting camera. A left press on the green
//! (or any moving) ball grabs it and the ball follows the pointer over the water, leaving
//! ripples; elsewhere a left drag orbits as in the race.

use glam::DVec3;
use render::OrbitCamera;
use render::pool::{PoolFrame, PoolRenderer, PoolScene, PoolSettings, PoolView, pointer_ray};

use super::State;

pub struct PoolMode {
    scene: PoolScene,
    renderer: Option<PoolRenderer>,
    /// The view of the last frame: pointer rays are cast through it.
    view: Option<PoolView>,
    /// The moving ball being dragged.
    grabbed: Option<usize>,
}

impl PoolMode {
    /// The default pool, its waves replaced by `sea` when one was given.
    pub fn new(sea: Option<ocean::WaveSet>) -> PoolMode {
        let mut scene = PoolScene::default();
        if let Some(s) = sea {
            scene.water.waves = s;
        }
        PoolMode {
            scene,
            renderer: None,
            view: None,
            grabbed: None,
        }
    }

    /// The starting camera: above the pool's south-east corner.
    pub fn orbit() -> OrbitCamera {
        OrbitCamera {
            target: DVec3::new(0.0, -0.3, 0.0),
            distance: 3.4,
            yaw: 2.7,
            pitch: 0.75,
            far: render::pool::FAR_M,
        }
    }

    pub fn draw(&mut self, st: &State, t: f64, orbit: &OrbitCamera) {
        let frame_tex = match st.surface.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            _ => return,
        };
        let size = [st.surface.config.width, st.surface.config.height];
        let settings = PoolSettings::default();
        let renderer = self
            .renderer
            .get_or_insert_with(|| PoolRenderer::new(&st.gpu, st.surface.config.format, settings));
        let view = PoolView {
            camera: orbit.camera(),
            ..PoolView::default_desktop(size)
        };
        let frame = PoolFrame::new(&self.scene, t, &view, &settings);
        let target = frame_tex.texture.create_view(&Default::default());
        renderer.render(&st.gpu, &target, &frame);
        self.view = Some(view);
        st.window.pre_present_notify();
        st.gpu.queue.present(frame_tex);
        st.window
            .set_title(&format!("Regatta: the pool at t = {t:.1} s"));
    }

    /// A left press or release at `cursor`; true when the press grabbed a ball.
    pub fn press(&mut self, pressed: bool, cursor: (f64, f64), t: f64) -> bool {
        self.grabbed = None;
        if !pressed {
            return false;
        }
        let Some(view) = &self.view else {
            return false;
        };
        self.grabbed = self.scene.grab(t, &pointer_ray(view, [cursor.0, cursor.1]));
        self.grabbed.is_some()
    }

    pub fn pointer_moved(&mut self, cursor: (f64, f64), t: f64) {
        if let (Some(i), Some(view)) = (self.grabbed, &self.view) {
            let ray = pointer_ray(view, [cursor.0, cursor.1]);
            self.scene.drag(i, t, &ray);
        }
    }
}
