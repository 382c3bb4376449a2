//! The reflected room drawn as a grid (f64 reference of `vs_main` and `fs_main` in
//! `shaders/effects/reflection_room.wgsl`).
//!
//! A texel of the planar reflection texture takes the room through a map: its reflected ray,
//! the ray's water crossing, the ring point it meets, that point's camera-image uv and the
//! image's edge weight (the per-texel map, [`RoomView::sample`]). The pass evaluates the smooth
//! part of it, the ring point's homogeneous camera-image point h = (u w, v w, w) (linear in the
//! ring point), at the corners of a grid of cells at most [`ROOM_CELL_TEXELS`] a side
//! ([`RoomView::image_point`]); the rasteriser interpolates h linearly over each cell's two
//! triangles, and every texel divides out its uv, takes the edge weight, samples the camera
//! image and evaluates the sky and the sun itself ([`GridSamples::at`]). The error is the ring
//! point's own curvature over a cell (linear interpolation errs by h²/8 times the second
//! derivative over a cell of side h: fourfold less per halving), measured texel by texel
//! against the per-texel map by [`interpolation_error`].
//!
//! Interpolating the uv and the weight themselves (as first planned) erred 3.3 times more in
//! uv and 24 times more in weight at the same cells (6.6 px and 0.44 against 2.0 px and 0.018
//! over [`phone_views`]): near the camera the projection bends the uv, and the edge fade is
//! narrower than a cell.
//!
//! Where the map is not smooth the grid cannot follow it. The per-texel map switches to the
//! sky where the water crossing leaves the ring's circle (the exit root then lies behind the
//! crossing); the vertex stage takes that root anyway, so the map runs on smoothly across the
//! circle and the grid stays exact to its curvature on the water inside it, and beyond the
//! circle (off the water, at least 5 % beyond the play area's corners,
//! [`crate::passes::ArConfig::ring_radius_for`]) the texture shows that continuation instead of
//! the sky. Texels above the reflected horizon (rays that do not rise) take the sky; the cells
//! across the horizon blend over their width, off the water too.

use glam::{DVec2, DVec3};

use super::Ring;
use crate::refraction::edge_weight;
use render::optics::PinholeCamera;

/// Texels per side of a cell of the reflected room's grid on a texture whose shorter side is
/// [`ROOM_CELL_REFERENCE_SIDE`] or more (the OPPO A54's `ultra` texture, 360 × 800): chosen by
/// [`interpolation_error`]'s measurement over [`phone_views`] (docs/effects.md, "Reflection:
/// the reflected room as a grid").
pub const ROOM_CELL_TEXELS: u32 = 8;

/// The shorter side, texels, from which a cell is [`ROOM_CELL_TEXELS`] a side.
pub const ROOM_CELL_REFERENCE_SIDE: u32 = 360;

/// Texels per side of a cell on a texture of `texels`: [`ROOM_CELL_TEXELS`] scaled by the
/// square root of its shorter side over [`ROOM_CELL_REFERENCE_SIDE`] (at least 1). The grid's
/// error goes as the square of a cell's angle, a texel's footprint as its angle, so cells
/// that shrink with the square root keep the error in texels of the texture's own footprint
/// at the reference's (a fixed 8 texels over the 32 × 24 texture of a 128 × 96 test frame
/// spans a quarter of the view and errs by several texels).
pub fn room_cell_texels(texels: [u32; 2]) -> u32 {
    let side = f64::from(texels[0].min(texels[1]).max(1));
    let scaled = f64::from(ROOM_CELL_TEXELS) * (side / f64::from(ROOM_CELL_REFERENCE_SIDE)).sqrt();
    (scaled.floor() as u32).clamp(1, ROOM_CELL_TEXELS)
}

/// The reflected room's grid over a texture of `texels` (width, height): columns and rows of
/// cells, each at most [`room_cell_texels`] a side (the cells split the texture evenly).
pub fn room_grid(texels: [u32; 2]) -> [u32; 2] {
    grid_of(texels, room_cell_texels(texels))
}

fn grid_of(texels: [u32; 2], cell: u32) -> [u32; 2] {
    texels.map(|t| t.max(1).div_ceil(cell))
}

/// Vertex invocations of the grid's draw: one triangle strip per row of cells, two vertices
/// per column line (each interior corner is shaded twice, once by each strip it borders).
pub fn room_grid_vertices(texels: [u32; 2]) -> u64 {
    let [cols, rows] = room_grid(texels);
    2 * u64::from(cols + 1) * u64::from(rows)
}

/// What a texel takes of the room: the camera-image uv and its weight (the sky gets 1 −
/// weight).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoomSample {
    pub uv: DVec2,
    pub weight: f64,
}

/// The reflection texture's view of the room: the render camera that draws it (its eye,
/// orthonormal basis, vertical field of view and the screen's aspect), the ring and the
/// physical camera whose image stands on it, and the water (play area) for the counts.
#[derive(Debug, Clone)]
pub struct RoomView {
    /// The render camera.
    pub render: render::Camera,
    pub eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    tan_half_y: f64,
    aspect: f64,
    pub ring: Ring,
    pub camera: PinholeCamera,
    /// min x, min z, max x, max z (local metres).
    pub water: [f64; 4],
}

impl RoomView {
    /// The texture drawn for render camera `cam` on a screen of aspect `aspect` (width over
    /// height), with the room's `ring` seen by the physical `camera`.
    pub fn new(
        cam: &render::Camera,
        aspect: f64,
        ring: Ring,
        camera: PinholeCamera,
        water: [f64; 4],
    ) -> Self {
        // glam's look_at_rh basis: the view the renderer draws with.
        let forward = (cam.target - cam.eye).normalize();
        let right = forward.cross(cam.up).normalize();
        let up = right.cross(forward);
        RoomView {
            render: *cam,
            eye: cam.eye,
            forward,
            right,
            up,
            tan_half_y: (0.5 * cam.fov_y).tan(),
            aspect,
            ring,
            camera,
            water,
        }
    }

    /// The mirrored eye's ray through NDC point `ndc` of the texture (the reflection of the
    /// eye's ray through the same screen point) and the point `p` the shader takes as its
    /// water crossing: eye′ + r·(−eye′.y / max(r.y, 10⁻⁶)), as `room_sample` computes it.
    pub fn ray(&self, ndc: DVec2) -> (DVec3, DVec3) {
        let d = (self.forward
            + ndc.x * self.tan_half_y * self.aspect * self.right
            + ndc.y * self.tan_half_y * self.up)
            .normalize();
        let r = DVec3::new(d.x, -d.y, d.z);
        let eye = DVec3::new(self.eye.x, -self.eye.y, self.eye.z);
        let p = eye + r * (-eye.y / r.y.max(1e-6));
        (p, r)
    }

    /// `room_image_point` of the vertex stage at NDC point `ndc`, in exact arithmetic: the
    /// homogeneous camera-image point (u w, v w, w) of the ring point the reflected ray meets,
    /// the ring's exit root taken wherever the ray rises (also behind the water crossing,
    /// outside the ring's circle); (0, 0, −1) where the ray does not rise.
    pub fn image_point(&self, ndc: DVec2) -> DVec3 {
        let (p, r) = self.ray(ndc);
        if r.y <= 0.0 {
            return DVec3::new(0.0, 0.0, -1.0);
        }
        let o = DVec2::new(p.x, p.z) - self.ring.centre;
        let d = DVec2::new(r.x, r.z);
        let a = d.length_squared().max(1e-8);
        let b = o.dot(d);
        let k = (b * b - a * (o.length_squared() - self.ring.radius * self.ring.radius)).max(0.0);
        let q = p + r * ((-b + k.sqrt()) / a);
        let h = self.camera.image_projection(self.camera.pose.inverse()) * q.extend(1.0);
        h.truncate()
    }

    /// The per-texel map at NDC point `ndc` (the pass before the grid, one texel at a time):
    /// the uv of the ring point the reflected ray meets ([`Ring::hit`]; the image's centre
    /// behind the camera) and the edge weight there (0 where the ray meets no ring point or
    /// the camera does not see it).
    pub fn sample(&self, ndc: DVec2) -> RoomSample {
        let (p, r) = self.ray(ndc);
        let hit = self.ring.hit(p, r);
        let q = hit.unwrap_or(DVec3::ZERO);
        match self.camera.project_uv(q) {
            Some(uv) => RoomSample {
                uv,
                weight: if hit.is_some() { edge_weight(uv) } else { 0.0 },
            },
            None => RoomSample {
                uv: DVec2::splat(0.5),
                weight: 0.0,
            },
        }
    }

    /// Is the water crossing of the texel at `ndc` on the water (inside the play area)?
    fn on_water(&self, ndc: DVec2) -> bool {
        let (p, r) = self.ray(ndc);
        let [ax, az, bx, bz] = self.water;
        r.y > 0.0 && p.x >= ax && p.x <= bx && p.z >= az && p.z <= bz
    }

    /// Corner (column, row) of a grid of `grid` cells, in NDC (row 0 at the top).
    fn corner(grid: [u32; 2], c: u32, r: u32) -> DVec2 {
        DVec2::new(
            2.0 * f64::from(c) / f64::from(grid[0]) - 1.0,
            1.0 - 2.0 * f64::from(r) / f64::from(grid[1]),
        )
    }

    /// The texel (i, j)'s centre in NDC on a texture of `texels`.
    pub fn texel_ndc(texels: [u32; 2], i: u32, j: u32) -> DVec2 {
        DVec2::new(
            2.0 * (f64::from(i) + 0.5) / f64::from(texels[0]) - 1.0,
            1.0 - 2.0 * (f64::from(j) + 0.5) / f64::from(texels[1]),
        )
    }

    /// The image points at the corners of a grid of `grid` cells, as the vertex stage
    /// computes them.
    pub fn grid_samples(&self, grid: [u32; 2]) -> GridSamples {
        let mut points = Vec::new();
        for r in 0..=grid[1] {
            for c in 0..=grid[0] {
                points.push(self.image_point(Self::corner(grid, c, r)));
            }
        }
        GridSamples { grid, points }
    }
}

/// A grid's corner image points ([`RoomView::grid_samples`]).
pub struct GridSamples {
    grid: [u32; 2],
    points: Vec<DVec3>,
}

impl GridSamples {
    /// The texel (i, j)'s sample as the grid gives it over a texture of `texels`: the corners'
    /// image points interpolated linearly over the cell's triangle, as the triangle strip of
    /// its row splits it (corners (c, r), (c, r + 1), (c + 1, r), then (c, r + 1), (c + 1, r),
    /// (c + 1, r + 1)), then `fs_main`'s uv and edge weight (0 behind the camera).
    pub fn at(&self, texels: [u32; 2], i: u32, j: u32) -> RoomSample {
        let grid = self.grid;
        let gx = (f64::from(i) + 0.5) * f64::from(grid[0]) / f64::from(texels[0]);
        let gy = (f64::from(j) + 0.5) * f64::from(grid[1]) / f64::from(texels[1]);
        let (c, r) = (
            (gx.floor() as u32).min(grid[0] - 1),
            (gy.floor() as u32).min(grid[1] - 1),
        );
        let (a, b) = (gx - f64::from(c), gy - f64::from(r));
        let index = |c: u32, r: u32| (r * (grid[0] + 1) + c) as usize;
        let [v0, v1, v2, v3] = [
            index(c, r),
            index(c, r + 1),
            index(c + 1, r),
            index(c + 1, r + 1),
        ]
        .map(|k| self.points[k]);
        let h = if a + b <= 1.0 {
            v0 + a * (v2 - v0) + b * (v1 - v0)
        } else {
            v3 + (1.0 - a) * (v1 - v3) + (1.0 - b) * (v2 - v3)
        };
        if h.z > 0.0 {
            let uv = DVec2::new(h.x / h.z, h.y / h.z);
            RoomSample {
                uv,
                weight: edge_weight(uv),
            }
        } else {
            RoomSample {
                uv: DVec2::splat(0.5),
                weight: 0.0,
            }
        }
    }
}

/// The grid's error against the per-texel map over the texels of one texture whose water
/// crossing lies on the water (the texels the water's pixels sample).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GridError {
    /// Largest |Δuv| in camera-image pixels where either weight is above 0 (elsewhere the
    /// image is not seen).
    pub uv_px: f64,
    /// The same over the texel's own footprint in the image (|Δuv| over the uv step to the
    /// next texel across): the error in texels of the reflection texture.
    pub uv_texels: f64,
    /// Largest |Δweight|.
    pub weight: f64,
    /// Texels on the water where either weight is above 0.
    pub seen: usize,
}

impl GridError {
    /// The worse of two, their texels added.
    pub fn max(self, o: GridError) -> GridError {
        GridError {
            uv_px: self.uv_px.max(o.uv_px),
            uv_texels: self.uv_texels.max(o.uv_texels),
            weight: self.weight.max(o.weight),
            seen: self.seen + o.seen,
        }
    }
}

/// The grid of cells at most `cell` texels a side against the per-texel map, every texel on
/// the water of a texture of `texels`.
pub fn interpolation_error(view: &RoomView, texels: [u32; 2], cell: u32) -> GridError {
    let grid = view.grid_samples(grid_of(texels, cell));
    let px = DVec2::new(view.camera.width, view.camera.height);
    let mut e = GridError::default();
    for j in 0..texels[1] {
        for i in 0..texels[0] {
            let ndc = RoomView::texel_ndc(texels, i, j);
            if !view.on_water(ndc) {
                continue;
            }
            let exact = view.sample(ndc);
            let value = grid.at(texels, i, j);
            e.weight = e.weight.max((value.weight - exact.weight).abs());
            if exact.weight > 0.0 || value.weight > 0.0 {
                e.seen += 1;
                let error = ((value.uv - exact.uv) * px).length();
                let next = view.sample(RoomView::texel_ndc(texels, i + 1, j));
                let footprint = ((next.uv - exact.uv) * px).length();
                e.uv_px = e.uv_px.max(error);
                e.uv_texels = e.uv_texels.max(error / footprint.max(1e-9));
            }
        }
    }
    e
}

/// A fixed-seed set of `n` phone views of a 1.0 m × 0.8 m water on a table (AR metres; the map
/// is the same at any scale): the phone 0.2–1.5 m above the water, pitched 15–85° down, at
/// any yaw, rolled up to ±45°, looking at a point of the water; a portrait screen of
/// `screen` pixels whose height spans the long side of a 1920×1080 landscape camera image
/// (focal length 1480 px, the sensor turned a quarter turn to the screen, as a phone held
/// upright has it); the ring 1.05 × the water's half diagonal
/// ([`crate::passes::ArConfig::ring_radius_for`]).
pub fn phone_views(n: usize, screen: [u32; 2]) -> Vec<RoomView> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        // xorshift64*
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    };
    let water = [-0.5, -0.4, 0.5, 0.4];
    let ring = Ring {
        centre: DVec2::ZERO,
        radius: 1.05 * 0.5 * DVec2::new(1.0, 0.8).length(),
    };
    let focal = 1480.0;
    let fov_y = 2.0 * (960.0f64 / focal).atan();
    (0..n)
        .map(|_| {
            let height = 0.2 + 1.3 * next();
            let pitch = (15.0 + 70.0 * next()).to_radians();
            let yaw = std::f64::consts::TAU * next();
            let roll = (90.0 * next() - 45.0).to_radians();
            let target = DVec3::new(-0.45 + 0.9 * next(), 0.0, -0.35 + 0.7 * next());
            let back = DVec3::new(yaw.cos(), 0.0, yaw.sin()) * (height / pitch.tan());
            let eye = target + back + DVec3::Y * height;
            let forward = (target - eye).normalize();
            let level_right = forward.cross(DVec3::Y).normalize();
            let level_up = level_right.cross(forward);
            let up = level_up * roll.cos() + level_right * roll.sin();
            let cam = render::Camera {
                eye,
                target,
                up,
                fov_y,
                near: 0.01,
                far: 100.0,
            };
            // The sensor's up is the screen's right: its long side along the screen's height.
            let screen_right = forward.cross(up).normalize();
            let camera = PinholeCamera {
                fx: focal,
                fy: focal,
                cx: 960.0,
                cy: 540.0,
                width: 1920.0,
                height: 1080.0,
                pose: glam::dcamera::rh::view::look_at_mat4(eye, target, screen_right).inverse(),
            };
            let aspect = f64::from(screen[0]) / f64::from(screen[1]);
            RoomView::new(&cam, aspect, ring, camera, water)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bound of [`ROOM_CELL_TEXELS`]'s grid over [`phone_views`] (24 views, the A54's
    /// 360 × 800 texture): the measured maximum, rounded up (docs/effects.md, "Reflection:
    /// the reflected room as a grid").
    const UV_BOUND_PX: f64 = 2.0;
    const UV_BOUND_TEXELS: f64 = 0.6;
    const WEIGHT_BOUND: f64 = 0.02;

    /// The OPPO A54's screen and its `ultra` reflection texture (half of each side).
    const SCREEN: [u32; 2] = [720, 1600];
    const TEXELS: [u32; 2] = [360, 800];

    #[test]
    fn the_grid_splits_the_texture_evenly_and_counts_its_strips() {
        assert_eq!(room_grid(TEXELS), [45, 100]);
        // Smaller textures get smaller cells: √(24/360) × 8 = 2.07 texels.
        assert_eq!(room_cell_texels([32, 24]), 2);
        assert_eq!(room_grid([32, 24]), [16, 12]);
        assert_eq!(room_cell_texels([180, 400]), 5);
        assert_eq!(room_cell_texels([1440, 2880]), 8);
        assert_eq!(room_grid([361, 1]), [361, 1]);
        // 100 strips of 46 column lines, two vertices each.
        assert_eq!(room_grid_vertices(TEXELS), 2 * 46 * 100);
    }

    #[test]
    fn the_reflected_ray_crosses_the_water_where_the_eyes_ray_does() {
        let view = &phone_views(3, SCREEN)[2];
        let ndc = DVec2::new(0.1, -0.3);
        let (p, r) = view.ray(ndc);
        assert!(p.y.abs() < 1e-12 && r.y > 0.0);
        // The eye's own ray through the same point reaches p: p − eye is along (r.x, −r.y, r.z).
        let d = (p - view.eye).normalize();
        assert!((d - DVec3::new(r.x, -r.y, r.z)).length() < 1e-12);
    }

    /// Choosing the cell: the error per cell size over the views (all four sizes printed
    /// with REGATTA_ROOM_CELLS=1 and `--nocapture`), and the chosen size's error asserted
    /// within the measured maximum over the 24 views (rounded up), which docs/effects.md
    /// states: a measured bound over this view set, not a derived one.
    #[test]
    fn the_grid_follows_the_per_texel_room_within_its_bound() {
        let views = phone_views(24, SCREEN);
        let mut chosen = GridError::default();
        for cell in [4, 8, 16, 32] {
            if cell != ROOM_CELL_TEXELS && std::env::var_os("REGATTA_ROOM_CELLS").is_none() {
                continue;
            }
            let e = views
                .iter()
                .map(|v| interpolation_error(v, TEXELS, cell))
                .fold(GridError::default(), GridError::max);
            eprintln!(
                "cell {cell}: worst |Δuv| {:.3} px of 1920×1080 ({:.3} of the texel's own \
                 footprint), worst |Δweight| {:.4}, over {} seen texels on the water",
                e.uv_px, e.uv_texels, e.weight, e.seen
            );
            if cell == ROOM_CELL_TEXELS {
                chosen = e;
            }
        }
        // The views see the room on the water (not all of them: looking steeply down, the
        // ring is out of the image).
        assert!(chosen.seen > 100_000, "{chosen:?}");
        assert!(chosen.uv_px < UV_BOUND_PX, "{chosen:?}");
        assert!(chosen.uv_texels < UV_BOUND_TEXELS, "{chosen:?}");
        assert!(chosen.weight < WEIGHT_BOUND, "{chosen:?}");
        // Smaller textures of the same screen (180 × 400 and 90 × 200), their cells shrunk by
        // room_cell_texels: within the same bound in texels of their own footprint.
        for (texels, screen) in [([180, 400], SCREEN), ([90, 200], SCREEN)] {
            let cell = room_cell_texels(texels);
            let e = phone_views(24, screen)
                .iter()
                .map(|v| interpolation_error(v, texels, cell))
                .fold(GridError::default(), GridError::max);
            eprintln!("{texels:?}, cell {cell}: {e:?}");
            assert!(e.uv_texels < UV_BOUND_TEXELS, "{texels:?}: {e:?}");
        }
    }

    /// A grid of twice the cell errs about four times as much: the error is linear
    /// interpolation's over a smooth map (h²/8 times its curvature), not a fault of the map.
    #[test]
    fn the_error_is_the_grids_curvature() {
        let views = phone_views(24, SCREEN);
        let at = |cell| {
            views
                .iter()
                .map(|v| interpolation_error(v, TEXELS, cell))
                .fold(GridError::default(), GridError::max)
        };
        let (fine, coarse) = (at(ROOM_CELL_TEXELS / 2), at(ROOM_CELL_TEXELS));
        let ratio = coarse.uv_px / fine.uv_px;
        assert!((2.5..6.0).contains(&ratio), "{fine:?} {coarse:?}");
    }
}
