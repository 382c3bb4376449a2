//! The machine-independent frame budget: per pass, the invocations a GPU must run (vertex
//! and fragment invocations from pipeline-statistics queries, compute and offscreen
//! invocations from the sizes the CPU planned), times the work per invocation counted in the
//! compiled shaders ([`super::shader_cost`]), against each phone's published ALU rate, texture
//! rate and memory bandwidth. A pass takes as long as its slowest of the three (a roofline);
//! the frame is the sum of its passes. No clock is read: the same commit and scene give the
//! same numbers on any machine whose rasteriser counts the same invocations.

use effects::passes as fx;
use render::shader;

use super::shader_cost::{Cost, Trips, entry_cost};

/// A phone GPU's published rates, each as the range the spec sheets give.
#[derive(Debug, Clone, Copy)]
pub struct PhoneGpu {
    pub phone: &'static str,
    pub gpu: &'static str,
    /// Screen, pixels (portrait).
    pub screen: [u32; 2],
    /// FP32 GFLOP/s (an FMA = 2), low and high.
    pub gflops: [f64; 2],
    /// Bilinear texels per second, G/s.
    pub gtexels: [f64; 2],
    /// Memory bandwidth, GB/s.
    pub gbytes: [f64; 2],
    /// Where the figures come from.
    pub sources: &'static str,
    /// Does the GPU shade each pixel of opaque geometry once whatever the draw order
    /// (PowerVR's tile-based hidden surface removal)? Otherwise every fragment the depth test
    /// lets through in draw order is shaded, as counted by the pipeline statistics.
    pub hidden_surface_removal: bool,
}

/// The phones the product targets.
pub const PHONES: [PhoneGpu; 2] = [
    PhoneGpu {
        phone: "OPPO A54",
        gpu: "PowerVR GE8320 (MediaTek Helio P35)",
        screen: [720, 1600],
        // 64 FP32 FLOP per clock (Imagination's 8XEP sheet; third-party tables: 32 FMA
        // lanes) at 650–680 MHz (chipguider lists 650 MHz, MediaTek's Helio P35 and hwpure
        // 680 MHz): 40 (hmc-tech's figure at 650 MHz) to 43.5 GFLOP/s.
        gflops: [40.0, 43.5],
        // 2 TMUs at 650 MHz (hmc-tech: 1.3 Gtexel/s) to Imagination's 4 pixels per clock at
        // 680 MHz (2.72 G/s).
        gtexels: [1.3, 2.72],
        // MT6765 memory: LPDDR3-933 (6.4 GB/s, some P35 phones) to LPDDR4X-1600
        // 2×16-bit (12.8 GB/s). Not published for the A54 itself.
        gbytes: [6.4, 12.8],
        sources: "Imagination PowerVR 8XEP GE8320 (4 pixels/clock, 64 FP32 FLOP/clock); \
                  hmc-tech.com GE8320 650 MHz (2 TMU, 40 GFLOPS, 1.3 GTexel/s); chipguider.com \
                  (650 MHz); hwpure.com (680 MHz in the Helio P35); MediaTek MT6765 memory \
                  (LPDDR3 933 MHz / LPDDR4X 1600 MHz)",
        hidden_surface_removal: true,
    },
    PhoneGpu {
        phone: "Pixel 2 XL",
        gpu: "Adreno 540 (Snapdragon 835)",
        screen: [1440, 2880],
        // 384 FP32 ALU lanes × 2 FLOP at 670–710 MHz: 514–567 GFLOP/s (Qualcomm lists 710 MHz;
        // several reviews 670 MHz).
        gflops: [514.0, 567.0],
        // 12–16 texture units at 670–710 MHz (reviews differ): 8.0–11.4 Gtexel/s.
        gtexels: [8.0, 11.4],
        // LPDDR4X-1866 dual channel 2×32-bit: 29.8 GB/s (Qualcomm's Snapdragon 835 page);
        // AnandTech's 835 review measures about 25 GB/s sustained.
        gbytes: [25.0, 29.8],
        sources: "Qualcomm Snapdragon 835 product brief (Adreno 540 at 710 MHz, LPDDR4X 1866 \
                  MHz); notebookcheck Adreno 540 (567 GFLOPS); AnandTech Snapdragon 835 review \
                  (670 MHz, memory bandwidth)",
        // Adreno's low-resolution Z rejects some occluded fragments, not all: counted as
        // none (the conservative side; the optimistic end of the range assumes all).
        hidden_surface_removal: false,
    },
];

/// One pass's work in a frame.
#[derive(Debug, Clone, PartialEq)]
pub struct PassWork {
    pub pass: String,
    pub cost: Cost,
    /// Bytes to and from memory: render targets (colour and depth), vertices, and the
    /// storage buffers once each (a wake source is read by every vertex of its bins, from the
    /// cache: the shader's storage loads, `cost.storage_bytes`, are not memory traffic).
    pub target_bytes: f64,
    /// Invocations: vertex (or compute), fragment.
    pub invocations: [f64; 2],
}

impl PassWork {
    /// Milliseconds on `phone` at the low (`hi = false`) or high end of its rates.
    pub fn ms(&self, phone: &PhoneGpu, hi: bool) -> f64 {
        self.bound(phone, hi).1
    }

    /// What bounds the pass on `phone` ("ALU", "texture" or "memory") and its milliseconds.
    pub fn bound(&self, phone: &PhoneGpu, hi: bool) -> (&'static str, f64) {
        let k = usize::from(hi);
        let alu = self.cost.alu / (phone.gflops[k] * 1e9);
        let tex = self.cost.tex / (phone.gtexels[k] * 1e9);
        let mem = self.target_bytes / (phone.gbytes[k] * 1e9);
        [("ALU", alu), ("texture", tex), ("memory", mem)]
            .into_iter()
            .map(|(what, s)| (what, s * 1e3))
            .fold(("ALU", 0.0), |a, b| if b.1 > a.1 { b } else { a })
    }
}

/// What the model needs of one drawn frame.
pub struct FrameInputs<'a> {
    pub report: &'a render::FrameReport,
    pub offscreen: fx::OffscreenSizes,
    pub ar: &'a fx::ArConfig,
    pub trips: Trips,
    /// The frame's wake buffers (sources, bins, indices), bytes.
    pub wake_buffer_bytes: f64,
    /// The clip-map's vertices: the water's compute stage runs once per vertex.
    pub clipmap_vertices: f64,
    /// Target (screen) size, pixels; the drawn frame is `report.size`.
    pub screen: [u32; 2],
    /// A YUV camera image converted every frame: its size and the camera's rate over the
    /// frame rate (1 = a new image every frame).
    pub yuv: Option<([u32; 2], f64)>,
}

/// The entry points a pass runs, by the pass's name in the frame record.
pub(crate) fn pass_shaders(
    name: &str,
    ar: &fx::ArConfig,
) -> Option<(String, &'static str, &'static str)> {
    let mask = ar.effects.iter().fold(0u32, |m, e| m | 1 << e as u32);
    Some(match name {
        "sky" => (shader::source(&[shader::SKY]), "vs_main", "fs_main"),
        "water" => (
            shader::source(&[
                shader::WATER_DISPLACED,
                shader::WATER,
                render::water_look::WATER_LOOK_WGSL,
            ]),
            "vs_main",
            "fs_main",
        ),
        "ar_water" => {
            let constants = format!(
                "const FX_MASK: u32 = {}u;\nconst FX_CHEAP_CAUSTICS: bool = {};",
                mask & 0b1_1110,
                ar.cheap_caustics
            );
            (
                {
                    let parts: Vec<&str> = std::iter::once(shader::WATER_DISPLACED)
                        .chain(fx::AR_WATER_PARTS)
                        .chain(std::iter::once(constants.as_str()))
                        .collect();
                    effects::wgsl::source(&parts)
                },
                "vs_ar",
                "fs_ar",
            )
        }
        "boats" => (shader::source(&[shader::BOATS]), "vs_main", "fs_main"),
        "background" => (
            effects::wgsl::source(&[fx::EFFECTS_COMMON, fx::BACKGROUND]),
            "vs_main",
            "fs_main",
        ),
        _ => return None,
    })
}

/// Bytes per fragment written: colour (RGBA8) and depth (32-bit read and write).
const FRAGMENT_BYTES: f64 = 12.0;
/// Bytes per vertex read from vertex buffers (the displaced water vertex).
const VERTEX_BYTES: f64 = render::passes::water::DISPLACED_VERTEX_BYTES as f64;

/// Every pass's work in the frame. Passes the model has no shaders for are listed in the
/// second value (none in the frames the budget draws). With `hsr` (hidden surface removal) a
/// pass shades each drawn pixel at most once: its fragment invocations are capped at the drawn
/// frame's pixels. (The budget gives the water's fragments as a phone shades them, 2×2 quads:
/// lavapipe counts 16 per 4×4 block a triangle touches, before the depth test.)
pub fn frame_work(inp: &FrameInputs, hsr: bool) -> Result<(Vec<PassWork>, Vec<String>), String> {
    let drawn_px = f64::from(inp.report.size[0]) * f64::from(inp.report.size[1]);
    let trips = &inp.trips;
    let mut out = Vec::new();
    let mut unmodelled = Vec::new();
    let run = |src: &str, entry: &str, n: f64| -> Result<Cost, String> {
        Ok(entry_cost(src, entry, trips)?.scaled(n))
    };
    for inv in &inp.report.shader_invocations {
        let Some((src, vs, fs)) = pass_shaders(&inv.pass, inp.ar) else {
            unmodelled.push(inv.pass.clone());
            continue;
        };
        let v = inv.vertex as f64;
        let f = if hsr {
            (inv.fragment as f64).min(drawn_px)
        } else {
            inv.fragment as f64
        };
        let mut cost = run(&src, vs, v)?;
        cost.add(run(&src, fs, f)?);
        let mut target_bytes = f * FRAGMENT_BYTES + v * VERTEX_BYTES;
        if inv.pass == "water" || inv.pass == "ar_water" {
            // The compute stage displaces every clip-map vertex by the sea and the wakes.
            let vertices = inp.clipmap_vertices;
            let cs = shader::source(&[&shader::wake(), shader::WATER_VERTICES]);
            cost.add(run(&cs, "cs_displace", vertices)?);
            target_bytes += vertices * (16.0 + VERTEX_BYTES) + inp.wake_buffer_bytes;
        }
        out.push(PassWork {
            pass: inv.pass.clone(),
            cost,
            target_bytes,
            invocations: [v, f],
        });
    }
    let drawn = inp.report.size.map(f64::from);
    if let Some([w, h]) = inp.offscreen.reflection_px {
        // The mirrored room over every texel (the boats' share is a few per cent: left out):
        // its grid's strips, each corner's vertex stage per strip it borders, then every
        // texel's fragment. The grid's vertices come from the vertex index: no vertex bytes.
        let px = f64::from(w) * f64::from(h);
        let vertices = effects::reflection::room_grid_vertices([w, h]) as f64;
        let src = effects::wgsl::source(&[fx::EFFECTS_COMMON, fx::REFLECTION, fx::REFLECTION_ROOM]);
        let mut cost = run(&src, "vs_main", vertices)?;
        cost.add(run(&src, "fs_main", px)?);
        out.push(PassWork {
            pass: "reflection texture".into(),
            cost,
            target_bytes: px * FRAGMENT_BYTES,
            invocations: [vertices, px],
        });
    }
    if let Some(cells) = inp.offscreen.caustic_map_cells {
        // Scatter method: each surface grid point once, each of its two triangles once, then
        // one resolve per map cell.
        let grid = (inp.ar.caustic_resolution.0 as f64).powi(2);
        let cells = f64::from(cells).powi(2);
        let src = effects::wgsl::source(&[
            effects::caustic_map::CAUSTIC_MAP,
            effects::caustic_map::CAUSTIC_SCATTER,
        ]);
        let mut cost = run(&src, "cs_points", grid)?;
        cost.add(run(&src, "cs_triangles", 2.0 * grid)?);
        cost.add(run(&src, "fs_resolve", cells)?);
        out.push(PassWork {
            pass: "caustic map".into(),
            cost,
            target_bytes: cells * FRAGMENT_BYTES + grid * 16.0,
            invocations: [3.0 * grid, cells],
        });
    }
    let screen = inp.screen.map(f64::from);
    if drawn != screen {
        let px = screen[0] * screen[1];
        out.push(PassWork {
            pass: "upscale".into(),
            cost: run(shader::UPSCALE, "fs_main", px)?,
            target_bytes: px * 8.0,
            invocations: [3.0, px],
        });
    }
    if let Some((image, per_frame)) = inp.yuv {
        out.push(camera_yuv_work(image, per_frame, trips)?);
    }
    Ok((out, unmodelled))
}

/// The camera image's work: its YUV 4:2:0 planes uploaded (1.5 bytes per pixel) and converted
/// to RGBA (`shaders/effects/camera_yuv.wgsl`, one fragment and a 4-byte write per pixel),
/// `per_frame` times per drawn frame (1: a new image every frame).
pub fn camera_yuv_work(
    [w, h]: [u32; 2],
    per_frame: f64,
    trips: &Trips,
) -> Result<PassWork, String> {
    let px = f64::from(w) * f64::from(h) * per_frame;
    let src = effects::wgsl::source(&[
        effects::camera_upload::CAMERA_YUV,
        "const ENCODED_TARGET: bool = false;",
    ]);
    Ok(PassWork {
        pass: "camera yuv".into(),
        cost: entry_cost(&src, "fs_main", trips)?.scaled(px),
        target_bytes: px * (1.5 + 4.0),
        invocations: [3.0, px],
    })
}

/// Frame milliseconds on `phone`: (at its spec sheets' high rates, at their low rates).
pub fn frame_ms(work: &[PassWork], phone: &PhoneGpu) -> (f64, f64) {
    let sum = |hi| work.iter().map(|p| p.ms(phone, hi)).sum::<f64>();
    (sum(true), sum(false))
}

#[cfg(test)]
mod tests {
    use super::*;
    use quality::Tier;
    use regatta::tier_render::TierRender;

    /// The sample race's frame at 600 s for `tier` at 180×320 drawn by a fresh renderer: the
    /// model's work per pass.
    fn work_of(gpu: &render::Gpu, tier: Tier) -> Vec<PassWork> {
        let race = race::Race::sample();
        let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), 600.0, None);
        let t = TierRender::of(tier);
        let size = [180, 320];
        let (mut renderer, fx) =
            regatta::setup::RaceSetup::tier_renderer(&t, gpu, Some(&race), &scene, size)
                .expect("renderer");
        let view = crate::offscreen(gpu, size);
        let report = renderer.render(gpu, &view, size, &scene).expect("frame");
        assert!(
            !report.shader_invocations.is_empty(),
            "no pipeline statistics"
        );
        let drawn = f64::from(report.size[0] * report.size[1]);
        for inv in &report.shader_invocations {
            // A pass shades each drawn pixel a few times at most: lavapipe counts 16 lanes per
            // 4×4 block a triangle touches, so the clip-map's far, few-pixel triangles count
            // about 4 per pixel (docs/quality.md, "Goals").
            assert!(inv.fragment as f64 <= 8.0 * drawn, "{inv:?}");
        }
        let inputs = FrameInputs {
            report: &report,
            offscreen: fx.offscreen_sizes(),
            ar: &t.ar,
            trips: Trips {
                waves: scene.sea.waves.len() as f64,
                resolved_waves_in_pixel: scene.sea.waves.len() as f64,
                fading_waves_in_pixel: 1.0,
                wake_sources_per_vertex: 4.0,
                wake_foam_sources_per_vertex: 1.0,
                vertex_waves_per_vertex: 1.0,
                marks: scene.marks.len() as f64,
            },
            screen: size,
            wake_buffer_bytes: 1e6,
            clipmap_vertices: render::frame::FrameContext::new(
                &scene,
                report.size,
                t.options.error_px,
            )
            .mesh
            .vertices
            .len() as f64,
            yuv: None,
        };
        let (work, unmodelled) = frame_work(&inputs, false).expect("model");
        // Hidden surface removal never adds work.
        let hsr = frame_work(&inputs, true).expect("model").0;
        for (a, b) in work.iter().zip(&hsr) {
            assert!(b.cost.alu <= a.cost.alu && b.invocations[1] <= a.invocations[1]);
        }
        assert!(unmodelled.is_empty(), "{unmodelled:?}");
        work
    }

    /// Same commit, same numbers: two renderers drawing the same frame give the same work to
    /// the last bit, and the richer tier costs more on both phones.
    #[test]
    fn the_model_is_deterministic_and_ranks_the_tiers() {
        let Some(gpu) = render::gpu::test_gpu() else {
            return;
        };
        let a = work_of(&gpu, Tier::High);
        let b = work_of(&gpu, Tier::High);
        assert_eq!(a, b);
        let water = a
            .iter()
            .find(|w| w.pass == "ar_water")
            .expect("the AR water");
        assert!(water.invocations[1] > 0.0 && water.cost.alu > 0.0);
        let low = work_of(&gpu, Tier::Low);
        for phone in &PHONES {
            let (hi, lo) = (frame_ms(&a, phone), frame_ms(&low, phone));
            assert!(
                hi.0 > lo.0 && hi.1 > lo.1,
                "{}: {hi:?} vs {lo:?}",
                phone.phone
            );
            // The slow end of the spec sheets is slower.
            assert!(hi.1 >= hi.0);
        }
    }
}
