//! ARCore through its C API ([`super::arcore::ArCore`], [`super::frame`]) as the app core's AR
//! backend: the same trait the simulated ARCore implements on the host.

use ar::arcore::{Command, Event};
use ar::{CameraFrame, FrameSource};

use super::arcore::ArCore;
use crate::core::ar::{ArBackend, DisplayCamera};

impl ArBackend for ArCore {
    fn is_loaded(&self) -> bool {
        ArCore::is_loaded(self)
    }

    fn carry_out(&mut self, command: Command) -> Option<Event> {
        ArCore::carry_out(self, command)
    }

    fn set_display_geometry(&mut self, rotation: i32, width: u32, height: u32) {
        ArCore::set_display_geometry(self, rotation, width, height);
    }

    fn update(&mut self) -> Option<Event> {
        ArCore::update(self)
    }

    fn next_frame(&mut self) -> Result<Option<(CameraFrame, DisplayCamera)>, ar::ArError> {
        let frame = FrameSource::next_frame(self)?;
        let display = self.view.map(|v| DisplayCamera {
            view: v.view,
            projection_gl: v.projection_gl,
            hint: v.hint,
            light_towards: v.light_towards,
        });
        Ok(frame.zip(display))
    }
}
