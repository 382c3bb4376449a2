//! Android entry point (native activity). Filled in by the APK work.

// std's `_Unwind_*` come from the `unwinding` crate (see app/Cargo.toml); naming the crate links it.
use unwinding as _;

#[unsafe(no_mangle)]
fn android_main(_app: android_activity::AndroidApp) {
    android_logger::init_once(
        android_logger::Config::default().with_max_level(log::LevelFilter::Info),
    );
    log::info!("regatta: android_main started");
}
