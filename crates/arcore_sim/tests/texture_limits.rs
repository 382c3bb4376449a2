//! Phone realities (issue 19): a phone's GPU may take textures no larger than 2048 or 4096
//! pixels a side (the OPPO A54's PowerVR GE8320 reports less than 8192). On a device made with
//! `wgpu::Limits::downlevel_defaults()` (2048) a full-size camera image, read through the FFI
//! with the device's limit, comes halved with its intrinsics, and its planes upload without a
//! validation error; the same upload at full size is refused (the cap is real).

mod common;

use ar::{FrameImage, FrameSource};
use camera_image::CameraImage;
use common::{Sim, granted, start};

fn capped_device() -> Option<(wgpu::Device, wgpu::Queue)> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle().with_env());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::default(),
        force_fallback_adapter: false,
        compatible_surface: None,
        apply_limit_buckets: false,
    }))
    .ok()?;
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("capped like a phone"),
        required_features: wgpu::Features::empty(),
        required_limits: wgpu::Limits::downlevel_defaults(),
        experimental_features: wgpu::ExperimentalFeatures::disabled(),
        memory_hints: wgpu::MemoryHints::Performance,
        trace: wgpu::Trace::Off,
    }))
    .ok()
}

/// Makes and fills the luma and chroma textures of `image` as the renderer's camera upload
/// does; the validation error, if any.
fn upload(device: &wgpu::Device, queue: &wgpu::Queue, image: &CameraImage) -> Option<String> {
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let CameraImage::Yuv420(p) = image else {
        panic!("ARCore's image is YUV")
    };
    let [cw, ch] = camera_image::Yuv420::chroma_size(p.width(), p.height());
    for (size, format, bytes, texel) in [
        (
            [p.width(), p.height()],
            wgpu::TextureFormat::R8Unorm,
            p.y(),
            1,
        ),
        ([cw, ch], wgpu::TextureFormat::Rg8Unorm, p.uv(), 2),
    ] {
        let extent = wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        };
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("camera plane"),
            size: extent,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        queue.write_texture(
            texture.as_image_copy(),
            bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(size[0] * texel),
                rows_per_image: Some(size[1]),
            },
            extent,
        );
    }
    pollster::block_on(scope.pop()).map(|e| e.to_string())
}

#[test]
fn a_full_size_camera_image_is_halved_to_fit_a_capped_gpu() {
    let Some((device, queue)) = capped_device() else {
        let required = std::env::var("REGATTA_REQUIRE_GPU").is_ok_and(|v| v == "true");
        assert!(!required, "REGATTA_REQUIRE_GPU=true but no GPU adapter");
        eprintln!("skipped: no GPU adapter");
        return;
    };
    let max = device.limits().max_texture_dimension_2d;
    assert_eq!(max, 2048, "the device has the downlevel cap");

    let sim = Sim::take();
    // A phone camera's full-size 4:3 image, wider than the cap.
    sim.set2_u32("RegattaSim_useSynth", 2560, 1920, 1);
    let (mut core, _jni) = sim.arcore(granted());
    start(&mut core);

    // Without the cap the image comes at full size, and the GPU refuses it.
    core.update();
    let full = core.next_frame().unwrap().unwrap();
    assert_eq!(full.image.size(), (2560, 1920));
    let refused = upload(&device, &queue, &full.image.to_camera_image().unwrap());
    assert!(
        refused.is_some(),
        "a 2560-wide texture on a 2048 device is refused"
    );

    core.set_max_image_side(max);
    core.update();
    let fitted = core.next_frame().unwrap().unwrap();
    assert_eq!(fitted.image.size(), (1280, 960));
    assert!(matches!(fitted.image, FrameImage::Yuv420 { .. }));
    // Intrinsics follow the image: half the focal length and principal point.
    let k = (full.intrinsics, fitted.intrinsics);
    assert!((k.1.fx - k.0.fx / 2.0).abs() < 1e-3 && (k.1.cx - k.0.cx / 2.0).abs() < 1e-3);
    let error = upload(&device, &queue, &fitted.image.to_camera_image().unwrap());
    assert_eq!(error, None);
}
