//! The race clock's logic: playing and scrubbing agree, speeds, steps, jumps, bounds.

use ui::{RaceClock, SPEEDS, format_race_time};

#[test]
fn playing_to_t_and_scrubbing_to_t_give_the_same_time() {
    for &speed in &SPEEDS {
        // Backwards from the end, forwards from the start.
        let from = if speed < 0.0 { 3600.0 } else { -60.0 };
        let mut played = RaceClock::new((-60.0, 3600.0));
        played.scrub_to(from);
        played.set_speed(speed);
        played.play();
        // 90 frames of a 60 Hz display.
        for _ in 0..90 {
            played.advance(1.0 / 60.0);
        }
        let expected = from + 1.5 * speed;
        assert!(
            (played.time() - expected).abs() < 1e-9,
            "{speed}×: {}",
            played.time()
        );
        let mut scrubbed = RaceClock::new((-60.0, 3600.0));
        scrubbed.scrub_to(expected);
        assert!((scrubbed.time() - played.time()).abs() < 1e-9);
        // With binary-exact frame times the two agree to the bit.
        let mut exact = RaceClock::new((-60.0, 3600.0));
        exact.scrub_to(from);
        exact.set_speed(speed);
        exact.play();
        for _ in 0..96 {
            exact.advance(1.0 / 64.0);
        }
        scrubbed.scrub_to(from + 1.5 * speed);
        assert_eq!(exact.time(), scrubbed.time());
    }
}

#[test]
fn paused_clock_does_not_move_and_play_stops_at_the_end() {
    let mut c = RaceClock::new((0.0, 100.0));
    assert!(!c.advance(1.0));
    assert_eq!(c.time(), 0.0);
    c.set_speed(64.0);
    c.play();
    assert!(c.advance(1.0));
    assert_eq!(c.time(), 64.0);
    c.advance(1.0);
    assert_eq!(c.time(), 100.0);
    assert!(!c.is_playing());
    // Play at the end starts over.
    c.play();
    assert_eq!(c.time(), 0.0);
    let mut l = RaceClock::new((0.0, 100.0));
    l.looping = true;
    l.set_speed(64.0);
    l.play();
    l.advance(2.0); // 128 s: 28 s into the second loop.
    assert!((l.time() - 28.0).abs() < 1e-12 && l.is_playing());
}

#[test]
fn speeds_snap_to_the_list_and_saturate() {
    let mut c = RaceClock::new((0.0, 10.0));
    assert_eq!(c.speed(), 1.0);
    c.set_speed(5.0);
    assert_eq!(c.speed(), 4.0);
    c.set_speed(1000.0);
    assert_eq!(c.speed(), 64.0);
    c.faster();
    assert_eq!(c.speed(), 64.0);
    c.slower();
    assert_eq!(c.speed(), 32.0);
    for _ in 0..10 {
        c.slower();
    }
    assert_eq!(c.speed(), 1.0);
    // Slower in reverse stops at −1×, faster at −64×; reverse keeps the magnitude.
    c.set_speed(-5.0);
    assert_eq!(c.speed(), -4.0);
    for _ in 0..10 {
        c.slower();
    }
    assert_eq!(c.speed(), -1.0);
    for _ in 0..10 {
        c.faster();
    }
    assert_eq!(c.speed(), -64.0);
    c.set_speed(8.0);
    c.reverse();
    assert_eq!(c.speed(), -8.0);
    c.reverse();
    assert_eq!(c.speed(), 8.0);
    assert_eq!(
        SPEEDS,
        [
            -64.0, -32.0, -16.0, -8.0, -4.0, -2.0, -1.0, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0
        ]
    );
}

/// Reverse play runs race time backwards at the speed's magnitude, stops at the span's start
/// (or goes round to the end when looping), and play at the start starts from the end.
#[test]
fn reverse_play_runs_back_and_stops_at_the_start() {
    let mut c = RaceClock::new((0.0, 100.0));
    c.scrub_to(90.0);
    c.set_speed(-32.0);
    c.play();
    assert!(c.advance(0.5));
    assert_eq!(c.time(), 74.0);
    c.advance(3.0);
    assert_eq!(c.time(), 0.0);
    assert!(!c.is_playing());
    c.play();
    assert_eq!(c.time(), 100.0);
    let mut l = RaceClock::new((0.0, 100.0));
    l.looping = true;
    l.scrub_to(10.0);
    l.set_speed(-64.0);
    l.play();
    l.advance(0.5); // 10 − 32 s: 22 s before the end.
    assert!((l.time() - 78.0).abs() < 1e-12 && l.is_playing());
    // A step is |speed| race seconds in the direction asked, whichever way play runs.
    l.step(1);
    assert!((l.time() - 142.0_f64.min(100.0)).abs() < 1e-12);
}

#[test]
fn step_pauses_and_moves_by_the_step_size() {
    let mut c = RaceClock::new((0.0, 600.0));
    c.scrub_to(100.0);
    c.set_speed(8.0);
    c.play();
    c.step(1);
    assert!(!c.is_playing());
    assert_eq!(c.time(), 108.0);
    c.step(-1);
    c.step(-1);
    assert_eq!(c.time(), 92.0);
}

#[test]
fn jumps_go_to_the_start_and_walk_through_roundings() {
    let mut c = RaceClock::new((-120.0, 1800.0));
    c.scrub_to(500.0);
    c.jump_to_start();
    assert_eq!(c.time(), 0.0);
    // Data that begin after the start signal: jump to the first data.
    let mut late = RaceClock::new((15.0, 100.0));
    late.scrub_to(50.0);
    late.jump_to_start();
    assert_eq!(late.time(), 15.0);

    let roundings = [300.0, 310.0, 900.0];
    assert_eq!(c.jump_to_next(&roundings), Some(300.0));
    assert_eq!(c.jump_to_next(&roundings), Some(310.0));
    assert_eq!(c.jump_to_next(&roundings), Some(900.0));
    assert_eq!(c.jump_to_next(&roundings), None);
    assert_eq!(c.time(), 900.0);
    assert_eq!(c.jump_to_previous(&roundings), Some(310.0));
    assert_eq!(c.jump_to_previous(&roundings), Some(300.0));
    assert_eq!(c.jump_to_previous(&roundings), None);
}

#[test]
fn scrubbing_clamps_to_the_span_and_ignores_nan() {
    let mut c = RaceClock::new((0.0, 60.0));
    c.scrub_to(-5.0);
    assert_eq!(c.time(), 0.0);
    c.scrub_to(1e9);
    assert_eq!(c.time(), 60.0);
    c.scrub_to(f64::NAN);
    assert_eq!(c.time(), 60.0);
    // A degenerate span still gives the scrubber a range.
    assert_eq!(RaceClock::new((5.0, 5.0)).span(), (5.0, 6.0));
}

#[test]
fn race_time_reads_like_a_race_clock() {
    assert_eq!(format_race_time(-30.0), "-0:30");
    assert_eq!(format_race_time(0.0), "0:00");
    assert_eq!(format_race_time(725.9), "12:05");
    assert_eq!(format_race_time(3723.0), "1:02:03");
}
