//! Moving a sphere with the mouse or a finger: the pointer's pixel becomes a ray from the eye
//! in pool space; a press whose ray hits a moving sphere grabs it; while the pointer moves,
//! the sphere follows the point where the ray meets the water's rest plane, floating at the
//! height of the waves there (`ocean`'s inverse, `WaveSet::height_at`). The drag is recorded
//! in the sphere's path, so its ripples stay a closed-form function of time.

use glam::{DVec2, DVec4};

use super::geometry::Ray;
use super::gpu::PoolView;
use super::scene::PoolScene;

/// The ray from the eye through pixel `px` (pixels from the top-left corner) in pool space.
pub fn pointer_ray(view: &PoolView, px: [f64; 2]) -> Ray {
    let [w, h] = view.size.map(|s| f64::from(s.max(1)));
    let aspect = w / h;
    let vp = view.camera.view_proj_local(DVec2::ZERO, aspect) * view.model;
    let inv = vp.inverse();
    let ndc = [2.0 * px[0] / w - 1.0, 1.0 - 2.0 * px[1] / h];
    let unproject = |z: f64| {
        let p = inv * DVec4::new(ndc[0], ndc[1], z, 1.0);
        p.truncate() / p.w
    };
    let near = unproject(0.0);
    Ray::new(near, unproject(1.0) - near)
}

impl PoolScene {
    /// The moving sphere that `ray` hits first at time `t`, if any (an index into `movers`).
    pub fn grab(&self, t: f64, ray: &Ray) -> Option<usize> {
        self.movers
            .iter()
            .enumerate()
            .filter_map(|(i, m)| {
                let s = super::geometry::Sphere {
                    center: m.path.position(t),
                    radius: m.radius,
                };
                s.hit(ray).map(|d| (d, i))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, i)| i)
    }

    /// Move mover `index` under `ray` at time `t`: to where the ray meets the rest plane,
    /// kept a radius inside the walls, its centre at the height of the waves there.
    pub fn drag(&mut self, index: usize, t: f64, ray: &Ray) {
        let Some(radius) = self.movers.get(index).map(|m| m.radius) else {
            return;
        };
        let Some(at) = self.drag_point(ray, radius) else {
            return;
        };
        let y = self.water.waves.height_at(at, t).unwrap_or_else(|e| {
            log::warn!("the dragged sphere floats at the rest level: {e}");
            0.0
        });
        self.movers[index].drag_to(t, at, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn pointer_ray_passes_through_the_point_its_pixel_shows() {
        let view = PoolView::default_desktop([200, 100]);
        let p = DVec3::new(0.3, -0.2, 0.4);
        let clip = view.camera.view_proj_local(DVec2::ZERO, 2.0) * p.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        let px = [(ndc.x + 1.0) * 100.0, (1.0 - ndc.y) * 50.0];
        let ray = pointer_ray(&view, px);
        // Distance from p to the ray's line.
        let v = p - ray.origin;
        let off = (v - ray.dir * v.dot(ray.dir)).length();
        assert!(off < 1e-9, "{off}");
    }

    #[test]
    fn pressing_on_a_sphere_grabs_it_and_dragging_moves_it_under_the_pointer() {
        let mut scene = PoolScene::default();
        let t = 2.0;
        let c = scene.movers[1].path.position(t);
        let eye = DVec3::new(0.2, 2.0, 1.5);
        let ray = Ray::new(eye, c - eye);
        assert_eq!(scene.grab(t, &ray), Some(1));
        assert_eq!(scene.grab(t, &Ray::new(eye, DVec3::Y)), None);
        // Drag to the point below (−0.4, 0, 0.2).
        let to = DVec3::new(-0.4, 0.0, 0.2);
        scene.drag(1, t + 0.5, &Ray::new(eye, to - eye));
        let p = scene.movers[1].path.position(t + 0.6);
        assert!((p.x + 0.4).abs() < 1e-9 && (p.z - 0.2).abs() < 1e-9);
        // It floats at the waves' height there.
        let h = scene.water.waves.height_at([-0.4, 0.2], t + 0.5).unwrap();
        assert!((p.y - h).abs() < 1e-12);
    }
}
