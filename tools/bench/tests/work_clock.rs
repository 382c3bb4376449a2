//! The budget's work clock (`regatta_bench::work_clock`) in a process of its own: its process
//! CPU clock counts every thread, so this file holds this one test and nothing runs beside it.

use regatta_bench::work_clock::{WorkClock, thread_cpu_s};

/// Work done on another thread counts; the calling thread's own work does not; a thread that
/// sleeps adds nothing. The spinning is measured in the spinning thread's own CPU time, so the
/// figures hold however busy the machine is.
#[cfg(unix)]
#[test]
fn driver_cpu_counts_the_other_threads_work_only() {
    let clock = WorkClock::DriverCpu;
    let spin_cpu = |s: f64| {
        let t0 = thread_cpu_s().expect("a thread CPU clock on unix");
        let mut x = 0u64;
        while thread_cpu_s().unwrap() - t0 < s {
            x = std::hint::black_box(x.wrapping_add(1));
        }
        x
    };
    let start = clock.now();
    std::thread::spawn(move || spin_cpu(0.1)).join().unwrap();
    let other = clock.since(start);
    assert!((0.1..0.12).contains(&other), "{other}");
    let start = clock.now();
    spin_cpu(0.1);
    let own = clock.since(start);
    assert!(own < 0.01, "{own}");
    let start = clock.now();
    std::thread::spawn(|| std::thread::sleep(std::time::Duration::from_millis(100)))
        .join()
        .unwrap();
    let slept = clock.since(start);
    assert!(slept < 0.01, "{slept}");
}
