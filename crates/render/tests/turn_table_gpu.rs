//! The table of one turn (`ocean::turn_table`, `render::turn_table::TurnTable`) sampled on a
//! real GPU (lavapipe in CI) as the wake kernel samples it (`turn_sin_cos`, shaders/ocean/
//! wake.wgsl: fract(u), then one linear look-up at level 0 in a compute stage), against the f64
//! sine and cosine of 2π·fract(u) within the bound any conforming GPU is held to
//! (`turn_table_error(..).total()`), and against the CPU mirror.

use ocean::turn_table::{TURN_TABLE_TEXELS, turn_sin_cos_f32, turn_table_error};

const KERNEL: &str = r#"
@group(0) @binding(10) var<storage, read> input: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&input) {
        return;
    }
    output[id.x] = vec4<f32>(turn_sin_cos(input[id.x].x), 0.0, 0.0);
}
"#;

#[test]
fn the_table_on_the_gpu_is_within_its_bound_of_sin_and_cos() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let n = TURN_TABLE_TEXELS as f32;
    // Every texel centre and every point halfway between two (the chord's worst), a wrap
    // from the last texel to the first, and phases of many turns as the kernels form them.
    let mut u: Vec<f32> = (0..2 * TURN_TABLE_TEXELS)
        .map(|i| i as f32 / (2.0 * n))
        .collect();
    u.extend([1.0 - 0.25 / n, 0.1 / n, 0.0]);
    u.extend((0..4096).map(|i| 0.5 + i as f32 * 0.193_7));
    let inputs: Vec<[f32; 4]> = u.iter().map(|&u| [u, 0.0, 0.0, 0.0]).collect();
    let table = render::turn_table::TurnTable::new(&gpu.device, &gpu.queue);
    // The core's prelude (WORKGROUP_SIZE), the wake file (turn_sin_cos) and the table at
    // group 0, bindings 0 and 1.
    let source = format!(
        "{}{}{}{KERNEL}",
        render::shader::prelude(),
        render::shader::wake(),
        ocean::wake::turn_table_bindings(0, 0)
    );
    let out = render::compute::run_kernel_in(
        &gpu,
        "turn table",
        &source,
        &inputs,
        16,
        &table.entries(0),
        &[],
    )
    .expect("the kernel runs");
    let got: &[[f32; 4]] = bytemuck::cast_slice(&out);
    let bound = turn_table_error(TURN_TABLE_TEXELS).total();
    let (mut worst, mut worst_mirror) = (0.0f64, 0.0f64);
    for (&u, g) in u.iter().zip(got) {
        let f = f64::from(u - u.floor());
        let (s, c) = (std::f64::consts::TAU * f).sin_cos();
        let mirror = turn_sin_cos_f32(u);
        for (k, want) in [s, c].into_iter().enumerate() {
            let err = (f64::from(g[k]) - want).abs();
            assert!(err <= bound, "u {u} component {k}: GPU {} vs {want}", g[k]);
            worst = worst.max(err);
            worst_mirror = worst_mirror.max(f64::from(g[k] - mirror[k]).abs());
        }
    }
    eprintln!(
        "{}: turn table vs f64 sin/cos, worst {worst:.3e} (bound {bound:.3e}); vs the CPU mirror {worst_mirror:.3e}",
        gpu.describe()
    );
    // The look-up reads the table: its values are sin and cos to far better than chance.
    assert!(worst < bound && worst > 0.0);
}
