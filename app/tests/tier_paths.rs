//! One tier path for both apps (issue 27). A quality tier changed on the desktop's path (the
//! window's renderer as the scene set-up builds it, its Scene panel with the Wakes switch,
//! `SceneApplier::follow_tier` as `desktop::Overlay::follow_tier` calls it) and on the phone's
//! (the phone core driven headless by phone-sim, the tier pinned in its Scene panel) sets the
//! same renderer settings, and they are the tier's own definition in `crates/quality`
//! (`Tier::settings`: render scale, clip-map error target, wake source spacing in hull radii and
//! the wake source budget). Before, the desktop applied a tier through the panel's switches
//! and the phone through `TierRender::apply_live` with the race, and a race opened on the phone
//! kept its wakes at the default spacing whatever the tier.
//!
//! And a desktop and a phone renderer at the same race time, camera and tier draw the same
//! frame: the profiles differ only in what a tier sets (render scale) and in what does not
//! change pixels (GPU timestamps, re-presenting a still frame).

use ocean::wake::WakeParams;
use quality::Tier;
use regatta::feed::CameraFeed;
use regatta::panels::{SceneApplier, effect_toggles};
use regatta::phone_sim::PhoneSim;
use regatta::setup::{Profile, RaceSetup};
use regatta::sim_phone::device::Device;
use regatta::world::RaceWorld;
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

/// The desktop window's renderer and Scene panel (no feed: the Wakes switch only), through
/// the window's tier path.
struct DesktopPath {
    world: RaceWorld,
    renderer: Renderer,
    settings: ui::SceneSettings,
    scene: SceneApplier,
}

impl DesktopPath {
    fn new(gpu: &render::Gpu, profile: Profile) -> DesktopPath {
        let world = RaceSetup::world(race::Race::sample(), ocean::WaveSet::default_sea());
        let setup = RaceSetup::new(profile);
        let wake = setup.wake_or_none(&world.race);
        let renderer = setup.renderer(gpu, render::OFFSCREEN_FORMAT, wake.clone());
        DesktopPath {
            world,
            renderer,
            settings: ui::SceneSettings::new(effect_toggles(false)),
            scene: SceneApplier::new(wake),
        }
    }

    fn set_tier(&mut self, gpu: &render::Gpu, tier: Tier) {
        let race = &self.world.race;
        let (s, r) = (&mut self.settings, &mut self.renderer);
        assert!(
            self.scene
                .follow_tier(tier, s, gpu, r, None, race)
                .is_some()
        );
        // The window applies the Scene panel's switches every frame.
        self.scene.apply(&self.settings, &mut self.renderer, None);
    }
}

#[test]
fn a_tier_change_sets_the_tiers_definition_on_the_desktops_and_the_phones_path() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let mut desktop = DesktopPath::new(&gpu, Profile::Desktop);
    let size = [180, 400];
    let feed = CameraFeed::synth(ar::SynthConfig {
        frames: 1,
        width: 160,
        height: 120,
        supersample: 1,
        ..ar::SynthConfig::default()
    });
    let mut phone = PhoneSim::launch(feed, size, Device::A54.pixels_per_point(size), None);
    phone.app.panels.show_scene = true;
    phone.frame(1.0 / 60.0);
    for tier in CHANGES {
        desktop.set_tier(&gpu, tier);
        if let Some(p) = phone.app.panels.settings.tier.as_mut() {
            p.pinned = Some(tier);
        }
        // The pin is answered after a frame and applied before the next.
        phone.frame(1.0 / 60.0);
        phone.frame(1.0 / 60.0);
        assert_eq!(phone.app.tier_drawn(), Some(tier));
        let on_phone = settings_of(phone.app.race_renderer().expect("the phone draws"));
        let on_desktop = settings_of(&desktop.renderer);
        assert!(
            close(on_desktop, defined(tier)),
            "{tier}: desktop {on_desktop:?}, quality {:?}",
            defined(tier)
        );
        assert!(
            close(on_phone, defined(tier)),
            "{tier}: phone {on_phone:?}, quality {:?}",
            defined(tier)
        );
    }
}

/// A race opened on the phone takes the tier's wake spacing, as on the desktop (the phone kept
/// the default spacing until the tier next changed).
#[test]
fn a_new_race_on_either_path_has_its_wakes_at_the_tiers_spacing() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let mut desktop = DesktopPath::new(&gpu, Profile::Phone);
    desktop.set_tier(&gpu, Tier::Low);
    // A race opened: its wakes at the default spacing, as `RaceSetup` emits them.
    let wake = RaceSetup::new(Profile::Phone).wake_or_none(&desktop.world.race);
    let spacing = |r: &Renderer| r.wake().map(|w| w.params.spacing);
    desktop.scene.set_race_wake(wake, &mut desktop.renderer);
    assert_eq!(
        spacing(&desktop.renderer),
        Some(WakeParams::default().spacing)
    );
    let race = &desktop.world.race;
    let (s, r) = (&mut desktop.settings, &mut desktop.renderer);
    assert!(
        desktop
            .scene
            .follow_tier(Tier::Low, s, &gpu, r, None, race)
            .is_some()
    );
    assert!(close(settings_of(&desktop.renderer), defined(Tier::Low)));
}

/// The desktop's and the phone's renderer (their profiles from the scene set-up, each through
/// its shell's Scene panel) at one tier, race time and camera draw the same pixels.
#[test]
fn a_desktop_and_a_phone_renderer_at_one_tier_draw_the_same_frame() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let size = [160, 96];
    let mut desktop = DesktopPath::new(&gpu, Profile::Desktop);
    let mut phone = DesktopPath::new(&gpu, Profile::Phone);
    // The phone's Scene panel offers no switches.
    phone.settings = ui::SceneSettings::new(Vec::new());
    let t = desktop.world.middle_time();
    let scene = desktop.world.scene_at(t, None);
    for tier in [Tier::Medium, Tier::Ultra] {
        desktop.set_tier(&gpu, tier);
        phone.set_tier(&gpu, tier);
        assert_eq!(settings_of(&desktop.renderer), settings_of(&phone.renderer));
        let (a, ra) = render::render_image(&gpu, &mut desktop.renderer, &scene, size).unwrap();
        let (b, rb) = render::render_image(&gpu, &mut phone.renderer, &scene, size).unwrap();
        assert_eq!(ra.size, rb.size, "{tier}");
        let first = *a.get_pixel(0, 0);
        assert!(
            a.pixels().any(|p| *p != first),
            "{tier}: a frame of one colour"
        );
        assert!(a.as_raw() == b.as_raw(), "{tier}: the frames differ");
    }
}
