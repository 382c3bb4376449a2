//! The clock the budget's timed estimate reads (docs/benchmarks.md, "Budget: run to run").
//!
//! On a GPU, a frame and the throughput kernel are timed in wall seconds between submit and
//! finish, interleaved so that a load on the GPU slows both. On a CPU adapter (lavapipe) the
//! "GPU" is the driver's threads on the same cores that every other process on the machine
//! uses: wall time then counts the seconds those threads waited for a core, and five runs on a
//! busy two-core machine disagreed by up to 61 % even interleaved, because the frame (many
//! short raster jobs) and the kernel (one long dispatch) wait differently. There the work is
//! the CPU time the driver's threads spent: the process's CPU time minus the calling thread's
//! own (its command recording and validation are not GPU work). A load elsewhere on the
//! machine does not change how many CPU-seconds the driver needs, so it cancels in the ratio
//! without having to hit both measurements alike. Tested in its own process
//! (`app/tests/work_clock.rs`): the process clock counts every thread, so other tests running
//! beside it would count too.

use std::time::Instant;

/// How work on the adapter is timed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorkClock {
    /// Wall seconds from submit to finish (a real GPU).
    Wall,
    /// CPU seconds of the driver's threads (a CPU adapter).
    DriverCpu,
}

/// A reading of the clock.
#[derive(Debug, Clone, Copy)]
pub struct Reading {
    wall: Instant,
    process_cpu_s: f64,
    thread_cpu_s: f64,
}

impl WorkClock {
    /// The clock for `adapter`: driver CPU time on a CPU adapter where the platform has
    /// per-process and per-thread CPU clocks, else wall time.
    pub fn for_adapter(info: &wgpu::AdapterInfo) -> WorkClock {
        if info.device_type == wgpu::DeviceType::Cpu && cpu_clocks().is_some() {
            WorkClock::DriverCpu
        } else {
            WorkClock::Wall
        }
    }

    /// What [`WorkClock::for_adapter`] chose, in words for the table notes.
    pub fn describe(self) -> &'static str {
        match self {
            WorkClock::Wall => "wall time from submit to finish",
            WorkClock::DriverCpu => {
                "the CPU time of the driver's threads (the process's CPU time less the \
                 recording thread's): a CPU adapter shares its cores with the machine"
            }
        }
    }

    pub fn now(self) -> Reading {
        let (process_cpu_s, thread_cpu_s) = cpu_clocks().unwrap_or((0.0, 0.0));
        Reading {
            wall: Instant::now(),
            process_cpu_s,
            thread_cpu_s,
        }
    }

    /// Seconds of work since `start`, on this clock.
    pub fn since(self, start: Reading) -> f64 {
        match self {
            WorkClock::Wall => start.wall.elapsed().as_secs_f64(),
            WorkClock::DriverCpu => {
                let now = self.now();
                let process = now.process_cpu_s - start.process_cpu_s;
                let own = now.thread_cpu_s - start.thread_cpu_s;
                (process - own).max(0.0)
            }
        }
    }
}

/// The calling thread's CPU seconds, where the platform has the clock.
pub fn thread_cpu_s() -> Option<f64> {
    cpu_clocks().map(|(_, thread)| thread)
}

/// (process CPU seconds, calling thread's CPU seconds), where the platform has both clocks.
#[cfg(unix)]
fn cpu_clocks() -> Option<(f64, f64)> {
    fn read(clock: libc::clockid_t) -> Option<f64> {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid, writable timespec; the clock ids are the POSIX constants.
        let rc = unsafe { libc::clock_gettime(clock, &mut ts) };
        (rc == 0).then_some(ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9)
    }
    Some((
        read(libc::CLOCK_PROCESS_CPUTIME_ID)?,
        read(libc::CLOCK_THREAD_CPUTIME_ID)?,
    ))
}

#[cfg(not(unix))]
fn cpu_clocks() -> Option<(f64, f64)> {
    None
}
