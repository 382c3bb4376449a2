//! f32-safe wave inputs for a GPU.
//!
//! A shader evaluates θ = k D·p + θ0 at a *local* point p = x0 − o, where o is a local origin
//! near the camera (a few hundred metres at most from anything drawn) and
//! θ0 = (k D·o − ω t + φ) mod 2π is reduced here in f64. So the shader never sees an absolute
//! race time or a large coordinate, and every argument of sin/cos it computes is bounded by
//! k |p| + 2π. Phone GPUs lose accuracy on large sin() arguments; lavapipe does not, so the
//! tests assert the bound on θ0 rather than trusting a desktop render.

use std::f64::consts::TAU;

use crate::WaveSet;

/// Reduce an angle to [0, 2π) in f64.
pub fn reduce_phase(theta: f64) -> f64 {
    let r = theta.rem_euclid(TAU);
    // rem_euclid can return TAU itself for tiny negative inputs after rounding.
    if r >= TAU { 0.0 } else { r }
}

/// One wave as a shader reads it (std430/uniform layout: 32 bytes, 16-byte aligned).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuWave {
    /// Unit direction (x, z).
    pub direction: [f32; 2],
    /// k, rad/m.
    pub k: f32,
    /// A, metres.
    pub amplitude: f32,
    /// θ0 = (k D·o − ω t + φ) mod 2π, radians, in [0, 2π).
    pub phase0: f32,
    pub _pad: [f32; 3],
}

impl WaveSet {
    /// The waves as f32-safe GPU inputs at race time `t` for local origin `origin` (x, z).
    pub fn gpu_waves(&self, t: f64, origin: [f64; 2]) -> Vec<GpuWave> {
        self.waves
            .iter()
            .map(|w| {
                let theta0 = reduce_phase(self.phase_at(w, origin, t));
                GpuWave {
                    direction: [w.direction[0] as f32, w.direction[1] as f32],
                    k: w.k() as f32,
                    amplitude: w.amplitude() as f32,
                    phase0: theta0 as f32,
                    _pad: [0.0; 3],
                }
            })
            .collect()
    }
}

/// The displacement (dx, y, dz) at local rest point `p` in f32, exactly as the WGSL does it.
/// The f32 path that benches and tests compare against the f64 reference.
pub fn displace_f32(waves: &[GpuWave], p: [f32; 2]) -> [f32; 3] {
    let mut d = [0.0f32; 3];
    for w in waves {
        let theta = w.k * (w.direction[0] * p[0] + w.direction[1] * p[1]) + w.phase0;
        let (s, c) = theta.sin_cos();
        d[0] += w.direction[0] * w.amplitude * c;
        d[1] += w.amplitude * s;
        d[2] += w.direction[1] * w.amplitude * c;
    }
    d
}
