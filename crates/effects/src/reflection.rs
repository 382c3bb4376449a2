//! What the water mirrors of the real room (f64 reference of `ring_hit` and
//! `reflection_colour` in `shaders/reflection.wgsl`).
//!
//! The AR water thesis (TU Delft 2022, report 000 in docs/sources.md) places the camera image on a plane that moves on a circle around the water,
//! turned with the camera's yaw; its reflection then shows "parts that are below the water"
//! when looking steeply down, and reflections sit "right below" the objects. Here the room is
//! taken to stand on a vertical ring of radius R around the water (the whole circle, not one
//! plane): the reflected ray from the surface meets the ring at a point above the water, and
//! that point is projected through the camera's pose and intrinsics into the camera image, so
//! the ring turns with the camera by construction and a reflection appears where a mirror would
//! put it. A ring point the camera does not see (looking steeply down, it lies above the top of
//! the image) is not sampled at all (the sky is reflected instead), so the table below the
//! water never appears in the reflection.

use glam::{DVec2, DVec3};

use super::refraction::edge_weight;
use render::optics::PinholeCamera;

pub mod grid;
pub use grid::{ROOM_CELL_TEXELS, room_cell_texels, room_grid, room_grid_vertices};

/// The vertical ring the room's image stands on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ring {
    /// Centre (x, z), metres.
    pub centre: DVec2,
    /// Radius, metres; at least half the water's diagonal.
    pub radius: f64,
}

impl Ring {
    /// Where the upward ray `p + s·r` (s > 0, r.y > 0) leaves the ring, from a point inside it;
    /// `None` for rays going down or level (they meet the water or the table, not the room) or
    /// from outside the ring.
    pub fn hit(&self, p: DVec3, r: DVec3) -> Option<DVec3> {
        let o = DVec2::new(p.x, p.z) - self.centre;
        let d = DVec2::new(r.x, r.z);
        let a = d.length_squared();
        if a < 1e-16 || r.y <= 0.0 {
            return None;
        }
        let b = o.dot(d);
        let k = b * b - a * (o.length_squared() - self.radius * self.radius);
        if k < 0.0 {
            return None;
        }
        let s = (-b + k.sqrt()) / a;
        (s > 0.0).then(|| p + r * s)
    }
}

/// The camera-image sample the water at `p` mirrors along the reflected direction `r`: its UV
/// and weight (1 inside the image, fading to 0 just outside; the sky gets 1 − weight).
pub fn room_sample(
    ring: &Ring,
    camera: &PinholeCamera,
    p: DVec3,
    r: DVec3,
) -> Option<(DVec2, f64)> {
    let q = ring.hit(p, r)?;
    let uv = camera.project_uv(q)?;
    let w = edge_weight(uv);
    (w > 0.0).then_some((uv, w))
}

#[cfg(test)]
mod tests {
    use super::*;
    use render::optics::{Plane, reflect};

    fn camera(eye: DVec3, target: DVec3) -> PinholeCamera {
        crate::test_camera(eye, target, 300.0)
    }

    const RING: Ring = Ring {
        centre: DVec2::ZERO,
        radius: 10.0,
    };

    #[test]
    fn ring_hits_lie_on_the_ring_above_the_water() {
        for (p, r) in [
            (DVec3::new(1.0, 0.0, 2.0), DVec3::new(0.3, 0.4, -0.8)),
            (DVec3::new(-4.0, 0.1, 0.0), DVec3::new(-1.0, 0.05, 0.2)),
        ] {
            let q = RING.hit(p, r.normalize()).unwrap();
            assert!((DVec2::new(q.x, q.z).length() - 10.0).abs() < 1e-9);
            assert!(q.y > p.y, "above the surface point");
            assert!(
                (q - p).normalize().dot(r.normalize()) > 1.0 - 1e-12,
                "along the ray"
            );
        }
        assert!(
            RING.hit(DVec3::ZERO, DVec3::new(0.5, -0.1, 0.0)).is_none(),
            "downwards"
        );
        assert!(
            RING.hit(DVec3::ZERO, DVec3::Y).is_none(),
            "straight up never meets it"
        );
        assert!(
            RING.hit(DVec3::new(20.0, 0.0, 0.0), DVec3::new(1.0, 0.2, 0.0))
                .is_none()
        );
    }

    #[test]
    fn looking_steeply_down_reflects_no_part_of_the_table() {
        // 000's limitation: looking down, the reflected background showed what lies below the
        // water. Here every water pixel either samples a room point above the water that the
        // camera sees, or nothing (the sky).
        let eye = DVec3::new(0.0, 6.0, 1.5);
        let cam = camera(eye, DVec3::ZERO);
        let water = Plane::horizontal(0.0);
        let mut sampled = 0;
        for i in 0..40 {
            for j in 0..30 {
                let px = DVec2::new(8.0 + i as f64 * 16.0, 8.0 + j as f64 * 16.0);
                let Some((_, p)) = water.intersect_ray(eye, cam.pixel_ray(px)) else {
                    continue;
                };
                let r = reflect((p - eye).normalize(), DVec3::Y);
                if let Some((uv, w)) = room_sample(&RING, &cam, p, r) {
                    sampled += 1;
                    assert!(w > 0.0 && uv.x > -0.05 && uv.y > -0.05);
                    // The camera ray through that image point meets the table plane (if at
                    // all) outside the ring: what the camera sees there is room, not table.
                    let ray = cam.pixel_ray(uv * DVec2::new(640.0, 480.0));
                    if let Some((_, t)) = Plane::horizontal(-0.05).intersect_ray(eye, ray) {
                        assert!(DVec2::new(t.x, t.z).length() > RING.radius, "{uv}");
                    }
                }
            }
        }
        // Only the image's top rows reach the ring; most of the water mirrors the sky.
        assert!(sampled < 40 * 30 / 10, "{sampled}");
    }

    #[test]
    fn a_level_view_reflects_the_room_farther_away_than_the_water() {
        // Looking across the water, the room's reflection comes from a point that the camera
        // sees above the far side of the water: its image row lies above the water pixel's
        // (v smaller), as a real mirror shows the far wall, not what stands right below it.
        let eye = DVec3::new(0.0, 1.5, 8.0);
        let cam = camera(eye, DVec3::new(0.0, 0.0, -2.0));
        let water = Plane::horizontal(0.0);
        let px = DVec2::new(320.0, 300.0);
        let (_, p) = water.intersect_ray(eye, cam.pixel_ray(px)).unwrap();
        let r = reflect((p - eye).normalize(), DVec3::Y);
        let (uv, w) = room_sample(&RING, &cam, p, r).expect("the far ring is in view");
        assert!(w > 0.99);
        assert!(
            uv.y < 300.0 / 480.0,
            "reflected from higher in the image: {uv}"
        );
        assert!(
            (uv.x - 0.5).abs() < 1e-9,
            "straight ahead stays straight ahead"
        );
    }
}
