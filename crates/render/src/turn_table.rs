//! The GPU side of `ocean::turn_table`: the table of (sin 2πu, cos 2πu) over one turn as an
//! `Rg16Float` texture of `ocean::turn_table::TURN_TABLE_TEXELS` × 1 texels (8 KiB, uploaded
//! once) with a linear, repeating sampler, which the wake kernel (`shaders/ocean/wake.wgsl`,
//! `turn_sin_cos`) samples at fract(u) on the texture unit instead of reducing its phase and
//! taking sin and cos on the ALUs. Its error bound (`ocean::turn_table::turn_table_error`)
//! rests on the texture-filtering assumptions of [`crate::wgsl_accuracy`]; the tests below hold
//! ocean's copies of those constants (it sits below this crate) equal to this crate's.

use wgpu::util::DeviceExt;

use crate::gpu::layout;

/// The table's texture view and its sampler, as a bind group binds them.
pub struct TurnTable {
    pub view: wgpu::TextureView,
    pub sampler: wgpu::Sampler,
}

impl TurnTable {
    /// The table built on the CPU (`ocean::turn_table::turn_table_bytes`) and uploaded.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> TurnTable {
        let texture = device.create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some("turn table"),
                size: wgpu::Extent3d {
                    width: ocean::turn_table::TURN_TABLE_TEXELS,
                    height: 1,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rg16Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &ocean::turn_table::turn_table_bytes(),
        );
        // Linear between texel centres, wrapping from the last texel to the first (one turn).
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("turn table"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        TurnTable {
            view: texture.create_view(&Default::default()),
            sampler,
        }
    }

    /// Layout entries of the table at `binding` and its sampler at `binding + 1`, seen by
    /// `stages`.
    pub fn layout_entries(
        binding: u32,
        stages: wgpu::ShaderStages,
    ) -> [wgpu::BindGroupLayoutEntry; 2] {
        [
            layout::texture(binding, stages),
            layout::sampler(binding + 1, stages),
        ]
    }

    /// Bind group entries of the table at `binding` and its sampler at `binding + 1`.
    pub fn entries(&self, binding: u32) -> [wgpu::BindGroupEntry<'_>; 2] {
        [
            wgpu::BindGroupEntry {
                binding,
                resource: wgpu::BindingResource::TextureView(&self.view),
            },
            wgpu::BindGroupEntry {
                binding: binding + 1,
                resource: wgpu::BindingResource::Sampler(&self.sampler),
            },
        ]
    }
}

#[cfg(test)]
mod tests {
    use crate::wgsl_accuracy as wgsl;
    use ocean::turn_table as table;

    #[test]
    fn ocean_takes_the_filtering_assumptions_this_crate_states() {
        assert_eq!(
            table::SUB_TEXEL_PRECISION_BITS_MIN,
            wgsl::SUB_TEXEL_PRECISION_BITS_MIN
        );
        assert_eq!(table::WGSL_SIN_COS_ABSOLUTE, wgsl::SIN_COS_ABSOLUTE);
        // Half the f16 ULP of the values just below 1 (the largest below the exact 1.0).
        assert_eq!(
            table::HALF_FLOAT_ROUNDING_BELOW_ONE,
            wgsl::half_float_ulp(0.75) / 2.0
        );
        // The weight's snap: the whole step of wgsl_accuracy, over the texel difference.
        let e = table::turn_table_error(table::TURN_TABLE_TEXELS);
        let h = std::f64::consts::TAU / f64::from(table::TURN_TABLE_TEXELS);
        let snap = wgsl::sub_texel_snap_texels();
        assert_eq!(
            e.filtering,
            snap * (h + 2.0 * table::HALF_FLOAT_ROUNDING_BELOW_ONE)
        );
        // The filter's arithmetic in half floats: 1 ULP (as effects::flow_detail takes it).
        assert_eq!(e.filter_rounding, wgsl::half_float_ulp(0.75));
    }
}
