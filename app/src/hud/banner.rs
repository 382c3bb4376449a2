//! The one line the phone shows over the scene about the AR session: why there is no camera
//! (and that the 3D race view runs instead), what to do while ARCore is not tracking, and
//! what to do next (tap the table). A pure function of the session's state, so every message
//! is tested on the host.

use ar::arcore::SessionState;

/// How the banner looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tone {
    /// A next step ("tap the table …").
    Hint,
    /// Something is missing or wrong (no camera, not tracking).
    Warning,
}

/// What the session is doing, as the banner needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArStatus<'a> {
    pub session: SessionState,
    /// ARCore's tracking hint for the last frame (`ar::arcore::session::tracking_hint`), `None`
    /// while tracking.
    pub tracking_hint: Option<&'a str>,
    /// A camera frame has arrived since the session started running.
    pub has_frame: bool,
    /// The scene (course or pool) stands on the table.
    pub placed: bool,
    /// What a tap places: "course" or "pool".
    pub what: &'a str,
    /// The last message the session asked to tell (e.g. the camera is busy), shown while paused.
    pub note: Option<&'a str>,
}

/// The banner's text and tone, or `None` when there is nothing to say (tracking, placed).
pub fn banner(s: &ArStatus<'_>) -> Option<(String, Tone)> {
    use SessionState as S;
    let warn = |m: &str| Some((m.to_string(), Tone::Warning));
    match s.session {
        // The message names the cause and says that the 3D race view runs without the camera.
        S::Unavailable(why) => Some((why.message(), Tone::Warning)),
        S::Start | S::CheckingInstall => Some(("Checking ARCore…".to_string(), Tone::Hint)),
        S::InstallRequested => Some((
            "Installing Google Play Services for AR; Regatta goes on when you come back."
                .to_string(),
            Tone::Hint,
        )),
        S::AwaitingPermission => Some((
            "Allow the camera to see the race on your table.".to_string(),
            Tone::Hint,
        )),
        S::Creating | S::Configuring(_) | S::Resuming => {
            Some(("Starting the camera…".to_string(), Tone::Hint))
        }
        S::Paused => s.note.and_then(warn),
        S::Running if !s.has_frame => Some(("Starting the camera…".to_string(), Tone::Hint)),
        S::Running => match (s.tracking_hint, s.placed) {
            (Some(h), _) => warn(h),
            (None, false) => Some((
                format!("Tap the table to place the {}.", s.what),
                Tone::Hint,
            )),
            (None, true) => None,
        },
    }
}

/// The label of the banner's button, where the user can do something about it: after the
/// camera was refused, ask for it again (issue 26, defect 6).
pub fn button(session: SessionState) -> Option<&'static str> {
    match session {
        SessionState::Unavailable(ar::arcore::Unavailable::PermissionRefused) => {
            Some("Allow the camera")
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ar::arcore::session::{status, tracking_hint, unavailable};
    use ar::arcore::{LightMode, Unavailable};

    fn status_of(session: SessionState) -> ArStatus<'static> {
        ArStatus {
            session,
            tracking_hint: None,
            has_frame: true,
            placed: false,
            what: "course",
            note: None,
        }
    }

    fn text(s: &ArStatus<'_>) -> String {
        banner(s).map(|(t, _)| t).unwrap_or_default()
    }

    /// Each way to lose the camera names its cause and says the race runs in 3D without it.
    #[test]
    fn without_ar_the_banner_says_why_and_that_the_3d_view_runs() {
        let cases = [
            (Unavailable::PermissionRefused, "Camera permission refused"),
            (
                unavailable(status::UNAVAILABLE_ARCORE_NOT_INSTALLED),
                "was not installed",
            ),
            (
                unavailable(status::UNAVAILABLE_DEVICE_NOT_COMPATIBLE),
                "does not support ARCore",
            ),
            (Unavailable::LibraryMissing, "no ARCore library"),
            (unavailable(status::UNAVAILABLE_APK_TOO_OLD), "too old"),
        ];
        for (why, cause) in cases {
            let (msg, tone) = banner(&status_of(SessionState::Unavailable(why))).unwrap();
            assert!(msg.contains(cause), "{msg}");
            assert!(msg.contains("race in 3D without the camera"), "{msg}");
            assert_eq!(tone, Tone::Warning);
        }
    }

    /// Running: not tracking says what ARCore wants (move slowly, more light); tracking but not
    /// placed says to tap; tracking and placed says nothing.
    #[test]
    fn while_running_the_banner_follows_tracking_and_placement() {
        let mut s = status_of(SessionState::Running);
        // ARCore: PAUSED (1), reason NONE (0) / EXCESSIVE_MOTION (3) / INSUFFICIENT_LIGHT (2).
        s.tracking_hint = tracking_hint(1, 0);
        assert_eq!(
            banner(&s),
            Some((
                "Move the phone slowly to find the table.".to_string(),
                Tone::Warning
            ))
        );
        s.tracking_hint = tracking_hint(1, 3);
        assert!(text(&s).contains("more slowly"));
        s.tracking_hint = tracking_hint(1, 2);
        assert!(text(&s).contains("light"));
        // Not tracking outranks "tap", even once placed.
        s.placed = true;
        assert!(text(&s).contains("light"));
        s.tracking_hint = tracking_hint(0, 0);
        assert_eq!(banner(&s), None);
        s.placed = false;
        assert_eq!(
            banner(&s),
            Some(("Tap the table to place the course.".to_string(), Tone::Hint))
        );
        s.what = "pool";
        assert_eq!(text(&s), "Tap the table to place the pool.");
        s.has_frame = false;
        assert_eq!(text(&s), "Starting the camera…");
    }

    #[test]
    fn on_the_way_to_the_camera_the_banner_says_what_happens() {
        assert_eq!(text(&status_of(SessionState::Start)), "Checking ARCore…");
        assert!(text(&status_of(SessionState::AwaitingPermission)).contains("Allow the camera"));
        assert!(text(&status_of(SessionState::InstallRequested)).contains("Installing"));
        for s in [
            SessionState::Creating,
            SessionState::Configuring(LightMode::EnvironmentalHdr),
            SessionState::Resuming,
        ] {
            assert_eq!(text(&status_of(s)), "Starting the camera…");
        }
        // Paused in the background says nothing; paused because the camera is busy says so.
        assert_eq!(banner(&status_of(SessionState::Paused)), None);
        let mut p = status_of(SessionState::Paused);
        p.note = Some("The camera is in use by another app; Regatta will retry when you return.");
        assert!(text(&p).contains("in use by another app"));
    }
}
