//! Bench table `race_import`: import throughput per format and peak memory. A generated
//! 100 MB NMEA 0183 log (RMC, HDT and MWV at 10 Hz), a generated 100 MB instrument CSV
//! (time, lat, lon, sog, heading, heel at 10 Hz; `race::synth_logs`), 100 MB NMEA 2000 candump
//! and canboat JSON logs and a TCX file (`race::synth_formats`, 10 Hz) and a FIT file of 1 Hz
//! records (binary: judged in fixes per second) are loaded by `Race::from_files` (detect,
//! parse, clean, derive) on one core. Peak memory is the OS's figure (VmHWM, reset through
//! /proc/self/clear_refs before each load) above the resident size before it, compared with
//! the kept samples' size. `--quick`: 10 MB each.

use std::time::Instant;

use race::Race;
use race::synth_formats::{canboat_json_log, candump_log, fit_log, tcx_log};
use race::synth_logs::{csv_log, nmea_log};
use serde_json::json;

use crate::{BenchContext, Table};
use regatta::error::{AppError, AppResult};

/// A field of /proc/self/status in kB, as bytes.
fn status_bytes(field: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with(field))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// CPU seconds this process has used (user + system, /proc/self/stat; 10 ms ticks): on a
/// shared machine the import's own time, which wall time is not.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which is in parentheses and may hold spaces).
    let rest = &s[s.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let (utime, stime): (f64, f64) = (f.get(11)?.parse().ok()?, f.get(12)?.parse().ok()?);
    Some((utime + stime) / 100.0)
}

/// Reset the peak resident size to the current one (Linux ≥ 4.0); false where unsupported.
fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

pub fn table(ctx: &BenchContext) -> AppResult<Table> {
    let bytes = if ctx.quick { 10_000_000 } else { 100_000_000 };
    let mut t = Table::new(
        "race_import",
        "Race import throughput and peak memory per format (one core)",
        &[
            "format",
            "file MB",
            "fixes kept",
            "import s (wall)",
            "import s (CPU)",
            "MB/s (CPU)",
            "fixes/s (CPU)",
            "kept samples MB",
            "peak above start MB",
            "peak / kept samples",
        ],
    );
    for (name, file, make) in [
        (
            "NMEA 0183",
            "bench.nmea",
            (|n| nmea_log(n).into_bytes()) as fn(usize) -> Vec<u8>,
        ),
        ("CSV", "bench.csv", |n| csv_log(n).into_bytes()),
        ("NMEA 2000 candump", "bench.log", |n| {
            candump_log(n).into_bytes()
        }),
        ("NMEA 2000 canboat JSON", "bench.json", |n| {
            canboat_json_log(n).into_bytes()
        }),
        ("TCX", "bench.tcx", |n| tcx_log(n).into_bytes()),
        // Binary, 1 Hz records of 17 bytes: as many fixes as the text logs have bytes / 100.
        ("FIT", "bench.fit", |n| fit_log(n / 100)),
    ] {
        ctx.progress(format!(
            "race import: generating {} MB of {name}",
            bytes / 1_000_000
        ));
        let text = make(bytes);
        let mb = text.len() as f64 / 1e6;
        let measured = reset_peak();
        let start = status_bytes("VmRSS:").unwrap_or(0);
        let (t0, c0) = (Instant::now(), cpu_seconds());
        let race = Race::from_files(&[(file, &text)])
            .map_err(|e| AppError::new(format!("the bench {name} log did not load: {e}")))?;
        let secs = t0.elapsed().as_secs_f64();
        let cpu = cpu_seconds().zip(c0).map(|(b, a)| b - a);
        let peak = status_bytes("VmHWM:").filter(|_| measured);
        let kept: usize = race.boats.iter().map(|b| b.fixes().len()).sum();
        // Fixes with their derived values, and the logged channels (f64 time, f32 value).
        let series: usize = race.series.iter().map(|s| s.t.len()).sum();
        let kept_mb = (kept * race::Boat::BYTES_PER_SAMPLE + series * 12) as f64 / 1e6;
        let above = peak.map(|p| p.saturating_sub(start) as f64 / 1e6);
        t.row(vec![
            json!(name),
            json!(mb),
            json!(kept),
            json!(secs),
            json!(cpu),
            json!(cpu.map_or(mb / secs, |c| mb / c.max(0.01))),
            json!(cpu.map_or(kept as f64 / secs, |c| kept as f64 / c.max(0.01))),
            json!(kept_mb),
            json!(above),
            json!(above.map(|a| a / kept_mb)),
        ]);
        drop(race);
    }
    t.note(
        "Method: each log is generated in memory, then loaded once by `Race::from_files` (content \
         detection, parsing, cleaning, PCHIP derivation); the time is that one load, as CPU time \
         of the process (the import is single-threaded; wall time on a shared machine includes \
         waiting for a core) and as wall time. Peak: the \
         process's VmHWM after resetting it through /proc/self/clear_refs, minus VmRSS before the \
         load; the file's text was already resident, so the peak is what the import allocates. \
         Kept samples: fixes × `Boat::BYTES_PER_SAMPLE` plus the logged channels' samples \
         (12 bytes each: f64 time, f32 value).",
    );
    t.note(
        "Goals (issues 17, 29): ≥ 50 MB/s on one core for the text formats; FIT in fixes per \
         second; peak ≤ 3 × the kept samples' size. The NMEA and CSV importers read by hand-written field parsers (checksums, \
         timestamps) because a per-row format-description parser dominated the import.",
    );
    Ok(t)
}
