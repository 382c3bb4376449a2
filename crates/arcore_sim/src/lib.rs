//! A host build of the ARCore C API subset Regatta calls (`ar::arcore::ffi::api` lists it),
//! with the names and C signatures of `arcore_c_api.h`, so that the app's real FFI
//! (`ar::arcore::ffi`, loaded with libloading) runs on the host: `REGATTA_ARCORE_LIB` names
//! this library (`target/<profile>/libarcore_sim.so`).
//!
//! It plays a replay folder (`ar::replay`; `REGATTA_SIM_REPLAY` or `RegattaSim_openReplay`),
//! else the synthetic table feed (`ar::synth`, 640 × 480): camera poses and intrinsics, the
//! image as a phone gives it (YUV 4:2:0, luma rows padded to 704 bytes for 640 pixels, NV21
//! chroma with pixel stride 2: [`feed::PhoneImage`]), the display-oriented camera for the
//! display geometry and rotation ([`display`]), the table as a detected plane, the light
//! estimate (ambient and Environmental HDR), and scripted tracking states, session errors,
//! camera and ArCoreApk availability ([`control`]: the `RegattaSim_*` functions).
//!
//! Every object is counted while alive (`RegattaSim_liveObjects`), every call by name
//! (`RegattaSim_callCount`). One simulator per process: the C API has no context argument.
//!
//! Not simulated: ARCore's tracking itself (poses are the replay's), hit tests through
//! `ArFrame_hitTest` (the app intersects the planes itself: `ar::arcore::hit_test`), anchors,
//! depth, GL textures.

// Every export's safety contract is that of its `arcore_c_api.h` counterpart: live objects
// made by this library, out pointers valid for the writes the header documents.
#![allow(clippy::missing_safety_doc)]

pub mod camera_config;
pub mod cameras;
pub mod control;
pub mod display;
pub mod feed;
pub mod frame_api;
pub mod objects;
pub mod session_api;
pub mod state;

/// The simulator library that cargo built next to the running test or program: a crate that
/// declares `arcore_sim` a (dev-)dependency gets `libarcore_sim.so` built into
/// `target/<profile>/deps/` (the cdylib comes with the rlib); this finds the newest one there
/// or in `target/<profile>/`. `None` when there is none.
pub fn built_library() -> Option<std::path::PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let name = format!(
        "{}arcore_sim{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    );
    let dir = exe.parent()?;
    // Tests run from target/<profile>/deps, programs from target/<profile>.
    let dirs = [
        dir.to_path_buf(),
        dir.join("deps"),
        dir.parent()?.to_path_buf(),
    ];
    dirs.iter()
        .filter_map(|d| std::fs::read_dir(d).ok())
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                n == name
                    || (n.starts_with("libarcore_sim-")
                        && n.ends_with(std::env::consts::DLL_SUFFIX))
            })
        })
        .max_by_key(|p| std::fs::metadata(p).and_then(|m| m.modified()).ok())
}
