//! The phone's "Share clip" (docs/phone.md): the bar shows the button in the race scene; a
//! press draws the last seconds of race time as a GIF on a worker thread (the banner says how
//! far), then hands it to Android through the host's scripted JNI: the bytes put into the media
//! store are the GIF the renderer wrote (decoded with the `gif` crate: seconds · fps + 1 frames,
//! both ends included, at the size asked), in `Pictures/Regatta` as `image/gif`, published
//! (not left pending), and the share sheet is opened on its URI. Each failure is one line on
//! the banner: Android older than 10, the media store's refusal, a full disk, a Java exception
//! from the share sheet.

use ar::arcore::ffi::share::NO_SPACE;
use ar::arcore::ffi::{JavaScript, ScriptedJni};
use regatta::core::app::{ClipRequest, ClipState};
use regatta::core::feed::CameraFeed;
use regatta::phone_sim::PhoneSim;
use regatta::sim_phone::device::Device;

/// The A54's layout (360 × 800 dp) on a quarter of its pixels: quick on lavapipe.
const SIZE: [u32; 2] = [180, 400];

/// 1 s at 2 fps, 32 × 24: three frames, a few seconds on lavapipe.
const SMALL: ClipRequest = ClipRequest {
    seconds: 1.0,
    fps: 2.0,
    size: [32, 24],
};

fn launch(name: &str) -> PhoneSim {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("phone_clip_share")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let feed = CameraFeed::synth(ar::SynthConfig {
        frames: 1,
        width: 320,
        height: 240,
        supersample: 1,
        ..ar::SynthConfig::default()
    });
    let mut sim = PhoneSim::launch(feed, SIZE, Device::A54.pixels_per_point(SIZE), Some(dir));
    sim.app.clip_request = SMALL;
    sim.app.android_sdk = Some(30);
    sim.app.panels.clock.scrub_to(600.0);
    sim
}

fn banner(sim: &PhoneSim) -> String {
    sim.app.banner().map(|(t, _)| t).unwrap_or_default()
}

/// Scripts the fake media store.
type Script = fn(&mut ar::arcore::ffi::share::MediaScript);

/// Presses "Share clip", waits for the worker and hands the clip to `jni`.
fn share(sim: &mut PhoneSim, jni: &ScriptedJni) {
    sim.app.share_clip();
    assert!(
        banner(sim).starts_with("Drawing the clip: frame"),
        "{}",
        banner(sim)
    );
    sim.app.clip.wait();
    sim.app.poll_share(jni);
}

/// (width, height, frames) of a GIF.
fn decode(bytes: &[u8]) -> (u16, u16, usize) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut d = options.read_info(bytes).unwrap();
    let (w, h) = (d.width(), d.height());
    let mut frames = 0;
    while d.read_next_frame().unwrap().is_some() {
        frames += 1;
    }
    (w, h, frames)
}

#[test]
fn the_clip_goes_into_the_media_store_and_to_the_share_sheet() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let mut sim = launch("shared");
    sim.frame(1.0 / 60.0);
    sim.frame(1.0 / 60.0);
    let bar = sim.app.bar.expect("the bar is laid out");
    assert!(
        bar.share_button.is_some(),
        "the race scene shows Share clip"
    );
    let jni = ScriptedJni::new(JavaScript::default());
    share(&mut sim, &jni);
    let ClipState::Shared(uri) = sim.app.clip.state() else {
        panic!("{:?}", sim.app.clip.state());
    };
    assert_eq!(banner(&sim), "Clip saved in Pictures/Regatta: pick an app");
    let stored = jni.script_media(|m| m.stored.clone());
    assert_eq!(stored.len(), 1);
    let item = &stored[0];
    assert_eq!(item.uri, uri);
    assert!(!item.pending, "published: IS_PENDING back to 0");
    assert_eq!(
        (item.item.mime.as_str(), item.item.relative_path.as_str()),
        ("image/gif", "Pictures/Regatta")
    );
    // The renderer's file, byte for byte, and a GIF of the clip asked for: 1 s at 2 fps from
    // 599 to 600 s is frames at 599, 599.5 and 600 s.
    let written = sim
        .app
        .data_dir
        .clone()
        .unwrap()
        .join("clips")
        .join("regatta-599-600s.gif");
    assert_eq!(item.item.display_name, "regatta-599-600s.gif");
    assert_eq!(std::fs::read(&written).unwrap(), item.bytes);
    let frames = (SMALL.seconds * SMALL.fps) as usize + 1;
    assert_eq!(decode(&item.bytes), (32, 24, frames));
    let choosers = jni.script_media(|m| m.choosers.clone());
    assert_eq!(choosers.len(), 1);
    assert_eq!(
        (
            choosers[0].uri.as_str(),
            choosers[0].mime.as_str(),
            choosers[0].title.as_str()
        ),
        (uri.as_str(), "image/gif", "Share clip")
    );
    // The pool has no button.
    sim.app.choose_scene(regatta::hud::SceneChoice::Pool);
    sim.frame(1.0 / 60.0);
    assert!(sim.app.bar.unwrap().share_button.is_none());
}

#[test]
fn each_failure_is_one_line_on_the_banner() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let mut sim = launch("failures");
    // Android 9: said at once, nothing drawn.
    sim.app.android_sdk = Some(28);
    sim.app.share_clip();
    assert_eq!(
        banner(&sim),
        "Sharing a clip needs Android 10 or newer (this phone runs API 28)."
    );
    assert!(!sim.app.data_dir.clone().unwrap().join("clips").exists());
    sim.app.android_sdk = Some(30);
    let cases: [(&str, Script); 3] = [
        (
            "Could not save the clip in Pictures/Regatta: the media store refused the new item (insert returned null)",
            |m| m.refuse_insert = true,
        ),
        (
            "Could not save the clip in Pictures/Regatta: java.io.IOException: No space left on device",
            |m| m.write_throws = Some(NO_SPACE.into()),
        ),
        (
            "Could not open the share sheet: android.content.ActivityNotFoundException: No Activity found to handle Intent",
            |m| {
                m.chooser_throws = Some(
                    "android.content.ActivityNotFoundException: No Activity found to handle Intent"
                        .into(),
                )
            },
        ),
    ];
    for (said, script) in cases {
        let jni = ScriptedJni::new(JavaScript::default());
        jni.script_media(script);
        share(&mut sim, &jni);
        assert_eq!(banner(&sim), said);
        assert!(!banner(&sim).contains('\n'));
        assert!(
            matches!(sim.app.clip.state(), ClipState::Failed(_)),
            "{:?}",
            sim.app.clip.state()
        );
        // A failed write leaves nothing half-written in the media store.
        assert!(jni.script_media(|m| m.stored.iter().all(|s| !s.pending)));
    }
}
