//! What the readers of watch, tracker and bus files (FIT, TCX, KML, NMEA 2000) share: fixes
//! and channels collected in absolute time, then handed on as one boat of a [`Source`] with
//! the common report (records, fixes, channels, date source, drops).

use super::{Coords, DEFAULT_MAX_SPEED_KN, RawBoat, RawPoint, Series, Source, Times};
use crate::track::Logged;

/// One boat's fixes and logged channels while a file is read.
#[derive(Default)]
pub(crate) struct Recorder {
    pub points: Vec<RawPoint>,
    /// (channel, unit, times, values), in the order first seen.
    channels: Vec<(&'static str, &'static str, Vec<f64>, Vec<f32>)>,
    /// The latest heading, degrees true (NaN until one is read).
    pub heading: f32,
    /// The latest speed over ground, m/s (NaN until one is read).
    pub sog: f64,
    max_sog: f64,
    /// Fixes refused for a position outside [-90, 90] × [-180, 180] or not a number.
    pub bad_positions: usize,
}

impl Recorder {
    pub(crate) fn new() -> Self {
        Recorder {
            heading: f32::NAN,
            sog: f64::NAN,
            ..Recorder::default()
        }
    }

    /// A fix at `t` (seconds since [`super::EPOCH_UNIX`]); one with an impossible position
    /// is counted, not kept.
    pub(crate) fn fix(&mut self, t: f64, lat: f64, lon: f64) {
        if !t.is_finite() || super::geo_problem(lat, lon).is_some() {
            self.bad_positions += 1;
            return;
        }
        self.points.push(RawPoint {
            t,
            c: [lat, lon],
            logged: Logged {
                heading: self.heading,
                heel: f32::NAN,
            },
            sog: self.sog,
        });
    }

    /// Speed over ground, m/s: kept for the following fixes and as the boat's speed limit.
    pub(crate) fn set_sog(&mut self, v: f64) {
        if v.is_finite() && v >= 0.0 {
            self.sog = v;
            self.max_sog = self.max_sog.max(v);
        }
    }

    /// A sample of a channel ("heading" deg, "bsp" m/s, "tws", "twd", "aws", "awa", …).
    pub(crate) fn put(&mut self, channel: &'static str, unit: &'static str, t: f64, v: f64) {
        if !(t.is_finite() && v.is_finite()) {
            return;
        }
        if channel == "heading" {
            self.heading = v as f32;
        }
        let k = match self.channels.iter().position(|c| c.0 == channel) {
            Some(k) => k,
            None => {
                self.channels.push((channel, unit, Vec::new(), Vec::new()));
                self.channels.len() - 1
            }
        };
        self.channels[k].2.push(t);
        self.channels[k].3.push(v as f32);
    }

    /// The boat `id` (named `name`) into `s`, with its channels as series and in the report.
    pub(crate) fn finish(self, s: &mut Source, id: String, name: String) {
        s.drop_rule("fixes with an impossible position", self.bad_positions);
        for (channel, unit, t, v) in self.channels {
            if !s.report.channels.iter().any(|c| c == channel) {
                s.report.channels.push(channel.to_string());
            }
            s.series.push(Series {
                boat: Some(id.clone()),
                channel: channel.into(),
                unit: unit.into(),
                t,
                v,
            });
        }
        s.boats.push(RawBoat {
            id,
            name,
            color: None,
            points: self.points,
            max_speed_mps: (1.2 * self.max_sog).max(super::knots_to_mps(DEFAULT_MAX_SPEED_KN)),
        });
    }
}

/// A geographic source in absolute time, its format named.
pub(crate) fn source(file: &str, format: &str) -> Source {
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    s.report.format = format.to_string();
    s
}
