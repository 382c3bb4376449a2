//! Android entry point (native activity, android-activity 0.6): a thin adapter. It translates
//! the activity's lifecycle, window, configuration and input events into the app core's
//! [`AppEvent`]s and measures wall time; every decision (surfaces and their configuration,
//! the AR session, touch, drawing) is the core's (`crate::core::app`), run on the host by
//! `regatta phone-sim` and `regatta run --phone`.
//!
//! AR: `ar::arcore::ffi::ArCore` loads `libarcore_sdk_c.so` with libloading and is the core's
//! [`crate::core::ar::ArBackend`]; its Java calls go through [`jni_calls::AndroidJni`].

use std::time::Duration;

use android_activity::input::{InputEvent, KeyAction, Keycode, MotionAction, MotionEvent};
use android_activity::{AndroidApp, InputStatus, MainEvent, PollEvent};
use ar::arcore::ffi::{ArCore, JavaObject, Jni};

use crate::core::app::{App, AppEvent};
use crate::core::gfx::SurfaceMaker;
use crate::hud::touch::{Finger, Touch, TouchAction};
use crate::wall_clock::Ticker;

mod intents;
mod jni_calls;
mod share;

// std's `_Unwind_*` come from the `unwinding` crate (see app/Cargo.toml); naming the crate links it.
use unwinding as _;

#[unsafe(no_mangle)]
fn android_main(app: AndroidApp) {
    android_logger::init_once(crate::android_log::config());
    log::info!("regatta: android_main started");
    let world = crate::setup::RaceSetup::load_world(&[], None);
    // Two handles on the same Activity: ARCore's glue owns one, the rotation reads use the other.
    let jni = jni_calls::AndroidJni::new(&app);
    let ar_jni = Box::new(jni_calls::AndroidJni::new(&app));
    let mut phone = match world {
        Ok(w) => App::phone(w, Box::new(ArCore::load(ar_jni))),
        Err(e) => return log::error!("regatta: {e}"),
    };
    phone.data_dir = app.internal_data_path();
    // "Share clip" needs the media store's API 29 columns; below, the phone says so.
    phone.android_sdk = Some(jni.sdk_int());
    // Where `adb push` can put races without root (docs/panels.md).
    phone.set_races_dir(app.external_data_path().map(|d| d.join("races")));
    // A race file from "Open with" or "Share": each such intent starts a new Activity (a
    // NativeActivity never sees onNewIntent), so it is read once, here.
    if let Some(Err(e)) = phone.open_intent(&jni) {
        log::warn!("regatta: the shared file was not opened: {e}");
    }
    let mut ticker = Ticker::default();
    let mut quit = false;
    while !quit {
        let timeout = phone.visible().then_some(Duration::ZERO);
        app.poll_events(timeout, |event| {
            let PollEvent::Main(main) = event else { return };
            quit |= matches!(main, MainEvent::Destroy);
            phone.on_all(translate(&app, &jni, &main));
        });
        input_events(&app, &mut phone);
        phone.frame(ticker.tick());
        // A clip written by the "Share clip" worker goes to the share sheet from this thread.
        phone.poll_share(&jni);
    }
    log::info!("regatta: android_main ends");
}

/// The core's events for one activity event.
fn translate(app: &AndroidApp, jni: &dyn Jni, event: &MainEvent<'_>) -> Vec<AppEvent> {
    match event {
        MainEvent::InitWindow { .. } => {
            let mut events = configuration(app, jni);
            events.extend(app.native_window().map(|w| AppEvent::WindowCreated {
                size: size_of(&w),
                surface: Some(surface_maker(w)),
            }));
            events
        }
        // The core drops the surface while its window still exists (wgpu issue 2302).
        MainEvent::TerminateWindow { .. } => vec![AppEvent::WindowDestroyed],
        MainEvent::WindowResized { .. } | MainEvent::ConfigChanged { .. } => {
            let mut events = configuration(app, jni);
            events.extend(app.native_window().map(|w| AppEvent::Resized(size_of(&w))));
            events
        }
        // The system bars or the cutout moved (issue 26, defect 5).
        MainEvent::ContentRectChanged { .. } => vec![content_rect(app)],
        MainEvent::Resume { .. } => vec![AppEvent::Resumed],
        MainEvent::Pause => vec![AppEvent::Paused],
        _ => vec![],
    }
}

/// Display rotation (read on the Activity) and density, as they are now.
fn configuration(app: &AndroidApp, jni: &dyn Jni) -> Vec<AppEvent> {
    let dpi = app.config().density().unwrap_or(160);
    let rotation = jni
        .display_rotation(JavaObject::Activity)
        .unwrap_or_else(|e| {
            log::warn!("regatta: display rotation not read ({e}); assuming 0");
            0
        });
    vec![
        AppEvent::Rotation(rotation),
        // Physical pixels per egui point: the display's density over Android's 160 dpi.
        AppEvent::Density(dpi as f32 / 160.0),
        content_rect(app),
    ]
}

/// The window's part free of the status bar, navigation bar and cutout (NativeActivity's
/// content rect, pixels): the bar and the panels are laid out inside it.
fn content_rect(app: &AndroidApp) -> AppEvent {
    let r = app.content_rect();
    AppEvent::ContentRect([r.left, r.top, r.right, r.bottom])
}

fn size_of(w: &ndk::native_window::NativeWindow) -> [u32; 2] {
    [w.width().max(1) as u32, w.height().max(1) as u32]
}

/// Makes wgpu surfaces for `window`; the maker holds a reference to the window, and the core
/// drops every surface on `TerminateWindow`, before the window goes.
fn surface_maker(window: ndk::native_window::NativeWindow) -> SurfaceMaker {
    Box::new(move |instance: &wgpu::Instance| {
        let raw_window = wgpu::rwh::RawWindowHandle::AndroidNdk(
            wgpu::rwh::AndroidNdkWindowHandle::new(window.ptr().cast()),
        );
        let raw_display =
            wgpu::rwh::RawDisplayHandle::Android(wgpu::rwh::AndroidDisplayHandle::new());
        // SAFETY: the window outlives the surface (see above).
        unsafe {
            instance.create_surface_unsafe(wgpu::SurfaceTargetUnsafe::RawHandle {
                raw_display_handle: Some(raw_display),
                raw_window_handle: raw_window,
            })
        }
        .map_err(|e| e.to_string())
    })
}

/// Touches to the core; volume-up toggles recording.
fn input_events(app: &AndroidApp, phone: &mut App) {
    let Ok(mut iter) = app.input_events_iter() else {
        return;
    };
    while iter.next(|event| match event {
        InputEvent::KeyEvent(k) if k.key_code() == Keycode::VolumeUp => {
            let down = k.action() == KeyAction::Down;
            phone.on_all(down.then_some(AppEvent::RecordKey));
            InputStatus::Handled
        }
        InputEvent::MotionEvent(m) => {
            phone.on_all(touch_of(m).map(AppEvent::Touch));
            InputStatus::Handled
        }
        _ => InputStatus::Unhandled,
    }) {}
}

/// An Android motion event as the HUD's [`Touch`]: the action, and every finger in
/// physical pixels. `None` for actions that are not touches (hover, scroll, buttons).
fn touch_of(m: &MotionEvent<'_>) -> Option<Touch> {
    let i = m.pointer_index();
    let action = match m.action() {
        MotionAction::Down => TouchAction::Down(i),
        MotionAction::PointerDown => TouchAction::PointerDown(i),
        MotionAction::Move => TouchAction::Move,
        MotionAction::PointerUp => TouchAction::PointerUp(i),
        MotionAction::Up => TouchAction::Up(i),
        MotionAction::Cancel => TouchAction::Cancel,
        _ => return None,
    };
    Some(Touch {
        action,
        fingers: m
            .pointers()
            .map(|p| Finger {
                id: p.pointer_id(),
                px: [p.x(), p.y()],
            })
            .collect(),
    })
}
