//! Test fixtures shared by the crate's own GPU tests and its integration tests (not an API).

use glam::{DMat4, DVec2};
use wgpu::util::DeviceExt;

/// Texels per side of the uv image, whose texel (i, j) holds its own centre's uv:
/// ((i + ½)/N, (j + ½)/N) in red and green. Filtered linearly (clamped to the edge) it returns
/// the uv it is sampled at, kept to the texel centres' range, so the colour a shader returns is
/// the point it sampled. (2i + 1)/2N has 11 significant bits: exact in a half float.
pub const UV_IMAGE: u32 = 1024;

/// What the uv image shows at `uv`.
pub fn uv_image_at(uv: DVec2) -> DVec2 {
    let half = 0.5 / f64::from(UV_IMAGE);
    uv.clamp(DVec2::splat(half), DVec2::splat(1.0 - half))
}

/// The uv image as an `Rg16Float` texture (a camera image for the effects' bindings).
pub fn uv_image(gpu: &render::gpu::Gpu) -> wgpu::Texture {
    let n = UV_IMAGE;
    // The half float of a texel centre, which holds it exactly.
    let exact_half = |v: f32| {
        let h = half::f16::from_f32(v);
        assert_eq!(
            h.to_f32(),
            v,
            "a texel centre must be exact in a half float"
        );
        h.to_bits()
    };
    let texels: Vec<u16> = (0..n * n)
        .flat_map(|k| {
            let centre = |i: u32| (2 * i + 1) as f32 / (2 * n) as f32;
            [exact_half(centre(k % n)), exact_half(centre(k / n))]
        })
        .collect();
    gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("uv image"),
            size: wgpu::Extent3d {
                width: n,
                height: n,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rg16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&texels),
    )
}

/// A uniform buffer holding `frame` (bind group 0's first binding, for test kernels).
pub fn frame_buffer(gpu: &render::gpu::Gpu, frame: &render::frame::FrameUniform) -> wgpu::Buffer {
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("frame"),
            contents: bytemuck::bytes_of(frame),
            usage: wgpu::BufferUsages::UNIFORM,
        })
}

/// Bindings 0, 1 and 4 of the effects' group 2: their uniform, the camera image and its
/// sampler (what a test of a camera-sampling shader binds).
pub fn camera_entries<'a>(
    uniform: &'a wgpu::Buffer,
    image: &'a wgpu::TextureView,
    sampler: &'a wgpu::Sampler,
) -> [wgpu::BindGroupEntry<'a>; 3] {
    [
        wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 1,
            resource: wgpu::BindingResource::TextureView(image),
        },
        wgpu::BindGroupEntry {
            binding: 4,
            resource: wgpu::BindingResource::Sampler(sampler),
        },
    ]
}

/// The effects' test camera: a 640×480 px image, focal length 500 px, principal point at the
/// centre, at `pose` (camera to world).
pub fn test_camera(pose: DMat4) -> render::optics::PinholeCamera {
    render::optics::PinholeCamera {
        fx: 500.0,
        fy: 500.0,
        cx: 320.0,
        cy: 240.0,
        width: 640.0,
        height: 480.0,
        pose,
    }
}
