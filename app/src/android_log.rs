//! The Android logger's configuration: every line of the app under one logcat tag, so that
//! `adb logcat -s regatta` shows them (issue 26, defect 4). Without `with_tag`, android_logger
//! tags each line with its module path (`regatta::core::app`, `ar::arcore::ffi::session`, …)
//! and a `-s regatta` filter shows none of them. Built on the host too (android_logger compiles
//! there as a dev-dependency) so the configuration is tested without a phone.

/// The logcat tag of every line the app logs.
pub const LOG_TAG: &str = "regatta";

/// The logger `android_main` installs: info and above, tagged [`LOG_TAG`].
pub fn config() -> android_logger::Config {
    android_logger::Config::default()
        .with_max_level(log::LevelFilter::Info)
        .with_tag(LOG_TAG)
}

#[cfg(test)]
mod tests {
    /// The tag a `-s regatta` filter matches is set, not left to the module path; the level
    /// lets the session's warnings and info lines through.
    #[test]
    fn every_line_is_tagged_regatta_at_info() {
        let shown = format!("{:?}", super::config());
        assert!(shown.contains(r#"tag: Some("regatta")"#), "{shown}");
        assert!(shown.contains("Info"), "{shown}");
    }
}
