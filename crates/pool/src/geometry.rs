//! Rays, spheres and the pool box, in f64 pool space (metres; x east, y up, z south; the rest
//! level of the water at y = 0, the pool centred on the origin).
//!
//! Every intersection here is closed form: a quadratic for a sphere, slabs for the box. The WGSL
//! in `shaders/pool_common.wgsl` does the same in f32; these are its references.

use glam::DVec3;

/// Hits closer than this along a ray are ignored, metres: a ray leaving a surface must not hit
/// the surface it starts on through rounding.
pub const RAY_EPSILON: f64 = 1e-9;

/// A half-line `origin + s · dir`, s ≥ 0. `dir` is a unit vector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Metres, pool space.
    pub origin: DVec3,
    /// Unit direction.
    pub dir: DVec3,
}

impl Ray {
    /// A ray from `origin` along `dir` (normalised here).
    pub fn new(origin: DVec3, dir: DVec3) -> Ray {
        Ray {
            origin,
            dir: dir.normalize(),
        }
    }
    /// The point at distance `s` (metres) along the ray.
    pub fn at(&self, s: f64) -> DVec3 {
        self.origin + self.dir * s
    }
}

/// A sphere in pool space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Centre, metres.
    pub center: DVec3,
    /// Radius, metres, > 0.
    pub radius: f64,
}

impl Sphere {
    /// Distance along `ray` to the nearest crossing of the sphere's surface beyond
    /// [`RAY_EPSILON`], if any (from outside: the entry; from inside: the exit).
    ///
    /// |o + s d − c|² = r² with |d| = 1 is s² + 2 b s + q = 0, b = d·(o − c), q = |o − c|² − r².
    /// The roots are computed in the cancellation-free form s₁ = −b − sign(b)·√(b² − q),
    /// s₂ = q / s₁.
    pub fn hit(&self, ray: &Ray) -> Option<f64> {
        let oc = ray.origin - self.center;
        let b = ray.dir.dot(oc);
        let q = oc.length_squared() - self.radius * self.radius;
        let disc = b * b - q;
        if disc < 0.0 {
            return None;
        }
        let root = disc.sqrt();
        let s1 = if b > 0.0 { -b - root } else { -b + root };
        if s1 == 0.0 {
            // b = 0 and q = 0: the ray starts on the sphere, tangent to it.
            return None;
        }
        let s2 = q / s1;
        let (near, far) = if s1 < s2 { (s1, s2) } else { (s2, s1) };
        [near, far].into_iter().find(|&s| s > RAY_EPSILON)
    }

    /// Outward unit normal at a point on the sphere.
    pub fn normal_at(&self, p: DVec3) -> DVec3 {
        (p - self.center) / self.radius
    }
}

/// Which face of the pool box a ray hit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Face {
    Floor,
    /// The wall at x = −half_x (its normal points +x, into the pool).
    West,
    /// x = +half_x.
    East,
    /// z = −half_z.
    North,
    /// z = +half_z.
    South,
}

impl Face {
    /// Unit normal of the face, pointing into the pool.
    pub fn inward_normal(self) -> DVec3 {
        match self {
            Face::Floor => DVec3::Y,
            Face::West => DVec3::X,
            Face::East => DVec3::NEG_X,
            Face::North => DVec3::Z,
            Face::South => DVec3::NEG_Z,
        }
    }
}

/// A hit on the inside of the pool box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxHit {
    /// Distance along the ray, metres.
    pub s: f64,
    pub point: DVec3,
    /// Unit normal of the face, pointing into the pool.
    pub normal: DVec3,
    pub face: Face,
}

/// The open-topped tiled box: inner walls at x = ±half_x, z = ±half_z, the floor at y = floor_y,
/// the rim at y = rim_y (the water's rest level is y = 0, between them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoolBox {
    /// Metres.
    pub half_x: f64,
    pub half_z: f64,
    /// y of the floor, metres (< 0).
    pub floor_y: f64,
    /// y of the rim, metres (> 0).
    pub rim_y: f64,
}

impl PoolBox {
    /// Whether `p` lies inside the box (tolerance `eps` metres on every side).
    pub fn contains(&self, p: DVec3, eps: f64) -> bool {
        p.x.abs() <= self.half_x + eps
            && p.z.abs() <= self.half_z + eps
            && p.y >= self.floor_y - eps
            && p.y <= self.rim_y + eps
    }

    /// Where a ray that starts inside the box leaves it through a wall or the floor; `None` when
    /// it leaves through the open top (it sees the sky, or whatever is above the pool).
    ///
    /// Slabs: along each axis the ray leaves through the face it moves towards, at
    /// s = (bound − o)/d; the first of the three exits is the one it takes.
    pub fn hit_inside(&self, ray: &Ray) -> Option<BoxHit> {
        let o = ray.origin;
        let d = ray.dir;
        // `None` as the face is the open top.
        let mut best: Option<(f64, Option<Face>)> = None;
        let mut consider = |s: f64, face: Option<Face>| {
            if best.is_none_or(|(b, _)| s < b) {
                best = Some((s, face));
            }
        };
        if d.x > 0.0 {
            consider((self.half_x - o.x) / d.x, Some(Face::East));
        } else if d.x < 0.0 {
            consider((-self.half_x - o.x) / d.x, Some(Face::West));
        }
        if d.z > 0.0 {
            consider((self.half_z - o.z) / d.z, Some(Face::South));
        } else if d.z < 0.0 {
            consider((-self.half_z - o.z) / d.z, Some(Face::North));
        }
        if d.y < 0.0 {
            consider((self.floor_y - o.y) / d.y, Some(Face::Floor));
        } else if d.y > 0.0 {
            consider((self.rim_y - o.y) / d.y, None);
        }
        let (s, face) = best?;
        let face = face?;
        let s = s.max(0.0);
        Some(BoxHit {
            s,
            point: ray.at(s),
            normal: face.inward_normal(),
            face,
        })
    }

    /// Coordinates of a point on a face in the unfolded net of the box, metres: the floor keeps
    /// its (x, z); each wall is folded down flat around the floor's edge, so a point at height y
    /// on the east wall lands at x = half_x + (y − floor_y). The unfolding is an isometry of
    /// each face and continuous across the floor's edges, so areas and the light that lands on
    /// them are the same in the net as on the faces. The caustics texture is laid out on it.
    pub fn net_coords(&self, face: Face, p: DVec3) -> [f64; 2] {
        let up = p.y - self.floor_y;
        match face {
            Face::Floor => [p.x, p.z],
            Face::East => [self.half_x + up, p.z],
            Face::West => [-self.half_x - up, p.z],
            Face::South => [p.x, self.half_z + up],
            Face::North => [p.x, -self.half_z - up],
        }
    }

    /// Half extents of the net (x, z): the floor plus the walls up to the rim.
    pub fn net_half_extent(&self) -> [f64; 2] {
        let h = self.rim_y - self.floor_y;
        [self.half_x + h, self.half_z + h]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool() -> PoolBox {
        PoolBox {
            half_x: 1.0,
            half_z: 0.75,
            floor_y: -1.0,
            rim_y: 0.2,
        }
    }

    #[test]
    fn ray_through_sphere_centre_hits_at_distance_minus_radius() {
        let s = Sphere {
            center: DVec3::new(1.0, 2.0, 3.0),
            radius: 0.5,
        };
        let ray = Ray::new(DVec3::new(1.0, 2.0, -4.0), DVec3::Z);
        // 7 m to the centre, entry 0.5 m earlier.
        assert!((s.hit(&ray).unwrap() - 6.5).abs() < 1e-12);
    }

    #[test]
    fn ray_from_inside_sphere_exits_on_far_side() {
        let s = Sphere {
            center: DVec3::ZERO,
            radius: 2.0,
        };
        let ray = Ray::new(DVec3::new(0.5, 0.0, 0.0), DVec3::X);
        assert!((s.hit(&ray).unwrap() - 1.5).abs() < 1e-12);
    }

    #[test]
    fn oblique_ray_hits_sphere_at_closed_form_chord() {
        // A ray at perpendicular distance d from the centre enters at (along-ray distance to the
        // closest point) − sqrt(r² − d²).
        let c = DVec3::new(0.3, -0.2, 0.1);
        let r = 0.4;
        let d = 0.25;
        let dir = DVec3::new(1.0, 2.0, -0.5).normalize();
        let perp = dir.cross(DVec3::Y).normalize();
        let closest = c + perp * d;
        let origin = closest - dir * 3.0;
        let s = Sphere {
            center: c,
            radius: r,
        }
        .hit(&Ray::new(origin, dir))
        .unwrap();
        let expected = 3.0 - (r * r - d * d).sqrt();
        assert!((s - expected).abs() < 1e-12, "{s} vs {expected}");
        // The hit point is on the sphere.
        let p = origin + dir * s;
        assert!(((p - c).length() - r).abs() < 1e-12);
    }

    #[test]
    fn ray_missing_sphere_or_pointing_away_has_no_hit() {
        let s = Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        };
        assert!(
            s.hit(&Ray::new(DVec3::new(0.0, 1.01, -5.0), DVec3::Z))
                .is_none()
        );
        assert!(
            s.hit(&Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::NEG_Z))
                .is_none()
        );
    }

    #[test]
    fn ray_inside_box_hits_the_face_it_heads_for() {
        let b = pool();
        // Straight down from the water: the floor, 1 m below.
        let h = b.hit_inside(&Ray::new(DVec3::ZERO, DVec3::NEG_Y)).unwrap();
        assert_eq!(h.face, Face::Floor);
        assert!((h.s - 1.0).abs() < 1e-12);
        assert_eq!(h.normal, DVec3::Y);
        // Shallow towards +x: the east wall at x = 1 before the floor.
        let dir = DVec3::new(1.0, -0.2, 0.0).normalize();
        let h = b.hit_inside(&Ray::new(DVec3::ZERO, dir)).unwrap();
        assert_eq!(h.face, Face::East);
        assert!((h.point.x - 1.0).abs() < 1e-12);
        assert!((h.point.y + 0.2).abs() < 1e-12);
        // Towards the north-west corner region, z reached first.
        let dir = DVec3::new(-0.5, -0.1, -1.0).normalize();
        let h = b.hit_inside(&Ray::new(DVec3::ZERO, dir)).unwrap();
        assert_eq!(h.face, Face::North);
        assert!((h.point.z + 0.75).abs() < 1e-12);
        assert_eq!(h.normal, DVec3::Z);
    }

    #[test]
    fn ray_leaving_through_open_top_has_no_hit() {
        let b = pool();
        assert!(b.hit_inside(&Ray::new(DVec3::ZERO, DVec3::Y)).is_none());
        // Steeply up and a little sideways: leaves through the top at y = 0.2 before x = 1.
        let dir = DVec3::new(0.1, 1.0, 0.0).normalize();
        assert!(b.hit_inside(&Ray::new(DVec3::ZERO, dir)).is_none());
        // Shallow upward towards a wall: hits the wall above the water.
        let dir = DVec3::new(1.0, 0.1, 0.0).normalize();
        let h = b.hit_inside(&Ray::new(DVec3::ZERO, dir)).unwrap();
        assert_eq!(h.face, Face::East);
        assert!((h.point.y - 0.1).abs() < 1e-12);
    }

    #[test]
    fn net_unfolding_preserves_lengths_across_the_floor_edge() {
        let b = pool();
        // A point on the floor 0.1 m from the east edge and one on the east wall 0.1 m up are
        // 0.2 m apart along the surface of the box; in the net they are 0.2 m apart too.
        let a = b.net_coords(Face::Floor, DVec3::new(0.9, -1.0, 0.3));
        let c = b.net_coords(Face::East, DVec3::new(1.0, -0.9, 0.3));
        assert!(((c[0] - a[0]) - 0.2).abs() < 1e-12 && (c[1] - a[1]).abs() < 1e-12);
        let [ex, ez] = b.net_half_extent();
        assert!((ex - 2.2).abs() < 1e-12 && (ez - 1.95).abs() < 1e-12);
        let n = b.net_coords(Face::North, DVec3::new(0.0, 0.2, -0.75));
        assert!((n[1] + 1.95).abs() < 1e-12);
    }
}
