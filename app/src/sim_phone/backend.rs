//! A scripted AR backend for the host: the session machine's commands answered as ARCore and
//! Android would answer them (install, permission, create, configure, resume), frames from a
//! recorded feed (a replay folder, or the synthetic table) shown through the view's crop, the
//! table as the detected plane, a fixed light, and tracking lost and regained on cue. A
//! [`SimControl`] held by the driver sets the cues and advances the feed's time.

use std::sync::{Arc, Mutex, MutexGuard};

use ar::arcore::session::{status, tracking_hint};
use ar::arcore::{Command, Event};
use ar::{CameraFrame, TrackingState};
use glam::{DMat4, DVec3};

use crate::core::ar::{ArBackend, DisplayCamera};
use crate::core::camera_frame::fill_view;
use crate::core::feed::CameraFeed;

/// Whether ARCore is there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Availability {
    Ok,
    /// No ARCore library (an APK built without it).
    Missing,
    /// ARCore is installed but the device is not supported.
    Unsupported,
}

/// `AR_TRACKING_STATE_PAUSED`, and the failure reasons `tracking lost REASON` names.
const TRACKING_PAUSED: i32 = 1;
pub const FAILURE_REASONS: [(&str, i32); 6] = [
    ("none", 0),
    ("bad_state", 1),
    ("insufficient_light", 2),
    ("excessive_motion", 3),
    ("insufficient_features", 4),
    ("camera_unavailable", 5),
];

/// Display rotation and view size, as the app last gave them.
pub type Geometry = (i32, u32, u32);
/// What a frame handed out showed: the feed index, the geometry, the tracking cue.
type Shown = (usize, Geometry, Option<i32>);

/// The cues a script sets.
pub struct SimState {
    pub availability: Availability,
    pub permission: bool,
    /// `Some(reason)` while tracking is lost.
    pub lost: Option<i32>,
    /// CameraFeed time, seconds.
    pub t: f64,
    feed: CameraFeed,
    /// The feed index, geometry and cue last handed out (a frame is new when one changed).
    shown: Option<Shown>,
    /// The display rotation and view size the app last gave.
    pub geometry: Geometry,
    /// The display's rotation as Android reports it now (`Display.getRotation()`).
    pub display_rotation: i32,
    session: bool,
    running: bool,
    /// The last frame handed out, as the app got it.
    pub last_frame: Option<CameraFrame>,
}

/// The driver's handle on the simulated ARCore.
#[derive(Clone)]
pub struct SimControl(Arc<Mutex<SimState>>);

impl SimControl {
    pub fn lock(&self) -> MutexGuard<'_, SimState> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The backend the app core drives.
pub struct SimArCore(SimControl);

impl SimArCore {
    pub fn new(feed: CameraFeed) -> (SimArCore, SimControl) {
        let control = SimControl(Arc::new(Mutex::new(SimState {
            availability: Availability::Ok,
            permission: true,
            lost: None,
            t: 0.0,
            feed,
            shown: None,
            geometry: (0, 1, 1),
            display_rotation: 0,
            session: false,
            running: false,
            last_frame: None,
        })));
        (SimArCore(control.clone()), control)
    }
}

/// The light the simulated ARCore estimates: towards a high sun in the south-west.
pub fn sim_light() -> DVec3 {
    DVec3::new(-0.4, 0.8, 0.45).normalize()
}

impl ArBackend for SimArCore {
    fn is_loaded(&self) -> bool {
        self.0.lock().availability != Availability::Missing
    }

    fn carry_out(&mut self, command: Command) -> Option<Event> {
        let mut s = self.0.lock();
        match command {
            Command::RequestInstall { .. } => Some(match s.availability {
                Availability::Unsupported => Event::Install {
                    status: status::UNAVAILABLE_DEVICE_NOT_COMPATIBLE,
                    install_status: 0,
                },
                _ => Event::Install {
                    status: status::SUCCESS,
                    install_status: status::INSTALL_STATUS_INSTALLED,
                },
            }),
            Command::RequestCameraPermission | Command::CheckCameraPermission => {
                Some(Event::Permission {
                    granted: s.permission,
                })
            }
            Command::CreateSession => {
                s.session = true;
                Some(Event::Created {
                    status: status::SUCCESS,
                })
            }
            Command::Configure(_) => Some(Event::Configured {
                status: status::SUCCESS,
            }),
            Command::Resume => {
                s.running = s.session;
                Some(Event::Resumed {
                    status: status::SUCCESS,
                })
            }
            Command::Pause => {
                s.running = false;
                None
            }
            Command::Tell(_) | Command::FallBack(_) => None,
        }
    }

    fn set_display_geometry(&mut self, rotation: i32, width: u32, height: u32) {
        self.0.lock().geometry = (rotation, width, height);
    }

    fn display_rotation(&self) -> Option<i32> {
        Some(self.0.lock().display_rotation)
    }

    fn update(&mut self) -> Option<Event> {
        let s = self.0.lock();
        (!s.running).then_some(Event::Updated {
            status: status::ERROR_SESSION_PAUSED,
        })
    }

    fn next_frame(&mut self) -> Result<Option<(CameraFrame, DisplayCamera)>, ar::ArError> {
        let mut s = self.0.lock();
        let i = s.feed.index_at(s.t);
        let key = (i, s.geometry, s.lost);
        if s.shown == Some(key) {
            return Ok(None);
        }
        let mut frame = s.feed.frame(i)?;
        let (_, w, h) = s.geometry;
        let (display, _) = fill_view(&frame.intrinsics, [w, h]);
        frame.display_uv = glam::Affine2::from_cols_array(&[
            display[0][0] as f32,
            display[1][0] as f32,
            display[0][1] as f32,
            display[1][1] as f32,
            display[0][2] as f32,
            display[1][2] as f32,
        ]);
        frame.tracking = match s.lost {
            Some(_) => TrackingState::Paused,
            None => TrackingState::Tracking,
        };
        let camera = DisplayCamera {
            view: frame.camera_to_world.as_dmat4().inverse(),
            projection_gl: view_projection_gl(&frame.intrinsics, display, [w, h]),
            hint: s.lost.and_then(|r| tracking_hint(TRACKING_PAUSED, r)),
            light_towards: Some(sim_light()),
        };
        s.shown = Some(key);
        s.last_frame = Some(frame.clone());
        Ok(Some((frame, camera)))
    }
}

/// The OpenGL projection of the view of `size` pixels that shows the image through `display`
/// (a crop): the image's intrinsics carried into view pixels.
pub fn view_projection_gl(
    k: &ar::Intrinsics,
    display: crate::core::camera_frame::Display,
    size: [u32; 2],
) -> DMat4 {
    let (iw, ih) = (f64::from(k.width), f64::from(k.height));
    let (w, h) = (f64::from(size[0].max(1)), f64::from(size[1].max(1)));
    // Image pixel x = (a u + c) iw with u = x_view / w: x_img = (a iw / w) x_view + c iw.
    let sx = display[0][0] * iw / w;
    let sy = display[1][1] * ih / h;
    let view = ar::Intrinsics {
        fx: k.fx / sx,
        fy: k.fy / sy,
        cx: (k.cx - display[0][2] * iw) / sx,
        cy: (k.cy - display[1][2] * ih) / sy,
        width: size[0].max(1),
        height: size[1].max(1),
    };
    let wgpu = view.projection_wgpu(0.01, 100.0);
    // Clip z from 0..w back to OpenGL's −w..w: z_gl = 2 z − w.
    let to_gl = DMat4::from_cols_array(&[
        1.0, 0.0, 0.0, 0.0, //
        0.0, 1.0, 0.0, 0.0, //
        0.0, 0.0, 2.0, 0.0, //
        0.0, 0.0, -1.0, 1.0,
    ]);
    to_gl * wgpu
}
