//! GPU tests of the reflected room (`shaders/effects/reflection_room.wgsl`) on lavapipe,
//! skipped without an adapter unless `REGATTA_REQUIRE_GPU=true`: the texture's ray against
//! the mirrored f64 ray, and the grid pass's texels against the per-texel room, each texel
//! within a bound of its own: the grid's interpolation error (f64, exact for the texel) plus
//! what WGSL's accuracy lets a conforming GPU add (`render::wgsl_accuracy`, carried through
//! both shaders' arithmetic with [`Inexact`]), and two stated assumptions where WGSL and
//! Vulkan state nothing: the texture unit's (as `wgsl_accuracy` words it) and the
//! rasteriser's interpolation of a varying ([`INTERPOLATION_ULP`], [`VERTEX_SNAP_TEXELS`]).

use glam::{DMat4, DVec2, DVec3};
use wgpu::util::DeviceExt;

use crate::fixtures::{UV_IMAGE, uv_image};
use crate::passes::{EFFECTS_COMMON, EffectsUniform, REFLECTION, REFLECTION_ROOM};
use crate::reflection::grid::{RoomView, phone_views};
use crate::reflection::{Ring, room_grid};
use render::frame::FrameUniform;
use render::gpu::{Gpu, test_gpu};
use render::optics::{DepthRange, Plane, oblique_near_plane, reflection_matrix};
use render::wgsl_accuracy::{self as acc, Inexact};

/// Assumption (WGSL and Vulkan state no precision for it): a varying reaches a fragment as
/// its barycentric mix of the vertices' values to within this many f32 ULP of Σ λᵢ |vᵢ|.
const INTERPOLATION_ULP: f64 = 4.0;

/// Vulkan's least `subPixelPrecisionBits` (4): the rasteriser snaps a vertex to a grid of
/// 1/16 texel. Assumption (Vulkan leaves the rounding to the implementation): it snaps to the
/// nearest point of that grid, so a corner computed within 1/32 texel of a whole texel (the
/// grids here put every corner on one: the textures' sides are whole numbers of cells) lands
/// on it exactly; one farther off may move by up to 1/16 texel.
const VERTEX_SNAP_TEXELS: f64 = 1.0 / 16.0;

/// The reflection pass's view-projection for `cam` on a texture of aspect `aspect`: view ×
/// reflection matrix with the near plane moved onto the water, as `prepare_reflection` makes it.
fn reflected_view_proj(cam: &render::Camera, aspect: f64) -> DMat4 {
    let view = cam.view_local(DVec2::ZERO);
    let water = Plane::horizontal(0.0);
    let refl_view = view * reflection_matrix(&water);
    let proj = glam::dcamera::rh::proj::directx::perspective(cam.fov_y, aspect, cam.near, cam.far);
    oblique_near_plane(proj, &water.transformed(refl_view), DepthRange::ZeroToOne)
        .expect("the eye is above the water")
        * refl_view
}

/// A value the GPU gets as its f32.
fn input(v: f64) -> Inexact {
    Inexact::input(v, v as f32)
}

/// What the shaders read, as the GPU holds it (each f64 reference rounded to f32).
struct Inputs {
    /// inv_view_proj's columns.
    inv: [[Inexact; 4]; 4],
    /// The mirrored eye.
    eye: [Inexact; 3],
    /// camera_projection's columns (rows 0–2).
    projection: [[Inexact; 3]; 4],
    centre: [Inexact; 2],
    radius: Inexact,
}

impl Inputs {
    fn of(inv: DMat4, view: &RoomView) -> Inputs {
        let image = view
            .camera
            .image_projection(view.camera.pose.inverse())
            .to_cols_array_2d();
        Inputs {
            inv: inv.to_cols_array_2d().map(|c| c.map(input)),
            eye: [view.eye.x, -view.eye.y, view.eye.z].map(input),
            projection: image.map(|c| [c[0], c[1], c[2]].map(input)),
            centre: view.ring.centre.to_array().map(input),
            radius: input(view.ring.radius),
        }
    }

    /// `room_ray(ndc)`.
    fn room_ray(&self, ndc: [Inexact; 2]) -> [Inexact; 3] {
        let x = [ndc[0], ndc[1], Inexact::exact(0.5)];
        let far: Vec<Inexact> = (0..4)
            .map(|i| {
                acc::sum(&[
                    self.inv[0][i] * x[0],
                    self.inv[1][i] * x[1],
                    self.inv[2][i] * x[2],
                    self.inv[3][i],
                ])
            })
            .collect();
        [0, 1, 2].map(|i| far[i] - self.eye[i] * far[3])
    }

    /// The ring point's homogeneous image point for the unit direction `r`: with `vertex`,
    /// `room_image_point` (the exit root taken wherever the ray rises: a and k clamped, no
    /// test of the root's sign); without, `camera_uv(ring_hit(..))`'s before its division
    /// (which needs the ray to meet the ring ahead: k > 0, a > 10⁻⁸, the root > 0; where it
    /// does both compute the same). `None` where a conforming GPU may decide a test either way
    /// or the per-texel room meets no ring point.
    fn image_point(&self, r: [Inexact; 3], vertex: bool) -> Option<Option<[Inexact; 3]>> {
        let rises = r[1].above(1e-6)?;
        if !rises {
            // The vertex stage's horizon (r.y ≤ 0 decided here only from 10⁻⁶ down: between,
            // undecided) and the per-texel room's miss.
            return match (vertex, r[1].above(0.0)) {
                (true, Some(false)) => Some(Some([0.0, 0.0, -1.0].map(Inexact::exact))),
                (false, _) => Some(None),
                _ => None,
            };
        }
        let s = -self.eye[1] / r[1];
        let p = acc::add3(self.eye, acc::scale3(s, r));
        let o = [p[0] - self.centre[0], p[2] - self.centre[1]];
        let d = [r[0], r[2]];
        let a = acc::dot(&d, &d);
        let b = acc::dot(&o, &d);
        let k = b * b - a * (acc::dot(&o, &o) - self.radius * self.radius);
        let t = if vertex {
            (-b + k.max(Inexact::exact(0.0)).sqrt()) / a.max(Inexact::exact(1e-8))
        } else {
            let (Some(wide), Some(meets)) = (a.above(1e-8), k.above(0.0)) else {
                return None;
            };
            if !(wide && meets) {
                return Some(None);
            }
            let t = (-b + k.sqrt()) / a;
            match t.above(0.0) {
                None => return None,
                Some(false) => return Some(None),
                Some(true) => t,
            }
        };
        let q = acc::add3(p, acc::scale3(t, r));
        Some(Some([0, 1, 2].map(|i| {
            acc::sum(&[
                self.projection[0][i] * q[0],
                self.projection[1][i] * q[1],
                self.projection[2][i] * q[2],
                self.projection[3][i],
            ])
        })))
    }
}

/// `edge_weight(uv)`: 1 − (max-norm distance outside the image) / EDGE_FADE, clamped.
fn edge_weight(uv: [Inexact; 2]) -> Inexact {
    let one = Inexact::exact(1.0);
    let outside = uv.map(|c| (-c).max(c - one));
    (one - outside[0].max(outside[1]) / input(crate::refraction::EDGE_FADE)).clamp(0.0, 1.0)
}

/// `sky_above(r.y)` (the room shaders' sky with the sun's weight 0, for r.y > 0).
fn sky(r: [Inexact; 3]) -> [Inexact; 3] {
    let t = r[1].pow(input(0.45));
    let (horizon, zenith) = ([0.62, 0.74, 0.86], [0.10, 0.28, 0.62]);
    [0, 1, 2].map(|c| acc::mix(input(horizon[c]), input(zenith[c]), t))
}

/// The colour the uv image gives at `uv` (blue: none), with what the texture unit may add:
/// the filter's weight snapped to Vulkan's least sub-texel precision and the result held in
/// half floats (`render::wgsl_accuracy`'s assumption).
fn image_colour(uv: [Inexact; 2]) -> [Inexact; 3] {
    let half = 0.5 / f64::from(UV_IMAGE);
    let c = |u: Inexact| {
        let v = u.value.clamp(half, 1.0 - half);
        Inexact {
            value: v,
            error: u.error
                + acc::sub_texel_snap_texels() / f64::from(UV_IMAGE)
                + acc::half_float_ulp(v),
        }
    };
    [c(uv[0]), c(uv[1]), Inexact::exact(0.0)]
}

/// `mix(sky, sample_camera(uv), w)` with uv = h.xy / h.z and w its edge weight where h.z > 0;
/// the sky alone (mix with weight 0 returns it exactly) where h.z ≤ 0 or there is no image
/// point; `None` where a conforming GPU may decide h.z's sign either way.
fn texel_colour(r: [Inexact; 3], h: Option<[Inexact; 3]>) -> Option<[Inexact; 3]> {
    let s = sky(r);
    let Some(h) = h else { return Some(s) };
    if !h[2].above(0.0)? {
        return Some(s);
    }
    let uv = [h[0] / h[2], h[1] / h[2]];
    let (img, w) = (image_colour(uv), edge_weight(uv));
    Some([0, 1, 2].map(|c| acc::mix(s[c], img[c], w)))
}

/// A varying at a fragment: the barycentric mix `weights` of `values`, with the
/// interpolation's assumed rounding, and `snap`: the most the rasteriser moved a vertex
/// (texels) over a cell `cell` texels a side, which moves a barycentric weight by at most
/// 2·snap/cell per vertex (0 where every vertex stayed).
fn interpolate(values: &[[Inexact; 3]], weights: &[f64], snap: f64, cell: f64) -> [Inexact; 3] {
    [0, 1, 2].map(|c| {
        let value: f64 = values
            .iter()
            .zip(weights)
            .map(|(v, w)| v[c].value * w)
            .sum();
        let carried: f64 = values
            .iter()
            .zip(weights)
            .map(|(v, w)| v[c].error * w.abs())
            .sum();
        let size: f64 = values
            .iter()
            .zip(weights)
            .map(|(v, w)| v[c].magnitude() * w.abs())
            .sum();
        let spread = values
            .iter()
            .map(|v| (v[c].value - value).abs())
            .fold(0.0, f64::max);
        let moved = values.len() as f64 * 2.0 * snap / cell * spread;
        Inexact {
            value,
            error: carried + INTERPOLATION_ULP * acc::ulp(size) + moved,
        }
    })
}

/// The per-texel room as the pass drew it before the grid (its ray corrected as `room_ray`
/// explains): a full-screen triangle, every texel the whole map.
const PER_TEXEL_ROOM: &str = r#"
struct TexelOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ray: vec3<f32>,
}

@vertex
fn vs_texel(@builtin(vertex_index) i: u32) -> TexelOut {
    let xy = full_screen_xy(i);
    var out: TexelOut;
    out.clip = vec4<f32>(xy, 1.0, 1.0);
    out.ray = room_ray(xy);
    return out;
}

@fragment
fn fs_texel(in: TexelOut) -> @location(0) vec4<f32> {
    let r = normalize(in.ray);
    let eye = frame.eye.xyz;
    let s = -eye.y / max(r.y, 1e-6);
    let ring = ring_hit(eye + r * s, r);
    let uv = camera_uv(ring.xyz);
    let w = select(0.0, edge_weight(uv.xy) * uv.z, ring.w > 0.0);
    return vec4<f32>(mix(sky_colour_texel(r), sample_camera(uv.xy), w), 1.0);
}
"#;

/// One view drawn both ways into `texels`: the grid pass (its grid `grid`) and the per-texel
/// room, RGBA f32 per texel each.
fn draw_both(
    gpu: &Gpu,
    view: &RoomView,
    texels: [u32; 2],
    grid: [u32; 2],
) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let device = &gpu.device;
    let aspect = f64::from(texels[0]) / f64::from(texels[1]);
    let vp = reflected_view_proj(&view.render, aspect);
    let mut frame: FrameUniform = bytemuck::Zeroable::zeroed();
    frame.view_proj = vp.as_mat4().to_cols_array_2d();
    frame.inv_view_proj = vp.inverse().as_mat4().to_cols_array_2d();
    frame.eye = [
        view.eye.x as f32,
        -view.eye.y as f32,
        view.eye.z as f32,
        0.0,
    ];
    // The sun 35° up, its weight 0: the sky alone (its lobes have their own test).
    frame.sun = [0.3, 0.574, -0.76, 0.0];
    let mut fx: EffectsUniform = bytemuck::Zeroable::zeroed();
    fx.camera_projection = view
        .camera
        .image_projection(view.camera.pose.inverse())
        .as_mat4()
        .to_cols_array_2d();
    fx.table = [
        0.0,
        view.ring.radius as f32,
        view.ring.centre.x as f32,
        view.ring.centre.y as f32,
    ];
    fx.flags = [0, 0, grid[0], grid[1]];
    let buffer = |label, bytes: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage: wgpu::BufferUsages::UNIFORM,
        })
    };
    let (frame_buffer, fx_buffer) = (
        buffer("frame", bytemuck::bytes_of(&frame)),
        buffer("effects", bytemuck::bytes_of(&fx)),
    );
    let image = uv_image(gpu).create_view(&Default::default());
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let src = crate::wgsl::source(&[EFFECTS_COMMON, REFLECTION, REFLECTION_ROOM, PER_TEXEL_ROOM]);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("room"),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let format = wgpu::TextureFormat::Rgba32Float;
    let draw = |vs: &str, fs: &str, topology, vertices: u32, instances: u32| {
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(vs),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(vs),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState {
                topology,
                ..Default::default()
            },
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(fs),
                compilation_options: Default::default(),
                targets: &[Some(format.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let group = |i: u32, entries: &[wgpu::BindGroupEntry]| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout: &pipeline.get_bind_group_layout(i),
                entries,
            })
        };
        let groups = [
            group(
                0,
                &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: frame_buffer.as_entire_binding(),
                }],
            ),
            group(1, &[]),
            group(
                2,
                &crate::fixtures::camera_entries(&fx_buffer, &image, &sampler),
            ),
        ];
        let target = render::gpu::texture_2d(
            device,
            "room",
            texels,
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let view = target.create_view(&Default::default());
            let mut pass =
                render::gpu::colour_pass(&mut enc, "room", &view, wgpu::Color::BLACK, None);
            pass.set_pipeline(&pipeline);
            for (i, g) in groups.iter().enumerate() {
                pass.set_bind_group(i as u32, g, &[]);
            }
            pass.draw(0..vertices, 0..instances);
        }
        gpu.queue.submit([enc.finish()]);
        let bytes = gpu.read_texture_bytes(&target, 16).expect("read back");
        bytemuck::cast_slice::<u8, [f32; 4]>(&bytes).to_vec()
    };
    let strips = draw(
        "vs_main",
        "fs_main",
        wgpu::PrimitiveTopology::TriangleStrip,
        2 * (grid[0] + 1),
        grid[1],
    );
    let per_texel = draw(
        "vs_texel",
        "fs_texel",
        wgpu::PrimitiveTopology::TriangleList,
        3,
        1,
    );
    (strips, per_texel)
}

/// The grid pass against the per-texel room over one view: every texel whose water crossing
/// lies on the water and whose cell rises above the horizon at all four corners, each within
/// its own bound (the exact difference of the two maps' colours, f64, plus both GPUs'
/// allowances). The largest error, the largest error over its bound, the texels checked,
/// those where the two maps' colours differ at all in the image's channels (red, green), and
/// those a conforming GPU may decide either way.
#[derive(Debug, Default)]
struct Comparison {
    worst: f64,
    ratio: f64,
    checked: usize,
    differ: usize,
    undecided: usize,
}

fn compare(gpu: &Gpu, view: &RoomView, texels: [u32; 2], gpu_grid: [u32; 2]) -> Comparison {
    let grid = room_grid(texels);
    let (strips, per_texel) = draw_both(gpu, view, texels, gpu_grid);
    let aspect = f64::from(texels[0]) / f64::from(texels[1]);
    let inputs = Inputs::of(reflected_view_proj(&view.render, aspect).inverse(), view);
    let cell = f64::from(texels[0]) / f64::from(grid[0]);
    // Each corner's ray and image point as the vertex stage computes them: ndc from the
    // corner's f32 fraction of the grid.
    let corner = |c: u32, r: u32| {
        let fraction = |k: u32, n: u32| Inexact::exact(f64::from(k)) / Inexact::exact(f64::from(n));
        let two = Inexact::exact(2.0);
        let one = Inexact::exact(1.0);
        let ndc = [
            two * fraction(c, grid[0]) - one,
            one - two * fraction(r, grid[1]),
        ];
        // How far the rasteriser may put the corner from its whole texel.
        let off =
            (ndc[0].error * f64::from(texels[0])).max(ndc[1].error * f64::from(texels[1])) / 2.0;
        let snap = if off < VERTEX_SNAP_TEXELS / 2.0 {
            0.0
        } else {
            off + VERTEX_SNAP_TEXELS
        };
        let ray = inputs.room_ray(ndc);
        let point = inputs.image_point(acc::normalize(ray), true).flatten();
        (ray, point, snap)
    };
    let mut corners = Vec::new();
    for r in 0..=grid[1] {
        for c in 0..=grid[0] {
            corners.push(corner(c, r));
        }
    }
    // The full-screen triangle's corners for the per-texel room.
    let screen = [[-1.0, -1.0], [3.0, -1.0], [-1.0, 3.0]]
        .map(|[x, y]| inputs.room_ray([Inexact::exact(x), Inexact::exact(y)]));
    let mut e = Comparison::default();
    for j in 0..texels[1] {
        for i in 0..texels[0] {
            let ndc = RoomView::texel_ndc(texels, i, j);
            let (p, r) = view.ray(ndc);
            let [ax, az, bx, bz] = view.water;
            if !(r.y > 0.0 && p.x >= ax && p.x <= bx && p.z >= az && p.z <= bz) {
                continue;
            }
            // The grid: the strip's triangle of the texel's cell.
            let gx = (f64::from(i) + 0.5) * f64::from(grid[0]) / f64::from(texels[0]);
            let gy = (f64::from(j) + 0.5) * f64::from(grid[1]) / f64::from(texels[1]);
            let (c, rw) = (gx.floor() as u32, gy.floor() as u32);
            let (a, b) = (gx - f64::from(c), gy - f64::from(rw));
            let at = |c: u32, r: u32| &corners[(r * (grid[0] + 1) + c) as usize];
            let (tri, weights) = if a + b <= 1.0 {
                (
                    [at(c, rw), at(c + 1, rw), at(c, rw + 1)],
                    [1.0 - a - b, a, b],
                )
            } else {
                (
                    [at(c + 1, rw + 1), at(c, rw + 1), at(c + 1, rw)],
                    [a + b - 1.0, 1.0 - a, 1.0 - b],
                )
            };
            let Some(points) = tri
                .iter()
                .map(|(_, h, _)| *h)
                .collect::<Option<Vec<[Inexact; 3]>>>()
            else {
                e.undecided += 1;
                continue;
            };
            let rays: Vec<[Inexact; 3]> = tri.iter().map(|(ray, _, _)| *ray).collect();
            let snap = tri.iter().map(|(_, _, s)| *s).fold(0.0, f64::max);
            let grid_ray = acc::normalize(interpolate(&rays, &weights, snap, cell));
            let grid_h = interpolate(&points, &weights, snap, cell);
            // The per-texel room: the full-screen triangle's barycentrics of the texel.
            let (l1, l2) = ((ndc.x + 1.0) / 4.0, (ndc.y + 1.0) / 4.0);
            // Its corners are whole texels (0 and twice the side) computed exactly.
            let texel_ray =
                acc::normalize(interpolate(&screen, &[1.0 - l1 - l2, l1, l2], 0.0, 1.0));
            let (Some(new), Some(old)) = (
                texel_colour(grid_ray, Some(grid_h)),
                inputs
                    .image_point(texel_ray, false)
                    .and_then(|h| texel_colour(texel_ray, h)),
            ) else {
                e.undecided += 1;
                continue;
            };
            e.checked += 1;
            let k = (j * texels[0] + i) as usize;
            let (got_new, got_old) = (strips[k], per_texel[k]);
            let mut seen = false;
            for ch in 0..3 {
                let error = f64::from(got_new[ch] - got_old[ch]).abs();
                let bound = (new[ch].value - old[ch].value).abs() + new[ch].error + old[ch].error;
                e.worst = e.worst.max(error);
                e.ratio = e.ratio.max(error / bound);
                seen |= ch < 2 && (new[ch].value - old[ch].value).abs() > 0.0;
            }
            e.differ += usize::from(seen);
        }
    }
    e
}

/// Phone views at `texels` whose water shows the room (looking steeply down it does not).
fn views_showing_the_room(texels: [u32; 2]) -> Vec<RoomView> {
    let screen = [720, 1600];
    phone_views(24, screen)
        .into_iter()
        .filter(|v| crate::reflection::grid::interpolation_error(v, texels, 8).seen > 2000)
        .take(3)
        .collect()
}

#[test]
fn the_grid_room_matches_the_per_texel_room() {
    let Some(gpu) = test_gpu() else { return };
    let texels = [180, 400];
    let views = views_showing_the_room(texels);
    assert_eq!(views.len(), 3);
    for view in &views {
        let e = compare(&gpu, view, texels, room_grid(texels));
        eprintln!("grid room against the per-texel room, {texels:?}: {e:?}");
        // Every texel within its bound, and few a conforming GPU may decide otherwise.
        assert!(e.ratio <= 1.0, "{e:?}");
        assert!(e.checked > 5000 && e.undecided * 100 < e.checked, "{e:?}");
    }
}

#[test]
fn a_coarser_grid_on_the_gpu_fails_the_room_comparison() {
    // The same check with the GPU given half the columns the bound's grid has: its texels
    // leave their bounds (four times over on lavapipe: cells twice as wide err four times
    // as much, and the allowances are small beside the grid's own error).
    let Some(gpu) = test_gpu() else { return };
    let texels = [180, 400];
    let view = &views_showing_the_room(texels)[0];
    let [cols, rows] = room_grid(texels);
    let e = compare(&gpu, view, texels, [cols / 2, rows]);
    eprintln!("a coarser grid: {e:?}");
    assert!(e.ratio > 2.0, "{e:?}");
}

/// The demo table scene's view (the golden images'), its texture's aspect 4:3.
fn demo_view() -> RoomView {
    let scene = crate::demo_table_scene(40.0);
    let camera = crate::fixtures::test_camera(DMat4::IDENTITY);
    let ring = Ring {
        centre: DVec2::ZERO,
        radius: 44.5,
    };
    RoomView::new(&scene.camera, 4.0 / 3.0, ring, camera, scene.play_area)
}

#[test]
fn the_room_ray_is_the_texels_mirrored_ray() {
    // `room_ray` against the mirrored f64 ray through the same screen point, over the demo
    // view (the oblique projection's z = ½ plane passes behind the eye across its far water)
    // and the phone views. It used to be multiplied by far.w: that formula, evaluated here in
    // f64, turns a band of the demo view's rays around (the check below fails on it).
    let Some(gpu) = test_gpu() else { return };
    let mut views = vec![(demo_view(), 4.0 / 3.0)];
    views.extend(phone_views(6, [720, 1600]).into_iter().map(|v| (v, 0.45)));
    let ndcs: Vec<[f32; 4]> = (0..41 * 41)
        .map(|k| {
            let (i, j) = (k % 41, k / 41);
            [-1.0 + 0.05 * i as f32, -1.0 + 0.05 * j as f32, 0.0, 0.0]
        })
        .collect();
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        output[id.x] = vec4<f32>(normalize(room_ray(input[id.x].xy)), 0.0);
    }
}
"#;
    let src = crate::wgsl::source(&[EFFECTS_COMMON, REFLECTION, REFLECTION_ROOM, kernel]);
    let mut turned_by_the_old_formula = 0;
    for (view, aspect) in &views {
        let vp = reflected_view_proj(&view.render, *aspect);
        let inv = vp.inverse();
        let mut frame: FrameUniform = bytemuck::Zeroable::zeroed();
        frame.inv_view_proj = inv.as_mat4().to_cols_array_2d();
        frame.eye = [
            view.eye.x as f32,
            -view.eye.y as f32,
            view.eye.z as f32,
            0.0,
        ];
        let frame_buffer = crate::fixtures::frame_buffer(&gpu, &frame);
        let bytes = render::compute::run_kernel_in(
            &gpu,
            "room ray",
            &src,
            &ndcs,
            16,
            &[wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buffer.as_entire_binding(),
            }],
            &[],
        )
        .expect("the kernel runs");
        let got: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
        let inputs = Inputs::of(inv, view);
        let mirrored_eye = DVec3::new(view.eye.x, -view.eye.y, view.eye.z);
        for (g, n) in got.iter().zip(&ndcs) {
            let ndc = DVec2::new(f64::from(n[0]), f64::from(n[1]));
            let want = view.ray(ndc).1;
            let bound = acc::normalize(inputs.room_ray([Inexact::of(n[0]), Inexact::of(n[1])]));
            for c in 0..3 {
                assert!((bound[c].value - want[c]).abs() < 1e-9, "{ndc} {want}");
                let error = (f64::from(g[c]) - want[c]).abs();
                assert!(error <= bound[c].error, "{ndc}: {g:?} against {want}");
            }
            let far = inv * glam::DVec4::new(ndc.x, ndc.y, 0.5, 1.0);
            let old = (far.truncate() - mirrored_eye * far.w) * far.w;
            turned_by_the_old_formula += usize::from(old.dot(want) < 0.0);
        }
    }
    assert!(
        turned_by_the_old_formula > 100,
        "{turned_by_the_old_formula}"
    );
}
