//! The wake bins of the sample race's busiest frame (t = 600 s, built as `regatta bench --only
//! budget-model` builds it: `world::scene_at`, `renderer::bin_wakes` with the tier's source
//! budget and mesh error, here at the OPPO A54's full screen) leave out no term the GPU would
//! add: at every clip-map vertex, and at points a few
//! millimetres around it (the GPU's f32 sea moves a vertex by less than that from the f64
//! sea's position used here), every source whose f32 term (`source_height_grad_sampled_f32`,
//! the exact mirror of the WGSL kernel) is not zero at the vertex's level spacing is in the
//! height list the shader reads there (`WakeBins::listed_at`: the point's bin, the vertex's
//! level), and the sum over that list equals the sum over every source bit for bit. The truth
//! is the kernel itself over all of the frame's sources, not the bins' own geometry. And the
//! frame's bins equal the straightforward binning's (`wake_bins::reference`) bit for bit.

use ocean::wake::source_height_grad_sampled_f32;
use quality::Tier;
use regatta::tier_render::TierRender;
use render::frame::FrameContext;
use render::wake_bins::WAKE_BUFFER_BUDGET_BYTES;

const T: f64 = 600.0;
/// The OPPO A54's screen.
const SIZE: [u32; 2] = [720, 1600];

fn check_tier(tier: Tier) {
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), T, None);
    let render = TierRender::of(tier);
    let wake = render.race_wake(&race).expect("the sample race's wake");
    let mut frame = FrameContext::new(&scene, SIZE, render.options.error_px);
    render::renderer::bin_wakes(
        &wake,
        WAKE_BUFFER_BUDGET_BYTES,
        render.wake_source_budget,
        &mut Default::default(),
        &mut frame,
    );
    equals_the_reference_binning(tier, &scene, &wake, render.wake_source_budget, &frame);
    let (sources, bins, o) = (&frame.wakes.sources, &frame.wake_bins, frame.origin);
    assert!(sources.len() >= 500, "{tier}: {} sources", sources.len());
    let (mut points, mut nonzero, mut listed, mut terms) = (0usize, 0usize, 0usize, 0usize);
    for v in &frame.mesh.vertices {
        let d = scene
            .sea
            .displace([f64::from(v.rest[0]) + o.x, f64::from(v.rest[1]) + o.y], T);
        let at = [(d[0] - o.x) as f32, (d[2] - o.y) as f32];
        let spacing = frame.clipmap.cell(v.level) as f32;
        for (dx, dz) in [(0.0, 0.0), (0.005, 0.005), (-0.005, 0.005), (0.005, -0.005)] {
            let p = [at[0] + dx, at[1] + dz];
            let list = bins.listed_at(p, v.level);
            let (mut every, mut binned) = ([0.0f32; 3], [0.0f32; 3]);
            for (k, s) in sources.iter().enumerate() {
                let g = source_height_grad_sampled_f32(s, p, spacing);
                if g != [0.0; 3] {
                    assert!(
                        list.binary_search(&(k as u32)).is_ok(),
                        "{tier}: source {k} adds {g:?} at {p:?} (level {}) but is not listed",
                        v.level
                    );
                    terms += 1;
                }
                every = [every[0] + g[0], every[1] + g[1], every[2] + g[2]];
            }
            for &k in list {
                let g = source_height_grad_sampled_f32(&sources[k as usize], p, spacing);
                binned = [binned[0] + g[0], binned[1] + g[1], binned[2] + g[2]];
            }
            // The list is in the sources' order and what it leaves out adds exact zeros.
            assert_eq!(binned, every, "{tier}: {p:?} level {}", v.level);
            points += 1;
            listed += list.len();
            nonzero += usize::from(every != [0.0; 3]);
        }
    }
    eprintln!(
        "{tier}: {points} points, {:.2} sources listed and {:.2} adding per point",
        listed as f64 / points as f64,
        terms as f64 / points as f64
    );
    // The frame is the busy one: a good share of its water sees wakes.
    assert!(nonzero > points / 10, "{tier}: {nonzero} of {points}");
}

/// The frame's bins (`bin_wakes`, the fast binning) equal the straightforward binning's
/// (`wake_bins::reference::fit`: a list per bin and level, every pair of a source's bounding
/// square tested on its own) of the same sources and mesh, bin for bin and index for index,
/// with the same sources kept; and at a cap of a third of the bytes they need, where both
/// drop sources.
fn equals_the_reference_binning(
    tier: Tier,
    scene: &render::Scene,
    wake: &ocean::wake::Wake,
    max_sources: usize,
    frame: &FrameContext,
) {
    use render::wake_spacing::SampleSpacing;
    let eye = glam::DVec2::new(scene.camera.eye.x, scene.camera.eye.z);
    let reach = frame.clipmap.half_extent(frame.clipmap.levels() - 1);
    let view = ocean::wake::WakeView::around([eye.x, eye.y], reach);
    let origin = [frame.origin.x, frame.origin.y];
    let sources = wake.gpu_sources(T, origin, &view, render::renderer::WAKE_EPSILON_M);
    let displacement: f64 = scene.sea.waves.iter().map(|w| w.amplitude()).sum();
    let spacing = SampleSpacing::of_mesh(&frame.clipmap, &frame.mesh, eye, displacement);
    let half = reach as f32 * 2.0;
    let mut slow = sources.clone();
    let want = render::wake_bins::reference::fit(
        &mut slow,
        half,
        WAKE_BUFFER_BUDGET_BYTES,
        max_sources,
        &spacing,
    );
    assert_eq!(
        (&frame.wake_bins, frame.wake_drop),
        (&want.0, want.1),
        "{tier}"
    );
    assert_eq!(frame.wakes.sources, slow.sources, "{tier}");
    let cap = want.0.bytes(slow.sources.len()) / 3;
    let (mut fast, mut slow) = (sources.clone(), sources);
    let got = render::wake_bins::fit(&mut fast, half, cap, max_sources, &spacing);
    let want = render::wake_bins::reference::fit(&mut slow, half, cap, max_sources, &spacing);
    assert!(want.1.dropped > 0, "{tier}: the cap drops sources");
    assert_eq!((got, fast), (want, slow), "{tier}: cap {cap}");
}

#[test]
fn every_source_adding_to_a_vertex_of_the_race_frame_is_in_its_list_ultra() {
    check_tier(Tier::Ultra);
}

#[test]
fn every_source_adding_to_a_vertex_of_the_race_frame_is_in_its_list_low() {
    check_tier(Tier::Low);
}
