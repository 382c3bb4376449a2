//! `regatta replay`: recorded camera feeds.
//!
//! - `regatta replay synth --out DIR [--frames N] [--size WxH] [--seed S]` writes the synthetic
//!   feed of [`ar::synth`] (a wooden table seen from a hand-held camera) as a replay folder.
//! - `regatta replay check DIR` reads a replay or TUM RGB-D folder, checks every frame, and prints
//!   what it holds.
//!
//! Both print JSON on stdout: `{"dir", "frames", "duration_s", "frame_rate", "intrinsics":
//! {"fx", "fy", "cx", "cy", "width", "height"}, "planes"}`.

use std::path::{Path, PathBuf};

use ar::{ReplayFeed, SynthConfig};
use clap::{Args, Subcommand};
use serde_json::json;

use crate::error::{AppError, AppResult};
use crate::setup::inputs::parse_frame_size as parse_size;

#[derive(Debug, Args)]
pub struct ReplayArgs {
    #[command(subcommand)]
    pub command: ReplayCommand,
}

#[derive(Debug, Subcommand)]
pub enum ReplayCommand {
    /// Write a synthetic recorded feed (a textured table from a hand-held camera path).
    Synth(SynthArgs),
    /// Read a replay or TUM RGB-D folder, check every frame, print a summary.
    Check {
        /// The folder (session.json, or rgb.txt + groundtruth.txt).
        dir: PathBuf,
    },
}

#[derive(Debug, Args)]
pub struct SynthArgs {
    /// Output folder (created; existing frames are overwritten).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Number of frames (the camera path loops over them).
    #[arg(long, value_name = "N", default_value_t = SynthConfig::default().frames,
        allow_negative_numbers = true,
        value_parser = crate::cli::inputs::whole_number::<usize>("from 1 to 100000"))]
    pub frames: usize,
    /// Image size in pixels.
    #[arg(
        long,
        value_name = "WxH",
        default_value = "400x300",
        allow_hyphen_values = true
    )]
    pub size: String,
    /// Seed of the hand tremor.
    #[arg(long, default_value_t = SynthConfig::default().seed, allow_negative_numbers = true,
        value_parser = crate::cli::inputs::whole_number::<u64>("from 0 to 18446744073709551615"))]
    pub seed: u64,
    /// JPEG quality, 1–100.
    #[arg(long, default_value_t = 85, allow_negative_numbers = true,
        value_parser = crate::cli::inputs::whole_number::<u8>("from 1 to 100"))]
    pub quality: u8,
}

pub fn run(args: ReplayArgs) -> AppResult {
    match args.command {
        ReplayCommand::Synth(a) => synth(a),
        ReplayCommand::Check { dir } => print_summary(&dir),
    }
}

fn synth(a: SynthArgs) -> AppResult {
    let (width, height) = parse_size(&a.size)?;
    if a.frames == 0 || a.frames > 100_000 {
        return Err(AppError::new(format!(
            "--frames {} is out of range: give 1 to 100000 frames",
            a.frames
        )));
    }
    if !(1..=100).contains(&a.quality) {
        return Err(AppError::new(format!(
            "--quality {} is out of range: give 1 to 100",
            a.quality
        )));
    }
    let cfg = SynthConfig {
        frames: a.frames,
        width,
        height,
        seed: a.seed,
        ..SynthConfig::default()
    };
    eprintln!(
        "regatta: rendering {} synthetic frames of {width}x{height} into {}",
        a.frames,
        input::show_path(&a.out)
    );
    cfg.write(&a.out, a.quality)
        .map_err(|e| AppError::new(e.to_string()))?;
    print_summary(&a.out)
}

/// Opens the feed, decodes every frame (a truncated image is named with its line), and prints
/// the summary.
fn print_summary(dir: &Path) -> AppResult {
    let feed = ReplayFeed::open(dir).map_err(|e| AppError::new(e.to_string()))?;
    feed.check_decodes()
        .map_err(|e| AppError::new(e.to_string()))?;
    let k = feed.intrinsics;
    let planes: Vec<_> = feed
        .planes
        .iter()
        .map(|p| {
            json!({"center": p.center_pose.w_axis.truncate().to_array(),
                   "extent": p.extent.to_array()})
        })
        .collect();
    let out = json!({
        "dir": dir.display().to_string(),
        "frames": feed.len(),
        "duration_s": feed.duration(),
        "frame_rate": feed.frame_rate,
        "intrinsics": {"fx": k.fx, "fy": k.fy, "cx": k.cx, "cy": k.cy,
                       "width": k.width, "height": k.height},
        "planes": planes,
    });
    crate::terminal::print_stdout("the replay summary", &out)
}
