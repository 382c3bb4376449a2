//! NMEA 2000 messages: the 29-bit CAN identifier, fast-packet reassembly and the PGNs a race
//! needs, decoded by hand. No maintained Rust crate reads candump text, reassembles fast
//! packets and decodes these PGNs (`nmea2000`/`n2k` crates target live embedded buses and
//! decode few of them); the layouts are small and published.
//!
//! Field layouts and resolutions are those of canboat's PGN database (`pgns.xml` /
//! `canboat.json`, Apache-2.0; the public reverse-engineered reference of NMEA 2000), all
//! little-endian, with the all-ones value (and the two below it) of a field meaning "not
//! available", "out of range" or "reserved":
//!
//! | PGN | name | fields (byte offset: type × resolution) |
//! | --- | --- | --- |
//! | 129025 | Position, Rapid Update (single frame) | 0: i32 latitude × 1e-7 °; 4: i32 longitude × 1e-7 ° |
//! | 129026 | COG & SOG, Rapid Update | 0: SID; 1: bits 0–1 COG reference (0 true, 1 magnetic); 2: u16 COG × 1e-4 rad; 4: u16 SOG × 0.01 m/s |
//! | 127250 | Vessel Heading | 0: SID; 1: u16 heading × 1e-4 rad; 3: i16 deviation × 1e-4 rad; 5: i16 variation × 1e-4 rad; 7: bits 0–1 reference (0 true, 1 magnetic) |
//! | 130306 | Wind Data | 0: SID; 1: u16 speed × 0.01 m/s; 3: u16 angle × 1e-4 rad; 5: bits 0–2 reference (0 true to north, 1 magnetic north, 2 apparent, 3 true boat-referenced, 4 true water-referenced) |
//! | 128259 | Speed (water referenced) | 0: SID; 1: u16 speed through water × 0.01 m/s; 3: u16 speed over ground × 0.01 m/s |
//! | 129029 | GNSS Position Data (fast packet, 43+ bytes) | 0: SID; 1: u16 date, days since 1970-01-01; 3: u32 time of day × 1e-4 s; 7: i64 latitude × 1e-16 °; 15: i64 longitude × 1e-16 ° |
//! | 129038 / 129039 | AIS Class A / B Position Report (fast packet) | 0: message id, repeat; 1: u32 MMSI; 5: i32 longitude × 1e-7 °; 9: i32 latitude × 1e-7 ° |
//!
//! Fast packet (NMEA 2000 Appendix B, as canboat implements it): a message of up to 223 bytes
//! sent as frames of 8 bytes. Byte 0 holds a 3-bit sequence counter (bits 5–7) and a 5-bit
//! frame counter (bits 0–4). Frame 0 carries the total length in byte 1 and 6 data bytes,
//! every later frame 7 data bytes. Frames of one message share the sequence counter and come in
//! order from one source address; a frame out of order or a new frame 0 abandons the message
//! (counted).

/// The parts of a 29-bit NMEA 2000 CAN identifier.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CanId {
    pub priority: u8,
    pub pgn: u32,
    pub source: u8,
}

impl CanId {
    /// ISO 11783 / J1939 layout: priority (bits 26–28), data page and PDU format (bits 16–24),
    /// PDU specific (bits 8–15: a destination address when PF < 240, else part of the PGN),
    /// source address (bits 0–7).
    pub(crate) fn from_raw(id: u32) -> CanId {
        let pf = (id >> 16) & 0xFF;
        let mut pgn = (id >> 8) & 0x3_FFFF;
        if pf < 240 {
            pgn &= 0x3_FF00;
        }
        CanId {
            priority: ((id >> 26) & 7) as u8,
            pgn,
            source: (id & 0xFF) as u8,
        }
    }
}

/// PGNs sent as fast packets that this reader decodes (others are single frames or ignored).
pub(crate) fn is_fast_packet(pgn: u32) -> bool {
    matches!(pgn, 129029 | 129038 | 129039)
}

/// A message being reassembled from one (source, PGN).
struct Partial {
    source: u8,
    pgn: u32,
    sequence: u8,
    next_frame: u8,
    len: usize,
    data: Vec<u8>,
    /// A frame was lost: the rest of this sequence's frames are dropped without counting.
    broken: bool,
}

/// Reassembles fast packets frame by frame.
#[derive(Default)]
pub(crate) struct FastPackets {
    partial: Vec<Partial>,
    /// Messages abandoned for a missing or out-of-order frame (each counted once).
    pub broken: usize,
}

impl FastPackets {
    /// One frame; the message once its last frame arrived.
    pub(crate) fn frame(&mut self, id: CanId, frame: &[u8]) -> Option<Vec<u8>> {
        if frame.len() < 2 {
            self.broken += 1;
            return None;
        }
        let (sequence, counter) = (frame[0] >> 5, frame[0] & 0x1F);
        let k = self
            .partial
            .iter()
            .position(|p| p.source == id.source && p.pgn == id.pgn);
        if counter == 0 {
            if let Some(k) = k {
                let p = self.partial.swap_remove(k);
                if !p.broken {
                    // Its last frames never came.
                    self.broken += 1;
                }
            }
            let len = frame[1] as usize;
            let mut data = Vec::with_capacity(len);
            data.extend_from_slice(&frame[2..]);
            if data.len() >= len {
                data.truncate(len);
                return Some(data);
            }
            self.partial.push(Partial {
                source: id.source,
                pgn: id.pgn,
                sequence,
                next_frame: 1,
                len,
                data,
                broken: false,
            });
            return None;
        }
        let Some(k) = k else {
            // A continuation without its first frame (lost, or the capture began mid-message).
            self.broken += 1;
            self.partial.push(Partial {
                source: id.source,
                pgn: id.pgn,
                sequence,
                next_frame: 0,
                len: 0,
                data: Vec::new(),
                broken: true,
            });
            return None;
        };
        let p = &mut self.partial[k];
        if p.broken && p.sequence == sequence {
            return None;
        }
        if p.sequence != sequence || p.next_frame != counter {
            if !p.broken || p.sequence != sequence {
                self.broken += 1;
            }
            p.broken = true;
            p.sequence = sequence;
            p.data.clear();
            return None;
        }
        p.data.extend_from_slice(&frame[1..]);
        p.next_frame += 1;
        if p.data.len() >= p.len {
            let mut p = self.partial.swap_remove(k);
            p.data.truncate(p.len);
            return Some(p.data);
        }
        None
    }
}

/// A decoded message, in SI units and degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Decoded {
    /// 129025 or 129029: degrees.
    Position { lat: f64, lon: f64 },
    /// 129029's own date and time: seconds since 1970-01-01T00:00Z.
    GnssTime { unix: f64 },
    /// 129026: course over ground, degrees (true unless `magnetic`); speed over ground, m/s.
    CogSog { cog: f64, sog: f64, magnetic: bool },
    /// 127250: degrees; deviation and variation NaN when not sent.
    Heading {
        heading: f64,
        deviation: f64,
        variation: f64,
        magnetic: bool,
    },
    /// 130306: m/s and degrees, `reference` as the PGN states it (see the table above).
    Wind {
        speed: f64,
        angle: f64,
        reference: u8,
    },
    /// 128259: speed through water, m/s.
    Stw { speed: f64 },
    /// 129038/129039: another vessel's AIS position, degrees.
    Ais { mmsi: u32, lat: f64, lon: f64 },
}

fn u16_at(d: &[u8], i: usize) -> Option<f64> {
    let v = u16::from_le_bytes(d.get(i..i + 2)?.try_into().ok()?);
    (v < 0xFFFD).then_some(v as f64)
}

fn i16_at(d: &[u8], i: usize) -> Option<f64> {
    let v = i16::from_le_bytes(d.get(i..i + 2)?.try_into().ok()?);
    (v < 0x7FFD).then_some(v as f64)
}

fn u32_at(d: &[u8], i: usize) -> Option<u32> {
    let v = u32::from_le_bytes(d.get(i..i + 4)?.try_into().ok()?);
    (v < 0xFFFF_FFFD).then_some(v)
}

fn i32_at(d: &[u8], i: usize) -> Option<f64> {
    let v = i32::from_le_bytes(d.get(i..i + 4)?.try_into().ok()?);
    (v < 0x7FFF_FFFD).then_some(v as f64)
}

fn i64_at(d: &[u8], i: usize) -> Option<f64> {
    let v = i64::from_le_bytes(d.get(i..i + 8)?.try_into().ok()?);
    (v < 0x7FFF_FFFF_FFFF_FFFD).then_some(v as f64)
}

/// Radians × 1e-4 → degrees.
fn deg(v: f64) -> f64 {
    (v * 1e-4).to_degrees()
}

/// The values of one complete message (`out` gets 0–2 of them).
pub(crate) fn decode(pgn: u32, d: &[u8], out: &mut Vec<Decoded>) {
    match pgn {
        129025 => {
            if let (Some(lat), Some(lon)) = (i32_at(d, 0), i32_at(d, 4)) {
                out.push(Decoded::Position {
                    lat: lat * 1e-7,
                    lon: lon * 1e-7,
                });
            }
        }
        129026 => {
            let magnetic = d.get(1).is_some_and(|b| b & 3 == 1);
            let (cog, sog) = (u16_at(d, 2), u16_at(d, 4));
            if cog.is_some() || sog.is_some() {
                out.push(Decoded::CogSog {
                    cog: cog.map_or(f64::NAN, deg),
                    sog: sog.map_or(f64::NAN, |v| v * 0.01),
                    magnetic,
                });
            }
        }
        127250 => {
            if let Some(h) = u16_at(d, 1) {
                out.push(Decoded::Heading {
                    heading: deg(h),
                    deviation: i16_at(d, 3).map_or(f64::NAN, deg),
                    variation: i16_at(d, 5).map_or(f64::NAN, deg),
                    magnetic: d.get(7).is_some_and(|b| b & 3 == 1),
                });
            }
        }
        130306 => {
            if let (Some(s), Some(a), Some(r)) = (u16_at(d, 1), u16_at(d, 3), d.get(5)) {
                out.push(Decoded::Wind {
                    speed: s * 0.01,
                    angle: deg(a),
                    reference: r & 7,
                });
            }
        }
        128259 => {
            if let Some(s) = u16_at(d, 1) {
                out.push(Decoded::Stw { speed: s * 0.01 });
            }
        }
        129029 => {
            if let (Some(day), Some(tod)) = (u16_at(d, 1), u32_at(d, 3)) {
                out.push(Decoded::GnssTime {
                    unix: day * 86_400.0 + tod as f64 * 1e-4,
                });
            }
            if let (Some(lat), Some(lon)) = (i64_at(d, 7), i64_at(d, 15)) {
                out.push(Decoded::Position {
                    lat: lat * 1e-16,
                    lon: lon * 1e-16,
                });
            }
        }
        129038 | 129039 => {
            if let (Some(mmsi), Some(lon), Some(lat)) = (u32_at(d, 1), i32_at(d, 5), i32_at(d, 9)) {
                out.push(Decoded::Ais {
                    mmsi,
                    lat: lat * 1e-7,
                    lon: lon * 1e-7,
                });
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn can_id_of_the_sample_frames() {
        // From candumpSample3.txt: 09F8012B is PGN 129025 (0x1F801) from source 0x2B.
        let id = CanId::from_raw(0x09F8_012B);
        assert_eq!((id.priority, id.pgn, id.source), (2, 129_025, 0x2B));
        // PDU1 (PF < 240): the PS byte is a destination, not part of the PGN (59904 request).
        let id = CanId::from_raw(0x18EA_FFAC);
        assert_eq!((id.pgn, id.source), (59_904, 0xAC));
    }

    #[test]
    fn fast_packet_reassembles_in_order_and_refuses_a_gap() {
        let id = CanId {
            priority: 3,
            pgn: 129_039,
            source: 7,
        };
        let mut fp = FastPackets::default();
        let msg: Vec<u8> = (0..20).collect();
        // Frame 0: 6 bytes, then 7 + 7.
        let mut f0 = vec![0x40, 20];
        f0.extend_from_slice(&msg[..6]);
        let mut f1 = vec![0x41];
        f1.extend_from_slice(&msg[6..13]);
        let mut f2 = vec![0x42];
        f2.extend_from_slice(&msg[13..20]);
        f2.push(0xFF);
        assert_eq!(fp.frame(id, &f0), None);
        assert_eq!(fp.frame(id, &f1), None);
        assert_eq!(fp.frame(id, &f2), Some(msg.clone()));
        // A lost frame 1: frame 2 abandons the message, counted once.
        assert_eq!(fp.frame(id, &f0), None);
        assert_eq!(fp.frame(id, &f2), None);
        assert_eq!(fp.frame(id, &f2), None);
        assert_eq!(fp.broken, 1);
        // The next message (frame 0 again) reassembles.
        assert_eq!(fp.frame(id, &f0), None);
        assert_eq!(fp.frame(id, &f1), None);
        assert_eq!(fp.frame(id, &f2), Some(msg.clone()));
        assert_eq!(fp.broken, 1);
        // Continuations without their frame 0: one message lost, not one per frame.
        assert_eq!(fp.frame(id, &f1), None);
        assert_eq!(fp.frame(id, &f2), None);
        assert_eq!(fp.broken, 2);
    }

    #[test]
    fn gnss_position_at_the_published_resolution() {
        // 129029 written from the layout: 2017-08-17 (17395 days), 12:34:56.7890,
        // 60.1234567890123456 N, 24.9876543210987654 E (1e-16 ° is 1.1e-11 m).
        let mut d = vec![0u8; 43];
        d[1..3].copy_from_slice(&17_395u16.to_le_bytes());
        d[3..7].copy_from_slice(&452_967_890u32.to_le_bytes());
        d[7..15].copy_from_slice(&601_234_567_890_123_456i64.to_le_bytes());
        d[15..23].copy_from_slice(&249_876_543_210_987_654i64.to_le_bytes());
        let mut out = Vec::new();
        decode(129_029, &d, &mut out);
        let Decoded::GnssTime { unix } = out[0] else {
            panic!("{out:?}")
        };
        assert!((unix - (1_502_928_000.0 + 45_296.789)).abs() < 1e-6);
        let Decoded::Position { lat, lon } = out[1] else {
            panic!("{out:?}")
        };
        assert!((lat - 60.123_456_789_012_35).abs() < 1e-12);
        assert!((lon - 24.987_654_321_098_77).abs() < 1e-12);
    }

    #[test]
    fn not_available_fields_are_not_values() {
        // 130306 with speed 0xFFFF: no wind; 129025 with 0x7FFFFFFF: no position.
        let mut out = Vec::new();
        decode(
            130_306,
            &[0, 0xFF, 0xFF, 0x10, 0x27, 2, 0xFF, 0xFF],
            &mut out,
        );
        decode(129_025, &[0xFF, 0xFF, 0xFF, 0x7F, 0, 0, 0, 0], &mut out);
        assert!(out.is_empty(), "{out:?}");
        // Wind 5.12 m/s at 1.0000 rad apparent.
        decode(
            130_306,
            &[0, 0x00, 0x02, 0x10, 0x27, 2, 0xFF, 0xFF],
            &mut out,
        );
        assert_eq!(
            out,
            vec![Decoded::Wind {
                speed: 5.12,
                angle: 1.0f64.to_degrees(),
                reference: 2
            }]
        );
    }
}
