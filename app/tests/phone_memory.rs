//! 100 pause/resume cycles of the phone app (issue 19): on each pause the window's surface is
//! dropped and on each resume a new one is made (wgpu issue 2302), and the resident memory of
//! the process grows by less than 5 MB over the cycles. Alone in its test binary, so no other
//! test's allocations count.

use regatta::phone_sim::PhoneSim;
use regatta::phone_sim::backend::Feed;
use regatta::phone_sim::device::Device;

/// Resident set size, bytes (/proc/self/statm: pages).
fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap();
    let pages: u64 = statm.split_whitespace().nth(1).unwrap().parse().unwrap();
    pages * 4096
}

#[test]
fn a_hundred_pause_resume_cycles_keep_memory_flat_and_the_surface_configuration() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let size = [120, 266];
    let feed = Feed::synth(ar::SynthConfig {
        frames: 4,
        width: 160,
        height: 120,
        supersample: 1,
        ..ar::SynthConfig::default()
    });
    let mut sim = PhoneSim::launch(feed, size, Device::A54.pixels_per_point(size), None);
    sim.tap([0.5, 0.6]);
    let first = sim.app.window_config().unwrap();
    let cycle = |sim: &mut PhoneSim| {
        sim.pause();
        assert!(!sim.app.visible(), "the window is gone in the background");
        sim.resume();
        sim.frame(0.1);
    };
    // Warm-up: caches, pipelines and allocator pools settle.
    for _ in 0..10 {
        cycle(&mut sim);
    }
    let before = resident_bytes();
    let drawn = sim.app.status().frames_drawn;
    for _ in 0..100 {
        cycle(&mut sim);
    }
    let growth = resident_bytes().saturating_sub(before);
    assert_eq!(sim.app.status().frames_drawn, drawn + 200);
    assert!(
        growth < 5 << 20,
        "resident memory grew by {:.1} MB over 100 cycles",
        growth as f64 / 1048576.0
    );
    // Every new window got the first window's configuration (format and egui's view format).
    let now = sim.app.window_config().unwrap();
    assert_eq!(
        (now.format, &now.view_formats),
        (first.format, &first.view_formats)
    );
    assert_eq!(sim.app.session(), ar::arcore::SessionState::Running);
    eprintln!("resident growth over 100 cycles: {growth} bytes");
}
