//! The boats pass (`shaders/boats.wgsl`): procedural hulls with sails and buoys, floating on
//! the analytic sea (height, pitch and roll from the surface under them, heading from the
//! race), instanced.

use glam::{DVec2, DVec3};

use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::{Gpu, upload};
use crate::hull::{self, MeshVertex};
use crate::passes::{PipelineSpec, pipeline};
use crate::scene::{float_matrix, float_pose};
use crate::shader;

/// Per-instance data: model matrix (local metres) and colour.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Instance {
    pub model: [[f32; 4]; 4],
    pub colour: [f32; 4],
}

/// The masthead of the boats pass's hull (`hull::boat`, length 1, bow along −z): where the app
/// anchors a boat's label. Multiply by the drawn length.
pub const MASTHEAD: [f64; 3] = [0.0, 1.3, -0.12];

/// Diameter of a course-mark buoy, metres.
pub const BUOY_DIAMETER: f64 = 2.0;
/// Colour of a course-mark buoy (linear RGB).
pub(crate) const BUOY_COLOUR: [f32; 3] = [0.9, 0.25, 0.02];

pub struct BoatsPass {
    pipeline: wgpu::RenderPipeline,
    meshes: [(wgpu::Buffer, u32); 2],
    instances: [Option<wgpu::Buffer>; 2],
    counts: [u32; 2],
}

impl BoatsPass {
    pub fn new(device: &wgpu::Device, frame_layout: &wgpu::BindGroupLayout, t: Targets) -> Self {
        use wgpu::util::DeviceExt;
        let module = shader::module(device, "boats", &[shader::BOATS]);
        let mesh_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Uint32];
        let inst_attrs = wgpu::vertex_attr_array![
            3 => Float32x4, 4 => Float32x4, 5 => Float32x4, 6 => Float32x4, 7 => Float32x4
        ];
        let spec = PipelineSpec {
            label: "boats",
            module: &module,
            buffers: &[
                Some(wgpu::VertexBufferLayout {
                    array_stride: size_of::<MeshVertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &mesh_attrs,
                }),
                Some(wgpu::VertexBufferLayout {
                    array_stride: size_of::<Instance>() as u64,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &inst_attrs,
                }),
            ],
            depth_write: true,
            depth_test: true,
            cull: None,
            extra_layouts: &[],
        };
        let mesh = |m: hull::Mesh| {
            let b = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("procedural mesh"),
                contents: bytemuck::cast_slice(&m.vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
            (b, m.vertices.len() as u32)
        };
        BoatsPass {
            pipeline: pipeline(device, frame_layout, t, spec),
            meshes: [mesh(hull::boat()), mesh(hull::buoy())],
            instances: [None, None],
            counts: [0, 0],
        }
    }

    /// The instances of a frame: boats, then buoys, each floated on the sea.
    pub(crate) fn instances(frame: &FrameContext) -> [Vec<Instance>; 2] {
        let s = frame.scene;
        let inst = |p: DVec2, heading: f64, length: f64, beam: f64, colour: [f32; 3]| {
            let pose = float_pose(&s.sea, s.t, p, heading, length, beam);
            let m = float_matrix(p, heading, &pose, frame.origin)
                * glam::DMat4::from_scale(DVec3::splat(length));
            Instance {
                model: m.as_mat4().to_cols_array_2d(),
                colour: [colour[0], colour[1], colour[2], 1.0],
            }
        };
        let boats = s
            .boats
            .iter()
            .filter(|b| frame.sphere_in_view(DVec3::new(b.position.x, 0.0, b.position.y), b.length))
            .map(|b| inst(b.position, b.heading, b.length, b.length * 0.32, b.colour))
            .collect();
        let marks = s
            .marks
            .iter()
            .filter(|m| {
                frame.sphere_in_view(DVec3::new(m.position.x, 0.0, m.position.y), BUOY_DIAMETER)
            })
            .map(|m| inst(m.position, 0.0, BUOY_DIAMETER, BUOY_DIAMETER, BUOY_COLOUR))
            .collect();
        [boats, marks]
    }
}

impl Pass for BoatsPass {
    fn name(&self) -> &'static str {
        "boats"
    }
    fn condition(&self) -> &'static str {
        "a boat or a course mark is inside the view frustum"
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        let s = frame.scene;
        let boats = s
            .boats
            .iter()
            .filter(|b| frame.sphere_in_view(DVec3::new(b.position.x, 0.0, b.position.y), b.length))
            .count();
        let marks = s
            .marks
            .iter()
            .filter(|m| {
                frame.sphere_in_view(DVec3::new(m.position.x, 0.0, m.position.y), BUOY_DIAMETER)
            })
            .count();
        if boats + marks > 0 {
            Ok(format!("{boats} boats and {marks} marks in view"))
        } else if s.boats.is_empty() && s.marks.is_empty() {
            Err("the scene has no boats and no marks".into())
        } else {
            Err("no boat or mark in view".into())
        }
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let [boats, marks] = Self::instances(frame);
        for (k, list) in [boats, marks].iter().enumerate() {
            upload(
                gpu,
                &mut self.instances[k],
                wgpu::BufferUsages::VERTEX,
                bytemuck::cast_slice(list),
            );
            self.counts[k] = list.len() as u32;
        }
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        pass.set_pipeline(&self.pipeline);
        let mut tris = 0;
        for k in 0..2 {
            let (Some(inst), n) = (&self.instances[k], self.counts[k]) else {
                continue;
            };
            if n == 0 {
                continue;
            }
            let (mesh, verts) = &self.meshes[k];
            pass.set_vertex_buffer(0, mesh.slice(..));
            pass.set_vertex_buffer(1, inst.slice(..));
            pass.draw(0..*verts, 0..n);
            tris += u64::from(verts / 3) * u64::from(n);
        }
        tris
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_masthead_is_the_hull_meshes_highest_point() {
        // Independent truth: the mesh the boats pass draws.
        let top = hull::boat()
            .vertices
            .iter()
            .map(|v| v.position)
            .max_by(|a, b| a[1].total_cmp(&b[1]))
            .unwrap();
        for k in 0..3 {
            assert!((f64::from(top[k]) - MASTHEAD[k]).abs() < 0.02, "{top:?}");
        }
    }
}
