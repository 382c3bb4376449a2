//! One app for the desktop and the phone (issue 27), driven here as the shells drive it: the
//! desktop profile (`App::desktop`, what the `regatta` window runs) and the phone profile
//! (`App::phone`, what the Android activity, `regatta run --phone` and `phone-sim` run), both
//! headless on lavapipe with offscreen windows.
//!
//! - A quality tier changed on either profile (pinned in its Scene panel, as a user does) sets
//!   the same renderer settings, and they are the tier's own definition in `crates/quality`
//!   (`Tier::settings`: render scale, clip-map error target, wake source spacing in hull radii
//!   and the wake source budget). Before the one app, the desktop applied a tier through the
//!   panel's switches and the phone through `TierRender::apply_live` with the race, and a race
//!   opened on the phone kept its wakes at the default spacing whatever the tier.
//! - A race opened on either profile takes the tier's wake spacing.
//! - The two profiles at the same race time, camera (the orbit view) and tier draw the same
//!   water, byte for byte: one code path draws both (the profiles' renderers differ only in
//!   what does not change pixels: GPU timestamps, re-presenting a still frame).

mod common;

use ocean::wake::WakeParams;
use quality::Tier;
use regatta::core::app::{App, DesktopStart};
use regatta::core::feed::CameraFeed;
use regatta::hud::SceneChoice;
use regatta::phone_sim::PhoneSim;
use regatta::setup::{Profile, RaceSetup};
use regatta::sim_phone::device::Device;
use render::Renderer;

/// The settings a tier sets on the race renderer: render scale, error target (px), wake
/// source spacing (m), wake source budget.
type Settings = (f64, f64, f64, usize);

/// `tier`'s definition in `crates/quality`, in the renderer's units (the spacing in hull
/// radii times the default wake boat's hull radius, the only wake boat races have).
fn defined(tier: Tier) -> Settings {
    let s = tier.settings();
    (
        s.render_scale,
        s.error_px,
        s.wake_spacing_radii * WakeParams::default().hull_radius,
        s.wake_source_budget as usize,
    )
}

fn settings_of(r: &Renderer) -> Settings {
    let wake = r.wake().expect("the race's wakes are drawn");
    (
        r.options.render_scale,
        r.options.error_px,
        wake.params.spacing,
        r.wake_source_budget(),
    )
}

fn close(a: Settings, b: Settings) -> bool {
    let near = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y.abs().max(1.0);
    near(a.0, b.0) && near(a.1, b.1) && near(a.2, b.2) && a.3 == b.3
}

/// The tiers changed to, in order: down from the phone's start, across, and up.
const CHANGES: [Tier; 3] = [Tier::Low, Tier::Ultra, Tier::Medium];

/// The sample race on the default sea, as both shells load it.
fn world() -> regatta::world::RaceWorld {
    RaceSetup::world(race::Race::sample(), ocean::WaveSet::default_sea())
}

/// The desktop profile without a feed (the orbit view over the sky), `tier` pinned.
fn desktop(size: [u32; 2], tier: Tier) -> App {
    let start = DesktopStart {
        feed: None,
        water: render::water_look::WaterLook::default(),
        tier: Some(tier),
        scene: SceneChoice::Race,
        pool_sea: None,
    };
    common::shown(App::desktop(world(), start), size)
}

/// The phone profile without ARCore, `tier` pinned.
fn phone(size: [u32; 2], tier: Tier) -> App {
    let mut app = App::phone(world(), Box::new(regatta::core::ar::NoAr));
    app.tiers = regatta::tier_control::TierControl::new(tier, true);
    common::shown(app, size)
}

/// Pins `tier` in the app's Scene panel, as a click there does.
fn pin_in_panel(app: &mut App, tier: Tier) {
    let panel = app
        .panels
        .settings
        .tier
        .as_mut()
        .expect("a frame was drawn");
    panel.pinned = Some(tier);
}

#[test]
fn a_tier_change_sets_the_tiers_definition_on_both_profiles() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let mut desktop = desktop([160, 96], Tier::Ultra);
    assert_eq!(desktop.profile(), Profile::Desktop);
    let size = [180, 400];
    let feed = CameraFeed::synth(ar::SynthConfig {
        frames: 1,
        width: 160,
        height: 120,
        supersample: 1,
        ..ar::SynthConfig::default()
    });
    // The phone as phone-sim runs it (the simulated ARCore, the camera image unplaced).
    let mut phone = PhoneSim::launch(feed, size, Device::A54.pixels_per_point(size), None);
    assert_eq!(phone.app.profile(), Profile::Phone);
    phone.app.panels.show_scene = true;
    phone.frame(1.0 / 60.0);
    desktop.frame(1.0 / 60.0);
    for tier in CHANGES {
        pin_in_panel(&mut desktop, tier);
        pin_in_panel(&mut phone.app, tier);
        // The pin is answered after a frame and applied before the next.
        for _ in 0..2 {
            phone.frame(1.0 / 60.0);
            desktop.frame(1.0 / 60.0);
        }
        for (name, app) in [("desktop", &desktop), ("phone", &phone.app)] {
            assert_eq!(app.tier_drawn(), Some(tier), "{name}");
            let got = settings_of(app.race_renderer().expect("a frame was drawn"));
            assert!(
                close(got, defined(tier)),
                "{tier} on the {name}: {got:?}, quality {:?}",
                defined(tier)
            );
        }
    }
}

/// A race opened on either profile takes the tier's wake spacing (the phone kept the default
/// spacing until the tier next changed).
#[test]
fn a_race_opened_on_either_profile_has_its_wakes_at_the_tiers_spacing() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/races/valencia/2025-06-21-ESP30782-P01.gpx");
    for mut app in [desktop([96, 64], Tier::Low), phone([96, 64], Tier::Low)] {
        app.frame(1.0 / 60.0);
        app.open_race(std::slice::from_ref(&file))
            .expect("the race opens");
        assert_ne!(app.race().name, race::Race::sample().name);
        app.frame(1.0 / 60.0);
        let got = settings_of(app.race_renderer().expect("a frame was drawn"));
        assert!(
            close(got, defined(Tier::Low)),
            "{:?}: {got:?}, quality {:?}",
            app.profile(),
            defined(Tier::Low)
        );
    }
}

/// The rows of a 320 × 400 frame that neither profile's panels cover (the phone's bar and
/// its banner's shaded strip end 115 px down, both timelines begin about 215 px down): the
/// water, the boats and the race overlays with their labels.
const WATER_ROWS: std::ops::Range<u32> = 120..210;

/// The desktop's and the phone's app at one tier, race time and camera draw the same water.
#[test]
fn the_desktop_and_the_phone_profile_draw_the_same_frame() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let size = [320, 400];
    for tier in [Tier::Medium, Tier::Ultra] {
        let mut d = desktop(size, tier);
        let mut p = phone(size, tier);
        // The desktop's side panels off: the phone has none.
        d.panels.show_leaderboard = false;
        d.panels.show_perf = false;
        for _ in 0..3 {
            d.frame(1.0 / 30.0);
            p.frame(1.0 / 30.0);
        }
        assert_eq!(d.race_time(), p.race_time(), "{tier}");
        assert!(d.race_time() > 0.0, "{tier}: the race played");
        assert_eq!(d.tier_drawn(), Some(tier));
        assert_eq!(p.tier_drawn(), Some(tier));
        let (rd, rp) = (d.race_renderer().unwrap(), p.race_renderer().unwrap());
        assert_eq!(settings_of(rd), settings_of(rp), "{tier}");
        let a = d.screenshot().expect("an offscreen window").unwrap();
        let b = p.screenshot().expect("an offscreen window").unwrap();
        let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("tier_paths");
        std::fs::create_dir_all(&dir).unwrap();
        a.save(dir.join(format!("desktop-{tier}.png"))).unwrap();
        b.save(dir.join(format!("phone-{tier}.png"))).unwrap();
        let band = |img: &image::RgbaImage| {
            let w = img.width() as usize * 4;
            img.as_raw()[WATER_ROWS.start as usize * w..WATER_ROWS.end as usize * w].to_vec()
        };
        let (wa, wb) = (band(&a), band(&b));
        assert!(
            wa.chunks(4).any(|p| p != &wa[..4]),
            "{tier}: the band is one colour"
        );
        assert!(
            wa == wb,
            "{tier}: the profiles' water differs (images in {})",
            dir.display()
        );
    }
}
