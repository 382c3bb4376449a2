//! The scene overlays (`shaders/overlay.wgsl`): one pass per overlay (labels' team rings,
//! trails, course, ahead/behind lines, wind), each a list of world-space segments drawn as
//! screen-space capsules of a given pixel width, depth-tested against the water and the boats
//! and alpha-blended over them. A segment of length 0 is a disc (a buoy seen from afar, a label
//! anchor).
//!
//! The renderer knows no race: the app fills each overlay's [`Layer`] through an
//! [`OverlayHandle`] before a frame (or says why the overlay is not drawn), and each pass plans
//! from it: off, nothing to draw (the app's reason, e.g. "no wind in the race"), nothing in
//! view, or run. The text of the labels is egui's, painted by the app after the frame.

use std::sync::{Arc, Mutex, MutexGuard};

use glam::DVec3;

use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::Gpu;
use crate::gpu::upload;
use crate::renderer::Renderer;
use crate::shader;

/// The overlays, in drawing order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OverlayKind {
    /// Boat labels: the GPU part is each boat's team-colour ring and the selected boats'
    /// highlight; the text is the app's (egui).
    Labels,
    Trails,
    Course,
    /// Ahead/behind lines across the current leg's axis.
    Lines,
    Wind,
}

impl OverlayKind {
    pub const ALL: [OverlayKind; 5] = [
        OverlayKind::Trails,
        OverlayKind::Course,
        OverlayKind::Lines,
        OverlayKind::Wind,
        OverlayKind::Labels,
    ];

    /// The name `--overlays` and the Effects panel use.
    pub fn name(self) -> &'static str {
        match self {
            OverlayKind::Labels => "labels",
            OverlayKind::Trails => "trails",
            OverlayKind::Course => "course",
            OverlayKind::Lines => "lines",
            OverlayKind::Wind => "wind",
        }
    }

    /// The pass's name in the frame report.
    pub fn pass_name(self) -> &'static str {
        match self {
            OverlayKind::Labels => "overlay-labels",
            OverlayKind::Trails => "overlay-trails",
            OverlayKind::Course => "overlay-course",
            OverlayKind::Lines => "overlay-lines",
            OverlayKind::Wind => "overlay-wind",
        }
    }

    pub fn from_name(name: &str) -> Option<OverlayKind> {
        OverlayKind::ALL.into_iter().find(|k| k.name() == name)
    }

    fn index(self) -> usize {
        match self {
            OverlayKind::Labels => 0,
            OverlayKind::Trails => 1,
            OverlayKind::Course => 2,
            OverlayKind::Lines => 3,
            OverlayKind::Wind => 4,
        }
    }

    fn condition(self) -> &'static str {
        match self {
            OverlayKind::Labels => "labels are on and a boat is in view",
            OverlayKind::Trails => "trails are on and a boat's recent track is in view",
            OverlayKind::Course => "the course is on, the race has marks and one is in view",
            OverlayKind::Lines => {
                "ahead/behind lines are on, the race has a course and a racing boat is in view"
            }
            OverlayKind::Wind => {
                "the wind indicator is on and the wind is known (race data or the sea)"
            }
        }
    }
}

/// One segment in world metres (x, y up, z south), `width_px` pixels wide on screen,
/// coloured linearly from `colour_a` to `colour_b` (linear RGB and alpha).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    pub a: DVec3,
    pub b: DVec3,
    pub colour_a: [f32; 4],
    pub colour_b: [f32; 4],
    pub width_px: f32,
}

impl Segment {
    /// A segment of one colour.
    pub fn line(a: DVec3, b: DVec3, colour: [f32; 4], width_px: f32) -> Segment {
        Segment {
            a,
            b,
            colour_a: colour,
            colour_b: colour,
            width_px,
        }
    }

    /// A disc `diameter_px` across at `p`.
    pub fn disc(p: DVec3, colour: [f32; 4], diameter_px: f32) -> Segment {
        Segment::line(p, p, colour, diameter_px)
    }
}

/// What an overlay draws this frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Layer {
    /// Turned off (`--overlays`, the Effects panel).
    #[default]
    Off,
    /// On, but the race gives it nothing to draw: the reason (e.g. "no wind in the race").
    Nothing(String),
    Draw(Vec<Segment>),
}

#[derive(Debug, Default)]
struct Shared {
    layers: [Layer; 5],
    revision: u64,
}

/// The app's side of the overlay passes: it sets each overlay's layer before a frame.
#[derive(Debug, Clone, Default)]
pub struct OverlayHandle(Arc<Mutex<Shared>>);

impl OverlayHandle {
    fn lock(&self) -> MutexGuard<'_, Shared> {
        // A panic while holding the lock cannot leave a layer half-written (each is replaced
        // whole), so a poisoned lock is still good.
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Sets what `kind` draws; a change makes the next frame be drawn (not re-presented).
    pub fn set(&self, kind: OverlayKind, layer: Layer) {
        let mut s = self.lock();
        if s.layers[kind.index()] != layer {
            s.layers[kind.index()] = layer;
            s.revision += 1;
        }
    }

    /// What `kind` draws.
    pub fn layer(&self, kind: OverlayKind) -> Layer {
        self.lock().layers[kind.index()].clone()
    }

    fn revision(&self) -> u64 {
        self.lock().revision
    }
}

/// Adds the five overlay passes after the renderer's passes (once: a renderer that has them
/// keeps them) and returns the handle that feeds them. The five draw alike (one shader, one
/// vertex layout, one blend), so they share one pipeline: compiled once, not five times (on
/// lavapipe each compilation is an LLVM JIT of its own).
pub fn add_overlay_passes(renderer: &mut Renderer, gpu: &Gpu, handle: &OverlayHandle) {
    let mut pipeline = None;
    for kind in OverlayKind::ALL {
        if !renderer.has_pass(kind.pass_name()) {
            let pipeline = pipeline
                .get_or_insert_with(|| {
                    OverlayPass::pipeline(&gpu.device, renderer.frame_layout(), renderer.targets)
                })
                .clone();
            renderer.add_pass(Box::new(OverlayPass {
                kind,
                handle: handle.clone(),
                pipeline,
                buffer: None,
                count: 0,
            }));
        }
    }
}

/// One segment as the shader reads it (local metres).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuSegment {
    a: [f32; 4],
    b: [f32; 4],
    colour_a: [f32; 4],
    colour_b: [f32; 4],
}

pub struct OverlayPass {
    kind: OverlayKind,
    handle: OverlayHandle,
    pipeline: wgpu::RenderPipeline,
    buffer: Option<wgpu::Buffer>,
    count: u32,
}

impl OverlayPass {
    /// The overlay passes' pipeline: segments as instanced screen-space capsules,
    /// depth-tested, alpha-blended.
    fn pipeline(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        targets: Targets,
    ) -> wgpu::RenderPipeline {
        let module = shader::module(device, "overlay", &[shader::OVERLAY]);
        let attrs = wgpu::vertex_attr_array![
            0 => Float32x4, 1 => Float32x4, 2 => Float32x4, 3 => Float32x4
        ];
        crate::passes::render_pipeline(
            device,
            "overlay",
            &module,
            &[Some(frame_layout)],
            targets,
            crate::passes::Raster {
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: size_of::<GpuSegment>() as u64,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &attrs,
                })],
                vertex: "vs_main",
                fragment: "fs_main",
                depth_write: false,
                depth_compare: wgpu::CompareFunction::LessEqual,
                cull: None,
                blend: Some(wgpu::BlendState::ALPHA_BLENDING),
            },
        )
    }

    /// The segments of this frame that can show: a bounding sphere in the view frustum.
    fn in_view<'a>(
        frame: &'a FrameContext,
        segments: &'a [Segment],
    ) -> impl Iterator<Item = &'a Segment> + 'a {
        segments.iter().filter(|s| {
            let centre = (s.a + s.b) / 2.0;
            frame.sphere_in_view(centre, (s.b - s.a).length() / 2.0 + 1e-3)
        })
    }
}

impl Pass for OverlayPass {
    fn name(&self) -> &'static str {
        self.kind.pass_name()
    }
    fn condition(&self) -> &'static str {
        self.kind.condition()
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        match self.handle.layer(self.kind) {
            Layer::Off => Err(format!(
                "turned off (\"{}\" not in --overlays)",
                self.kind.name()
            )),
            Layer::Nothing(why) => Err(why),
            Layer::Draw(segments) => match Self::in_view(frame, &segments).count() {
                0 if segments.is_empty() => Err("nothing to draw".into()),
                0 => Err(format!("none of its {} segments in view", segments.len())),
                n => Ok(format!("{n} of {} segments in view", segments.len())),
            },
        }
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let Layer::Draw(segments) = self.handle.layer(self.kind) else {
            self.count = 0;
            return;
        };
        let o = DVec3::new(frame.origin.x, 0.0, frame.origin.y);
        let local = |p: DVec3, w: f32| {
            let l = (p - o).as_vec3();
            [l.x, l.y, l.z, w]
        };
        let data: Vec<GpuSegment> = Self::in_view(frame, &segments)
            .map(|s| GpuSegment {
                a: local(s.a, s.width_px),
                b: local(s.b, 0.0),
                colour_a: s.colour_a,
                colour_b: s.colour_b,
            })
            .collect();
        upload(
            gpu,
            &mut self.buffer,
            wgpu::BufferUsages::VERTEX,
            bytemuck::cast_slice(&data),
        );
        self.count = data.len() as u32;
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        let Some(buffer) = &self.buffer else { return 0 };
        if self.count == 0 {
            return 0;
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_vertex_buffer(0, buffer.slice(..));
        pass.draw(0..6, 0..self.count);
        2 * u64::from(self.count)
    }
    fn revision(&self) -> u64 {
        self.handle.revision()
    }
}

/// The masthead of the boats pass's hull (`hull::boat`, length 1, bow along −z): where a boat's
/// label is anchored. Multiply by the drawn length.
pub const MASTHEAD: [f64; 3] = [0.0, 1.3, -0.12];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_masthead_is_the_hull_meshes_highest_point() {
        // Independent truth: the mesh the boats pass draws.
        let top = crate::hull::boat()
            .vertices
            .iter()
            .map(|v| v.position)
            .max_by(|a, b| a[1].total_cmp(&b[1]))
            .unwrap();
        for k in 0..3 {
            assert!((f64::from(top[k]) - MASTHEAD[k]).abs() < 0.02, "{top:?}");
        }
    }

    #[test]
    fn names_round_trip_and_a_change_bumps_the_revision() {
        for k in OverlayKind::ALL {
            assert_eq!(OverlayKind::from_name(k.name()), Some(k));
        }
        assert_eq!(OverlayKind::from_name("wakes"), None);
        let h = OverlayHandle::default();
        let r0 = h.revision();
        h.set(
            OverlayKind::Wind,
            Layer::Nothing("no wind in the race".into()),
        );
        let r1 = h.revision();
        assert!(r1 > r0);
        h.set(
            OverlayKind::Wind,
            Layer::Nothing("no wind in the race".into()),
        );
        assert_eq!(h.revision(), r1, "the same layer again changes nothing");
    }
}
