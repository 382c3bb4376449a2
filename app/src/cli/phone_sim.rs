//! `regatta phone-sim --script FILE --out DIR [--replay DIR] [--device pixel2xl|a54]
//! [--size WxH]`: the phone app headless, driven by a script (docs/phone-sim.md). Writes
//! `DIR/log.jsonl` (one line per step) and the screenshots; prints a summary (JSON) on stdout.
//! A bad script line is one line on stderr naming the file and line, exit 2; a failed step,
//! exit 1.

use std::path::PathBuf;

use clap::Args;
use serde_json::json;

use crate::core::feed::CameraFeed;
use crate::error::{AppError, AppResult};
use crate::phone_sim::{PhoneSim, run_script, script};
use crate::sim_phone::device::Device;

#[derive(Debug, Args)]
pub struct PhoneSimArgs {
    /// The session script: one step per line (docs/phone-sim.md).
    #[arg(long, value_name = "FILE")]
    pub script: PathBuf,
    /// Folder for log.jsonl, the screenshots and the recordings (created).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The camera feed the simulated ARCore shows (replay folder); the synthetic table without.
    #[arg(long, value_name = "DIR")]
    pub replay: Option<PathBuf>,
    /// Which phone's screen and density.
    #[arg(long, value_enum, default_value_t)]
    pub device: Device,
    /// The screen in portrait, WIDTHxHEIGHT pixels; half the phone's pixels per side without
    /// it (the layout in dp stays the phone's).
    #[arg(long, value_name = "WxH", allow_hyphen_values = true)]
    pub size: Option<String>,
    /// The simulated ARCore library (crates/arcore_sim's cdylib, `cargo build -p arcore_sim`):
    /// the phone's own ARCore glue runs against it. Without it, a scripted stand-in answers.
    #[arg(long, value_name = "FILE")]
    pub arcore_lib: Option<PathBuf>,
}

/// Largest phone-sim script, bytes: 1 MiB, thousands of times the longest script in
/// app/tests/phone (a few KiB); `/dev/zero` read until memory ran out (2.1 GB) before.
pub const MAX_SCRIPT_BYTES: u64 = 1 << 20;

pub fn run(a: PhoneSimArgs) -> AppResult {
    let bytes = input::read_capped(
        &a.script,
        MAX_SCRIPT_BYTES,
        "a phone-sim script",
        input::text_sniff,
    )
    .map_err(|e| AppError::new(e.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        AppError::new(format!(
            "{} is not UTF-8 text (byte {})",
            input::show_path(&a.script),
            e.utf8_error().valid_up_to()
        ))
    })?;
    let lines = match script::parse(&a.script, &text) {
        Ok(l) => l,
        Err(e) => {
            eprintln!("regatta: {e}");
            std::process::exit(2);
        }
    };
    let size = match &a.size {
        Some(s) => super::render::parse_size(s)?,
        None => a.device.host_size(),
    };
    std::fs::create_dir_all(&a.out)
        .map_err(|e| AppError::new(format!("{}: {e}", input::show_path(&a.out))))?;
    let ppp = a.device.pixels_per_point(size);
    let data = Some(a.out.clone());
    let mut sim = match &a.arcore_lib {
        Some(lib) => {
            PhoneSim::with_ffi(lib, a.replay.as_deref(), size, ppp, data).map_err(AppError::new)?
        }
        None => PhoneSim::new(CameraFeed::for_phone(a.replay.as_deref())?, size, ppp, data),
    };
    // The Races panel lists $REGATTA_RACES_DIR, else OUT/races.
    sim.app
        .set_races_dir(crate::core::app::host_races_dir(Some(&a.out)));
    let failed = run_script(&mut sim, &lines, &a.out).map_err(AppError::new)?;
    let summary = json!({
        "steps": lines.len(),
        "failed": failed,
        "log": a.out.join("log.jsonl"),
        "gpu": sim.app.describe_gpu(),
        "status": sim.app.status(),
    });
    crate::terminal::print_stdout(
        "the session summary",
        &serde_json::to_string_pretty(&summary)?,
    )?;
    if failed > 0 {
        return Err(AppError::new(format!(
            "{failed} of {} steps failed (see {})",
            lines.len(),
            input::show_path(&a.out.join("log.jsonl"))
        )));
    }
    Ok(())
}
