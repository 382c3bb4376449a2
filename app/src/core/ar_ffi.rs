//! ARCore through its C API (`ar::arcore::ffi::ArCore`) as the core's AR backend: Google's
//! library on the phone, the simulated ARCore (`crates/arcore_sim`) on the host, through the
//! same code.

use ar::arcore::ffi::ArCore;
use ar::arcore::{Command, Event, SessionState};
use ar::{CameraFrame, FrameSource};

use super::ar::{ArBackend, DisplayCamera};

impl ArBackend for ArCore {
    fn is_loaded(&self) -> bool {
        ArCore::is_loaded(self)
    }

    fn carry_out(&mut self, command: Command) -> Option<Event> {
        ArCore::carry_out(self, command)
    }

    /// ARCore's own driver: it also gives AR up on Androids too old for its texture mode, and
    /// closes the session (paused, destroyed off this thread) on a fall-back.
    fn drive(&mut self, state: &mut SessionState, event: Event) -> Option<&'static str> {
        ArCore::drive(self, state, event).note
    }

    fn set_display_geometry(&mut self, rotation: i32, width: u32, height: u32) {
        ArCore::set_display_geometry(self, rotation, width, height);
    }

    fn update(&mut self) -> Option<Event> {
        ArCore::update(self)
    }

    /// Camera images above the GPU's largest texture are halved to fit (PowerVR GE8320).
    fn limit_image_side(&mut self, max_side: u32) {
        ArCore::set_max_image_side(self, max_side);
    }

    /// Set before each resume: the back camera's config with the largest CPU image within
    /// the budget.
    fn set_camera_budget(&mut self, budget: ar::arcore::ffi::CameraBudget) {
        ArCore::set_camera_budget(self, budget);
    }

    /// `Display.getRotation()` on the Activity.
    fn display_rotation(&self) -> Option<i32> {
        ArCore::read_display_rotation(self)
    }

    fn next_frame(&mut self) -> Result<Option<(CameraFrame, DisplayCamera)>, ar::ArError> {
        let frame = FrameSource::next_frame(self)?;
        Ok(frame.zip(self.view))
    }
}
