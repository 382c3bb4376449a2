//! Segment layers (`shaders/render/segments.wgsl`): named lists of world-space segments, each
//! drawn by a pass of its own as screen-space capsules of a given pixel width, depth-tested
//! against the water and the boats and alpha-blended over them. A segment of length 0 is a
//! disc. Lines, ribbons (a run of segments, each end its own colour) and markers (discs) are
//! all segments.
//!
//! The renderer knows no meaning for a layer: the app names its layers and says what each
//! needs to run ([`LayerPass`]), fills each one's [`Layer`] through a [`SegmentLayers`] handle
//! before a frame (or says why it is hidden), and each pass plans from it: hidden (the app's
//! reason), nothing to draw, nothing in view, or run.

use std::sync::{Arc, Mutex, MutexGuard};

use glam::DVec3;

use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::Gpu;
use crate::gpu::upload;
use crate::renderer::Renderer;
use crate::shader;

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

/// What a layer draws this frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Layer {
    /// Not drawn, and the app's reason (the frame report prints it).
    Hidden(String),
    Draw(Vec<Segment>),
}

impl Default for Layer {
    fn default() -> Self {
        Layer::Hidden("no layer set yet".into())
    }
}

/// One segment pass as the frame report names it: `name` and what it
/// needs to run, both the app's words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LayerPass {
    pub name: &'static str,
    pub condition: &'static str,
}

#[derive(Debug, Default)]
struct Shared {
    /// Per pass name, its layer.
    layers: Vec<(&'static str, Layer)>,
    revision: u64,
}

impl Shared {
    fn slot(&mut self, name: &'static str) -> usize {
        match self.layers.iter().position(|(n, _)| *n == name) {
            Some(i) => i,
            None => {
                self.layers.push((name, Layer::default()));
                self.layers.len() - 1
            }
        }
    }
}

/// The app's side of the segment passes: it sets each layer, by its pass's name, before a frame.
#[derive(Debug, Clone, Default)]
pub struct SegmentLayers(Arc<Mutex<Shared>>);

impl SegmentLayers {
    fn lock(&self) -> MutexGuard<'_, Shared> {
        // A panic while holding the lock cannot leave a layer half-written (each is replaced
        // whole), so a poisoned lock is still good.
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Sets what the pass `name` draws; a change makes the next frame be drawn (not
    /// re-presented).
    pub fn set(&self, name: &'static str, layer: Layer) {
        let mut s = self.lock();
        let i = s.slot(name);
        if s.layers[i].1 != layer {
            s.layers[i].1 = layer;
            s.revision += 1;
        }
    }

    /// What the pass `name` draws (a layer never set is hidden).
    pub fn layer(&self, name: &str) -> Layer {
        self.lock()
            .layers
            .iter()
            .find(|(n, _)| *n == name)
            .map_or_else(Layer::default, |(_, l)| l.clone())
    }

    fn revision(&self) -> u64 {
        self.lock().revision
    }
}

/// Adds one segment pass per entry of `passes`, in that order, after the renderer's passes
/// (once: a renderer that has a pass of that name keeps it), each fed by `layers`. They draw
/// alike (one shader, one vertex layout, one blend), so they share one pipeline: compiled
/// once, not once per pass (on lavapipe each compilation is an LLVM JIT of its own).
pub fn add_segment_passes(
    renderer: &mut Renderer,
    gpu: &Gpu,
    layers: &SegmentLayers,
    passes: &[LayerPass],
) {
    let mut pipeline = None;
    for &spec in passes {
        if !renderer.has_pass(spec.name) {
            let pipeline = pipeline
                .get_or_insert_with(|| {
                    SegmentPass::pipeline(&gpu.device, renderer.frame_layout(), renderer.targets)
                })
                .clone();
            renderer.add_pass(Box::new(SegmentPass {
                spec,
                layers: layers.clone(),
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

pub struct SegmentPass {
    spec: LayerPass,
    layers: SegmentLayers,
    pipeline: wgpu::RenderPipeline,
    buffer: Option<wgpu::Buffer>,
    count: u32,
}

impl SegmentPass {
    /// The segment passes' pipeline: segments as instanced screen-space capsules,
    /// depth-tested, alpha-blended.
    fn pipeline(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        targets: Targets,
    ) -> wgpu::RenderPipeline {
        let module = shader::module(device, "segments", &[shader::SEGMENTS]);
        let attrs = wgpu::vertex_attr_array![
            0 => Float32x4, 1 => Float32x4, 2 => Float32x4, 3 => Float32x4
        ];
        crate::passes::render_pipeline(
            device,
            "segments",
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
                topology: wgpu::PrimitiveTopology::TriangleList,
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

impl Pass for SegmentPass {
    fn name(&self) -> &'static str {
        self.spec.name
    }
    fn condition(&self) -> &'static str {
        self.spec.condition
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        match self.layers.layer(self.spec.name) {
            Layer::Hidden(why) => Err(why),
            Layer::Draw(segments) => match Self::in_view(frame, &segments).count() {
                0 if segments.is_empty() => Err("nothing to draw".into()),
                0 => Err(format!("none of its {} segments in view", segments.len())),
                n => Ok(format!("{n} of {} segments in view", segments.len())),
            },
        }
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let Layer::Draw(segments) = self.layers.layer(self.spec.name) else {
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
        self.layers.revision()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_change_bumps_the_revision_and_the_same_layer_again_does_not() {
        let h = SegmentLayers::default();
        assert_eq!(
            h.layer("a"),
            Layer::default(),
            "a layer never set is hidden"
        );
        let r0 = h.revision();
        h.set("a", Layer::Hidden("why".into()));
        let r1 = h.revision();
        assert!(r1 > r0);
        h.set("a", Layer::Hidden("why".into()));
        assert_eq!(h.revision(), r1, "the same layer again changes nothing");
        let disc = Segment::disc(DVec3::ONE, [1.0; 4], 3.0);
        h.set("b", Layer::Draw(vec![disc]));
        assert!(h.revision() > r1);
        assert_eq!(h.layer("b"), Layer::Draw(vec![disc]));
        assert_eq!(
            h.layer("a"),
            Layer::Hidden("why".into()),
            "layers are kept by name"
        );
    }
}
