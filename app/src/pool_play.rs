//! The pool scene's play, shared by the desktop's mouse and the phone's finger: a press whose
//! ray (`pool::pointer_ray` through the pixel, in the view of the last frame drawn)
//! hits a moving sphere grabs it, and the sphere follows the pointer over the water
//! (`PoolScene::grab`, `PoolScene::drag`), leaving ripples.

use glam::DVec3;
use pool::{PoolFrame, PoolRenderer, PoolScene, PoolSettings, PoolView, pointer_ray};
use render::OrbitCamera;

/// The pool, the view its last frame was drawn with, and the sphere being dragged.
pub struct PoolPlay {
    pub scene: PoolScene,
    /// Pointer rays are cast through the view of the last frame drawn.
    pub view: Option<PoolView>,
    grabbed: Option<usize>,
}

impl PoolPlay {
    /// The default pool, its waves replaced by `sea` when one was given.
    pub fn new(sea: Option<ocean::WaveSet>) -> PoolPlay {
        let mut scene = PoolScene::default();
        if let Some(s) = sea {
            scene.water.waves = s;
        }
        PoolPlay {
            scene,
            view: None,
            grabbed: None,
        }
    }

    /// The starting 3D camera: above the pool's south-east corner.
    pub fn orbit() -> OrbitCamera {
        OrbitCamera {
            target: DVec3::new(0.0, -0.3, 0.0),
            distance: 3.4,
            yaw: 2.7,
            pitch: 0.75,
            far: pool::FAR_M,
        }
    }

    /// A press (or release) at pixel `px` (from the top-left corner of the view) at time `t`;
    /// true when the press grabbed a sphere.
    pub fn press(&mut self, pressed: bool, px: [f64; 2], t: f64) -> bool {
        self.grabbed = None;
        if !pressed {
            return false;
        }
        let Some(view) = &self.view else {
            return false;
        };
        self.grabbed = self.scene.grab(t, &pointer_ray(view, px));
        self.grabbed.is_some()
    }

    /// The pointer moved to pixel `px`: a grabbed sphere follows it.
    pub fn pointer_moved(&mut self, px: [f64; 2], t: f64) {
        if let (Some(i), Some(view)) = (self.grabbed, &self.view) {
            let ray = pointer_ray(view, px);
            self.scene.drag(i, t, &ray);
        }
    }

    /// The sphere being dragged, if any (an index into `scene.movers`).
    pub fn grabbed(&self) -> Option<usize> {
        self.grabbed
    }

    /// One frame of the pool at time `t` (seconds) seen through `view`, drawn into `target`
    /// by `renderer` (made for `format` on the first frame); the view kept for the pointer.
    /// The app's pool frame on both profiles (the phone's before it is placed, and the
    /// desktop's), and the play-versus-scrub test's.
    #[allow(clippy::too_many_arguments)]
    pub fn render(
        &mut self,
        renderer: &mut Option<PoolRenderer>,
        gpu: &render::Gpu,
        format: wgpu::TextureFormat,
        target: &wgpu::TextureView,
        view: PoolView,
        t: f64,
    ) -> PoolFrame {
        let settings = PoolSettings::default();
        let frame = PoolFrame::new(&self.scene, t, &view, &settings);
        renderer
            .get_or_insert_with(|| PoolRenderer::new(gpu, format, settings))
            .render(gpu, target, &frame);
        self.view = Some(view);
        frame
    }

    /// The view of the 3D pool under `orbit` in a window of `size` pixels.
    pub fn orbit_view(orbit: &OrbitCamera, size: [u32; 2]) -> PoolView {
        PoolView {
            camera: orbit.camera(),
            ..PoolView::default_desktop(size)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DMat4, DQuat, DVec2};
    use render::Camera;

    /// A phone 40 cm above a table, looking down at 50° and rolled 20°, the pool stood on the
    /// table at 1:6 and turned 0.4 rad, as the Android app builds its view: the pixel where
    /// each moving sphere's centre is drawn (the frame's own view-projection · model) grabs
    /// that sphere; a pixel in an empty corner grabs none; a drag puts the sphere under the
    /// point where the finger's ray meets the water's rest plane.
    #[test]
    fn a_finger_on_the_drawn_sphere_grabs_it_on_a_rolled_phone() {
        let size = [1080u32, 2340];
        let rot = DQuat::from_rotation_y(0.3)
            * DQuat::from_rotation_x(-50f64.to_radians())
            * DQuat::from_rotation_z(20f64.to_radians());
        let pose = DMat4::from_rotation_translation(rot, DVec3::new(0.05, 0.4, 0.35));
        let aspect = f64::from(size[0]) / f64::from(size[1]);
        let proj = glam::dcamera::rh::proj::opengl::perspective(1.2, aspect, 0.01, 100.0);
        let mut play = PoolPlay::new(None);
        let table = DMat4::from_scale_rotation_translation(
            DVec3::splat(1.0 / 6.0),
            DQuat::from_rotation_y(0.4),
            DVec3::new(0.02, -0.01, -0.05),
        );
        let view = PoolView {
            camera: Camera::from_view_projection(pose.inverse(), proj),
            model: PoolView::standing_on(table, &play.scene, &PoolSettings::default()),
            size,
            over_camera_image: true,
        };
        play.view = Some(view);
        let t = 1.5;
        let vp = view.camera.view_proj_local(DVec2::ZERO, aspect) * view.model;
        let pixel_of = |p: DVec3| {
            let c = vp * p.extend(1.0);
            let ndc = c.truncate() / c.w;
            [
                (ndc.x + 1.0) * 0.5 * f64::from(size[0]),
                (1.0 - ndc.y) * 0.5 * f64::from(size[1]),
            ]
        };
        for i in 0..play.scene.movers.len() {
            let px = pixel_of(play.scene.movers[i].path.position(t));
            assert!(
                px[0] > 0.0 && px[0] < 1080.0 && px[1] > 0.0 && px[1] < 2340.0,
                "{px:?}"
            );
            assert!(play.press(true, px, t), "sphere {i} at {px:?}");
            assert_eq!(play.grabbed(), Some(i));
            assert!(!play.press(false, px, t));
        }
        assert!(!play.press(true, [2.0, 2.0], t));
        // Drag mover 0 to the pixel showing the rest-plane point (−0.3, 0, 0.2).
        let to = DVec3::new(-0.3, 0.0, 0.2);
        assert!(play.press(true, pixel_of(play.scene.movers[0].path.position(t)), t));
        play.pointer_moved(pixel_of(to), t + 0.2);
        let p = play.scene.movers[0].path.position(t + 0.3);
        assert!(
            (p.x - to.x).abs() < 1e-6 && (p.z - to.z).abs() < 1e-6,
            "{p}"
        );
    }
}
