//! Geometric optics of a water surface, in f64, with no GPU code: the reference that the WGSL
//! mirrors in `shaders/optics.wgsl` are tested against, and what the CPU-side effect models
//! (refraction of the table, caustics) are built from.
//!
//! - The full Fresnel equations (as the CS114 WebGL pool report, 2018, uses them instead of
//!   Schlick's approximation; docs/sources.md) for s- and p-polarised light, their unpolarised
//!   average, and total internal reflection; Schlick's approximation only for comparison.
//! - Snell refraction and mirror reflection of direction vectors.
//! - The planar reflection matrix and oblique near-plane clipping (after Lengyel 2005), eqs. 1
//!   and 2 of the Sailing+ AR water thesis (TU Delft 2022, report 000 in docs/sources.md), on a glam projection matrix, for OpenGL's and for wgpu's depth
//!   range.
//! - Ray–plane intersection and pinhole projection through camera intrinsics and pose.
//!
//! Conventions: all direction vectors are unit length unless said otherwise; a [`Plane`] is
//! `n·x + d = 0` with unit `n`; the camera looks down its −z axis with +y up (ARCore's and
//! OpenGL's convention) and image rows grow downwards.

use glam::{DMat4, DVec2, DVec3, DVec4};

/// Refractive index of air.
pub const N_AIR: f64 = 1.0;
/// Refractive index of water for visible light (about 1.333 at 20 °C, 589 nm; the CS114 pool
/// report rounds it to 1.33).
pub const N_WATER: f64 = 1.333;

/// The Fresnel power coefficients at one interface and angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fresnel {
    /// Reflectance of s-polarised light (electric field perpendicular to the plane of
    /// incidence). The CS114 pool report (004) calls this one "fPar"; the name is swapped there, the average
    /// is the same.
    pub rs: f64,
    /// Reflectance of p-polarised light (field in the plane of incidence); zero at Brewster's
    /// angle.
    pub rp: f64,
    /// Unpolarised reflectance (rs + rp) / 2: the share of light that is reflected.
    pub r: f64,
    /// Transmittance 1 − r (energy conservation at a lossless interface).
    pub t: f64,
    /// Cosine of the refraction angle; 0 under total internal reflection.
    pub cos_t: f64,
    /// True when sin θt would exceed 1: everything is reflected.
    pub total_internal: bool,
}

/// The full Fresnel equations for light going from index `n1` into index `n2`, at an angle of
/// incidence whose cosine is `cos_i` (its sign is ignored: the side the ray comes from is the
/// `n1` side by definition).
///
/// Rs = ((n1 cos θi − n2 cos θt) / (n1 cos θi + n2 cos θt))²,
/// Rp = ((n1 cos θt − n2 cos θi) / (n1 cos θt + n2 cos θi))², R = (Rs + Rp)/2, T = 1 − R,
/// with cos θt from Snell's law n1 sin θi = n2 sin θt. Above the critical angle
/// (n1 > n2, sin θi > n2/n1) R = 1.
pub fn fresnel(cos_i: f64, n1: f64, n2: f64) -> Fresnel {
    let cos_i = cos_i.abs().min(1.0);
    let sin2_t = (n1 / n2).powi(2) * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return Fresnel {
            rs: 1.0,
            rp: 1.0,
            r: 1.0,
            t: 0.0,
            cos_t: 0.0,
            total_internal: true,
        };
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = ((n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)).powi(2);
    let rp = ((n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i)).powi(2);
    let r = 0.5 * (rs + rp);
    Fresnel {
        rs,
        rp,
        r,
        t: 1.0 - r,
        cos_t,
        total_internal: false,
    }
}

/// Reflectance at normal incidence, R0 = ((n1 − n2)/(n1 + n2))².
pub(crate) fn reflectance_normal(n1: f64, n2: f64) -> f64 {
    ((n1 - n2) / (n1 + n2)).powi(2)
}

/// Brewster's angle θB = atan(n2/n1), radians: where p-polarised light is not reflected.
pub fn brewster_angle(n1: f64, n2: f64) -> f64 {
    (n2 / n1).atan()
}

/// The critical angle asin(n2/n1), radians, beyond which light is totally reflected;
/// `None` when n1 ≤ n2 (no total internal reflection going into a denser medium).
pub fn critical_angle(n1: f64, n2: f64) -> Option<f64> {
    (n1 > n2).then(|| (n2 / n1).asin())
}

/// Schlick's approximation R ≈ R0 + (1 − R0)(1 − cos θ)⁵, kept for comparison only (the bench
/// tabulates its error). Going into a less dense medium it uses the transmitted angle, as
/// Schlick prescribes, and returns 1 under total internal reflection.
pub fn schlick(cos_i: f64, n1: f64, n2: f64) -> f64 {
    let r0 = reflectance_normal(n1, n2);
    let mut c = cos_i.abs().min(1.0);
    if n1 > n2 {
        let sin2_t = (n1 / n2).powi(2) * (1.0 - c * c);
        if sin2_t >= 1.0 {
            return 1.0;
        }
        c = (1.0 - sin2_t).sqrt();
    }
    r0 + (1.0 - r0) * (1.0 - c).powi(5)
}

/// Mirror reflection of direction `d` about a surface with normal `n` (either orientation):
/// d − 2 (d·n) n.
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// Snell refraction of the unit direction `d` through a surface with unit normal `n`, from
/// index `n1` (the side `d` comes from) into `n2`. The normal may face either way; it is turned
/// to face the incoming ray. Returns the unit transmitted direction, or `None` under total
/// internal reflection.
///
/// t = η d + (η cos θi − cos θt) n', η = n1/n2, cos θi = −n'·d, cos θt = sqrt(1 − η² sin² θi).
pub fn refract(d: DVec3, n: DVec3, n1: f64, n2: f64) -> Option<DVec3> {
    let n = if d.dot(n) > 0.0 { -n } else { n };
    let eta = n1 / n2;
    let cos_i = -n.dot(d);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return None;
    }
    Some(eta * d + (eta * cos_i - k.sqrt()) * n)
}

/// A plane n·x + d = 0 with unit normal n. The side n points to is the plane's "front".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    pub normal: DVec3,
    pub d: f64,
}

impl Plane {
    /// The plane through `point` with normal `normal` (normalised here; must not be zero).
    #[cfg(test)]
    pub(crate) fn from_point_normal(point: DVec3, normal: DVec3) -> Plane {
        let normal = normal.normalize();
        Plane {
            normal,
            d: -normal.dot(point),
        }
    }

    /// The horizontal plane y = `height`, facing up.
    pub fn horizontal(height: f64) -> Plane {
        Plane {
            normal: DVec3::Y,
            d: -height,
        }
    }

    /// Signed distance of `p` from the plane (positive on the front side).
    pub(crate) fn signed_distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) + self.d
    }

    /// The plane as the 4-vector (a, b, c, d), for homogeneous products.
    pub(crate) fn as_vec4(&self) -> DVec4 {
        self.normal.extend(self.d)
    }

    /// The same plane expressed in another frame: `m` maps points of the plane's frame into
    /// the new frame (e.g. a view matrix, world → camera). Planes transform by the inverse
    /// transpose.
    pub fn transformed(&self, m: DMat4) -> Plane {
        let v = m.inverse().transpose() * self.as_vec4();
        let len = v.truncate().length();
        Plane {
            normal: v.truncate() / len,
            d: v.w / len,
        }
    }

    /// Where the ray `origin + s·dir` (s ≥ 0) meets the plane: `(s, point)`, or `None` when
    /// the ray is parallel to the plane or points away from it.
    pub fn intersect_ray(&self, origin: DVec3, dir: DVec3) -> Option<(f64, DVec3)> {
        let denom = self.normal.dot(dir);
        if denom.abs() < 1e-12 {
            return None;
        }
        let s = -self.signed_distance(origin) / denom;
        (s >= 0.0).then(|| (s, origin + s * dir))
    }
}

/// The affine reflection about `plane` (the AR water thesis's eq. 1):
///
/// ```text
/// | 1−2a²  −2ab   −2ac   −2ad |
/// | −2ab   1−2b²  −2bc   −2bd |
/// | −2ac   −2bc   1−2c²  −2cd |
/// |   0      0      0      1  |
/// ```
///
/// Applied to a world-space point it gives its mirror image; a reflected camera's view matrix
/// is `view * reflection_matrix(plane)`. It flips handedness, so the reflection pass must swap
/// its front-face winding.
pub fn reflection_matrix(plane: &Plane) -> DMat4 {
    let DVec3 { x: a, y: b, z: c } = plane.normal;
    let d = plane.d;
    // glam takes columns.
    DMat4::from_cols(
        DVec4::new(1.0 - 2.0 * a * a, -2.0 * a * b, -2.0 * a * c, 0.0),
        DVec4::new(-2.0 * a * b, 1.0 - 2.0 * b * b, -2.0 * b * c, 0.0),
        DVec4::new(-2.0 * a * c, -2.0 * b * c, 1.0 - 2.0 * c * c, 0.0),
        DVec4::new(-2.0 * a * d, -2.0 * b * d, -2.0 * c * d, 1.0),
    )
}

/// The clip-space depth range a projection matrix maps the view frustum into.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthRange {
    /// OpenGL: −w ≤ z ≤ w (glam's `dcamera::rh::proj::opengl`); 000's eq. 2 is written for this.
    MinusOneToOne,
    /// wgpu, Vulkan, Metal, D3D: 0 ≤ z ≤ w (glam's `dcamera::rh::proj::directx`).
    ZeroToOne,
}

/// Oblique near-plane clipping (the AR water thesis's eq. 2; Lengyel, "Oblique view frustum depth
/// projection and clipping", 2005): returns `proj` with its third row replaced so that the near
/// plane becomes `clip_plane` (given in view space, its front the side that is kept) and the
/// far plane still passes through the far frustum corner Q opposite to it, so depth precision
/// is kept as well as possible. Everything behind the plane (under the water, for a reflection
/// camera) is clipped by the rasteriser for free.
///
/// For `MinusOneToOne`: M3' = (2 M4·Q / C·Q) C − M4 (eq. 2 as printed). For `ZeroToOne` the
/// near plane is z ≥ 0 instead of z ≥ −w, and the same derivation gives M3' = (M4·Q / C·Q) C.
/// Q = M⁻¹ (sgn Cx, sgn Cy, 1, 1).
///
/// Returns `None` when the camera (the view-space origin) is not strictly behind the plane
/// (C·(0,0,0,1) = d ≥ 0): a near plane through or behind the eye cannot be made.
pub fn oblique_near_plane(proj: DMat4, clip_plane: &Plane, range: DepthRange) -> Option<DMat4> {
    let c = clip_plane.as_vec4();
    if c.w >= 0.0 {
        return None;
    }
    // Rows of the projection matrix (glam stores columns).
    let rows = proj.transpose();
    let m4 = rows.w_axis;
    let q_clip = DVec4::new(c.x.signum(), c.y.signum(), 1.0, 1.0);
    let q = proj.inverse() * q_clip;
    let cq = c.dot(q);
    if cq.abs() < 1e-300 {
        return None;
    }
    let m3 = match range {
        DepthRange::MinusOneToOne => (2.0 * m4.dot(q) / cq) * c - m4,
        DepthRange::ZeroToOne => (m4.dot(q) / cq) * c,
    };
    let new_rows = DMat4::from_cols(rows.x_axis, rows.y_axis, m3, m4);
    Some(new_rows.transpose())
}

/// A pinhole camera: intrinsics in pixels and a camera-to-world pose.
///
/// The camera looks down its local −z axis with +y up and +x right (ARCore's convention);
/// pixel (0, 0) is the top-left corner of the image and rows grow downwards, so a camera-space
/// point (x, y, z), z < 0, lands at u = cx + fx·x/(−z), v = cy − fy·y/(−z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinholeCamera {
    /// Focal lengths, pixels.
    pub fx: f64,
    pub fy: f64,
    /// Principal point, pixels from the top-left corner.
    pub cx: f64,
    pub cy: f64,
    /// Image size, pixels.
    pub width: f64,
    pub height: f64,
    /// Camera-to-world rigid transform (metres).
    pub pose: DMat4,
}

impl PinholeCamera {
    /// World position of the optical centre.
    pub fn position(&self) -> DVec3 {
        self.pose.w_axis.truncate()
    }

    /// The pixel that world point `p` projects to (may lie outside the image), or `None` when
    /// `p` is not in front of the camera.
    pub fn project(&self, p: DVec3) -> Option<DVec2> {
        let c = self.pose.inverse().transform_point3(p);
        if c.z >= 0.0 {
            return None;
        }
        Some(DVec2::new(
            self.cx + self.fx * c.x / -c.z,
            self.cy - self.fy * c.y / -c.z,
        ))
    }

    /// The pixel as normalised image coordinates in [0, 1]² (texture UV, v down).
    pub fn project_uv(&self, p: DVec3) -> Option<DVec2> {
        self.project(p)
            .map(|px| DVec2::new(px.x / self.width, px.y / self.height))
    }

    /// The image projection as one matrix for points in the frame of `view` (world → camera,
    /// e.g. with a local origin folded in): rows 0–2 map (p, 1) to (u·w, v·w, w), with (u, v)
    /// `project_uv`'s and w = −z in the camera (> 0 in front of it); row 3 is zero. A shader
    /// projects with one matrix product and one division per coordinate, the intrinsics
    /// folded in here in f64 instead of applied to every pixel.
    pub fn image_projection(&self, view: DMat4) -> DMat4 {
        let (fx, fy) = (self.fx / self.width, self.fy / self.height);
        let (cx, cy) = (self.cx / self.width, self.cy / self.height);
        let k = DMat4::from_cols(
            DVec4::new(fx, 0.0, 0.0, 0.0),
            DVec4::new(0.0, -fy, 0.0, 0.0),
            DVec4::new(-cx, -cy, -1.0, 0.0),
            DVec4::ZERO,
        );
        k * view
    }

    /// The unit world-space direction of the ray through pixel `px` (inverse of `project`).
    pub fn pixel_ray(&self, px: DVec2) -> DVec3 {
        let c = DVec3::new(
            (px.x - self.cx) / self.fx,
            -(px.y - self.cy) / self.fy,
            -1.0,
        );
        self.pose.transform_vector3(c).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;
    use glam::dcamera::rh::proj::{directx, opengl};
    use glam::dcamera::rh::view::look_at_mat4;

    const EPS: f64 = 1e-12;

    /// The folded projection gives `project_uv`'s uv (and w > 0 exactly where it has one).
    #[test]
    fn the_image_projection_is_project_uv() {
        let cam = PinholeCamera {
            fx: 510.0,
            fy: 498.0,
            cx: 322.5,
            cy: 236.0,
            width: 640.0,
            height: 480.0,
            pose: look_at_mat4(
                DVec3::new(0.3, 1.2, 0.8),
                DVec3::new(-0.1, 0.0, 0.2),
                DVec3::Y,
            )
            .inverse(),
        };
        let view = cam.pose.inverse();
        let m = cam.image_projection(view);
        for p in [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.4, -0.1, -0.3),
            DVec3::new(-2.0, 0.5, 1.0),
            DVec3::new(5.0, 3.0, 9.0),
        ] {
            let h = m * p.extend(1.0);
            assert_eq!(h.w, 0.0);
            match cam.project_uv(p) {
                Some(uv) => {
                    assert!(h.z > 0.0);
                    assert!(
                        (DVec2::new(h.x / h.z, h.y / h.z) - uv).length() < EPS,
                        "{p}"
                    );
                }
                None => assert!(h.z <= 0.0, "{p}"),
            }
        }
    }

    #[test]
    fn normal_incidence_matches_closed_form() {
        let f = fresnel(1.0, N_AIR, N_WATER);
        let r0 = ((1.0 - 1.333) / (1.0 + 1.333f64)).powi(2);
        assert!((f.r - r0).abs() < EPS);
        assert!((f.rs - r0).abs() < EPS && (f.rp - r0).abs() < EPS);
        assert!(
            (f.r - 0.020_373_5).abs() < 1e-6,
            "R0 of water is about 2 %: {}",
            f.r
        );
        // The same from the water side (reciprocity at normal incidence).
        assert!((fresnel(1.0, N_WATER, N_AIR).r - r0).abs() < EPS);
    }

    #[test]
    fn brewster_angle_has_no_p_reflection() {
        let tb = brewster_angle(N_AIR, N_WATER);
        assert!(
            (tb.to_degrees() - 53.12).abs() < 0.01,
            "{}",
            tb.to_degrees()
        );
        let f = fresnel(tb.cos(), N_AIR, N_WATER);
        assert!(f.rp < 1e-20, "Rp at Brewster = {}", f.rp);
        assert!(f.rs > 0.05);
        // Also from inside the water, where θB = atan(1/1.333).
        let tb2 = brewster_angle(N_WATER, N_AIR);
        assert!(fresnel(tb2.cos(), N_WATER, N_AIR).rp < 1e-20);
        assert!((tb + tb2 - std::f64::consts::FRAC_PI_2).abs() < EPS);
    }

    #[test]
    fn total_internal_reflection_above_the_critical_angle() {
        let tc = critical_angle(N_WATER, N_AIR).unwrap();
        assert!((tc.sin() - 1.0 / 1.333).abs() < EPS);
        assert!((tc.to_degrees() - 48.61).abs() < 0.01);
        let above = fresnel((tc + 1e-6).cos(), N_WATER, N_AIR);
        assert!(above.total_internal && above.r == 1.0 && above.t == 0.0);
        let below = fresnel((tc - 1e-3).cos(), N_WATER, N_AIR);
        assert!(!below.total_internal && below.r < 1.0 && below.r > 0.5);
        assert!(critical_angle(N_AIR, N_WATER).is_none());
        // Refract agrees: no transmitted ray above the critical angle.
        let d = |th: f64| DVec3::new(th.sin(), th.cos(), 0.0); // going up through y = 0
        assert!(refract(d(tc + 1e-6), DVec3::Y, N_WATER, N_AIR).is_none());
        assert!(refract(d(tc - 1e-6), DVec3::Y, N_WATER, N_AIR).is_some());
        assert_eq!(schlick((tc + 1e-6).cos(), N_WATER, N_AIR), 1.0);
    }

    #[test]
    fn energy_is_conserved_and_grazing_reflects_all() {
        for i in 0..=90 {
            let th = (i as f64).to_radians();
            for (n1, n2) in [(N_AIR, N_WATER), (N_WATER, N_AIR)] {
                let f = fresnel(th.cos(), n1, n2);
                assert!((f.r + f.t - 1.0).abs() < EPS);
                assert!((0.0..=1.0).contains(&f.r) && (0.0..=1.0).contains(&f.rs));
                assert!(f.rs >= f.rp - EPS, "s reflects at least as much as p");
            }
        }
        assert!((fresnel(0.0, N_AIR, N_WATER).r - 1.0).abs() < EPS);
    }

    #[test]
    fn stokes_relations_hold_both_ways() {
        // Reciprocity: the reflectance going in at θi equals the one coming out at θt.
        for i in 0..89 {
            let ti = (i as f64).to_radians();
            let f_in = fresnel(ti.cos(), N_AIR, N_WATER);
            let f_out = fresnel(f_in.cos_t, N_WATER, N_AIR);
            assert!((f_in.rs - f_out.rs).abs() < 1e-12);
            assert!((f_in.rp - f_out.rp).abs() < 1e-12);
        }
    }

    #[test]
    fn schlick_agrees_at_the_ends_and_errs_in_between() {
        let r0 = reflectance_normal(N_AIR, N_WATER);
        assert!((schlick(1.0, N_AIR, N_WATER) - r0).abs() < EPS);
        assert!((schlick(0.0, N_AIR, N_WATER) - 1.0).abs() < EPS);
        let worst = (0..90)
            .map(|i| {
                let c = (i as f64).to_radians().cos();
                (schlick(c, N_AIR, N_WATER) - fresnel(c, N_AIR, N_WATER).r).abs()
            })
            .fold(0.0, f64::max);
        // Schlick's worst absolute error for water is about 0.058 near 84°, and at 50° it is
        // 23 % low: why the water uses the full equations.
        assert!(worst > 0.055 && worst < 0.06, "worst Schlick error {worst}");
        let c50 = 50f64.to_radians().cos();
        let full = fresnel(c50, N_AIR, N_WATER).r;
        assert!((full - schlick(c50, N_AIR, N_WATER)) / full > 0.2);
    }

    #[test]
    fn snell_law_and_reflection_vectors() {
        let n = DVec3::Y;
        for i in 0..90 {
            let ti = (i as f64).to_radians();
            let d = DVec3::new(ti.sin(), -ti.cos(), 0.0);
            let t = refract(d, n, N_AIR, N_WATER).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-12);
            let sin_t = t.x; // stays in the plane of incidence, on the far side
            assert!((N_AIR * ti.sin() - N_WATER * sin_t).abs() < 1e-12);
            assert!(t.y < 0.0 && t.z.abs() < EPS);
            // Flipping the normal changes nothing.
            assert!((refract(d, -n, N_AIR, N_WATER).unwrap() - t).length() < EPS);
            let r = reflect(d, n);
            assert!((r - DVec3::new(d.x, -d.y, 0.0)).length() < EPS);
        }
        // Equal indices: straight through.
        let d = DVec3::new(0.3, -0.8, 0.1).normalize();
        assert!((refract(d, n, 1.0, 1.0).unwrap() - d).length() < EPS);
    }

    #[test]
    fn reflection_matrix_mirrors_points_about_the_plane() {
        let plane =
            Plane::from_point_normal(DVec3::new(1.0, 0.25, -2.0), DVec3::new(0.2, 1.0, 0.1));
        let m = reflection_matrix(&plane);
        for p in [
            DVec3::ZERO,
            DVec3::new(3.0, 5.0, -7.0),
            DVec3::new(-1.0, -2.0, 0.5),
        ] {
            let q = m.transform_point3(p);
            // Same distance, other side, and the midpoint lies on the plane.
            assert!((plane.signed_distance(q) + plane.signed_distance(p)).abs() < 1e-12);
            assert!(plane.signed_distance(0.5 * (p + q)).abs() < 1e-12);
            assert!(
                (q - p).cross(plane.normal).length() < 1e-12,
                "moves along the normal"
            );
            // An involution.
            assert!((m.transform_point3(q) - p).length() < 1e-12);
        }
        assert!((m.determinant() + 1.0).abs() < 1e-12, "flips handedness");
    }

    fn look_at_camera(eye: DVec3, target: DVec3) -> DMat4 {
        look_at_mat4(eye, target, DVec3::Y)
    }

    #[test]
    fn oblique_clipping_clips_exactly_below_the_water() {
        // A camera above the water looking steeply down, reflected about y = 0.
        let water = Plane::horizontal(0.0);
        let eye = DVec3::new(0.3, 0.8, 1.0);
        let view = look_at_camera(eye, DVec3::new(0.0, 0.0, -0.2));
        let refl_view = view * reflection_matrix(&water);
        let plane_view = water.transformed(refl_view);
        for range in [DepthRange::ZeroToOne, DepthRange::MinusOneToOne] {
            let proj = match range {
                DepthRange::ZeroToOne => directx::perspective(1.0, 1.3, 0.05, 50.0),
                DepthRange::MinusOneToOne => opengl::perspective(1.0, 1.3, 0.05, 50.0),
            };
            let obl = oblique_near_plane(proj, &plane_view, range).unwrap();
            let near = |clip: DVec4| match range {
                DepthRange::ZeroToOne => clip.z,
                DepthRange::MinusOneToOne => clip.z + clip.w,
            };
            // x, y and w rows are unchanged: the image does not move.
            let (a, b) = (proj.transpose(), obl.transpose());
            assert_eq!(
                (a.x_axis, a.y_axis, a.w_axis),
                (b.x_axis, b.y_axis, b.w_axis)
            );
            // World points below the water are clipped, above kept, on it exactly at the
            // near plane; in front of the reflected camera in every case.
            for (x, y, z) in [
                (0.1, 0.2, -0.3),
                (-0.2, -0.05, 0.1),
                (0.0, 0.0, 0.0),
                (0.4, 0.6, -1.0),
                (0.2, -0.4, -0.5),
            ] {
                let pw = DVec3::new(x, y, z);
                let clip = obl * (refl_view * pw.extend(1.0));
                let s = near(clip) / clip.w.abs();
                if y > 0.0 {
                    assert!(s > 0.0, "{range:?}: above water must be kept ({pw})");
                } else if y < 0.0 {
                    assert!(s < 0.0, "{range:?}: below water must be clipped ({pw})");
                } else {
                    assert!(s.abs() < 1e-12);
                }
            }
            // The far corner Q still lies on the far plane.
            let c = plane_view.as_vec4();
            let q = proj.inverse() * DVec4::new(c.x.signum(), c.y.signum(), 1.0, 1.0);
            let qc: DVec4 = obl * q;
            assert!((qc.z / qc.w - 1.0).abs() < 1e-9);
        }
        // A camera in front of the plane (the eye on the kept side) cannot clip.
        let eye_side = Plane::from_point_normal(DVec3::new(0.0, 0.0, -1.0), DVec3::Z);
        let proj = directx::perspective(1.0, 1.0, 0.1, 10.0);
        assert!(oblique_near_plane(proj, &eye_side, DepthRange::ZeroToOne).is_none());
    }

    #[test]
    fn ray_plane_intersection() {
        let p = Plane::horizontal(-0.5);
        let (s, hit) = p
            .intersect_ray(DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.0, -1.0, 0.0))
            .unwrap();
        assert!((s - 1.5).abs() < EPS && (hit - DVec3::new(1.0, -0.5, 0.0)).length() < EPS);
        assert!(p.intersect_ray(DVec3::Y, DVec3::Y).is_none(), "points away");
        assert!(p.intersect_ray(DVec3::Y, DVec3::X).is_none(), "parallel");
    }

    #[test]
    fn pinhole_projection_round_trips_and_matches_intrinsics() {
        let pose = DMat4::from_rotation_translation(
            DQuat::from_rotation_x(-0.9) * DQuat::from_rotation_y(0.3),
            DVec3::new(0.2, 0.6, 0.7),
        );
        let cam = PinholeCamera {
            fx: 500.0,
            fy: 505.0,
            cx: 320.0,
            cy: 240.0,
            width: 640.0,
            height: 480.0,
            pose,
        };
        // The optical axis hits the principal point.
        let ahead = cam.position() + pose.transform_vector3(-DVec3::Z) * 2.0;
        assert!((cam.project(ahead).unwrap() - DVec2::new(320.0, 240.0)).length() < 1e-9);
        // A point up and right of the axis, 1 m away, by the closed form.
        let p = pose.transform_point3(DVec3::new(0.1, 0.2, -1.0));
        let px = cam.project(p).unwrap();
        assert!((px - DVec2::new(370.0, 240.0 - 101.0)).length() < 1e-9);
        // pixel_ray inverts project.
        let r = cam.pixel_ray(px);
        assert!(r.cross((p - cam.position()).normalize()).length() < 1e-12);
        assert!(
            cam.project(cam.position() - (ahead - cam.position()))
                .is_none(),
            "behind"
        );
        let uv = cam.project_uv(ahead).unwrap();
        assert!((uv - DVec2::splat(0.5)).length() < 1e-12);
    }
}
