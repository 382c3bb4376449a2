//! The phone-session script (docs/phone-sim.md): one step per line, `#` starts a comment.
//! Coordinates are 0–1 screen units from the top-left corner.

use std::path::{Path, PathBuf};

use crate::hud::SceneChoice;
use crate::sim_phone::backend::{Availability, FAILURE_REASONS};

/// One step of a script.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    Wait(f64),
    Tap([f64; 2]),
    Drag([f64; 2], [f64; 2], f64),
    /// Two fingers about the screen's centre: spread by the factor, turned by the degrees.
    Pinch(f64, f64),
    Pause,
    Resume,
    Rotate(u32),
    /// The phone turned upside down (180°): only the display's rotation changes; Android sends
    /// no window or configuration event.
    Flip,
    /// The system bars over the window: the status bar's and the navigation bar's heights, dp.
    Bars(f64, f64),
    Permission(bool),
    ArCore(Availability),
    /// `Some(reason code)`: tracking lost; `None`: regained.
    Tracking(Option<i32>),
    Screenshot(String),
    Record(bool),
    Scene(SceneChoice),
    /// Chooses the race of this name in the Races panel (one listed from the races folder).
    Race(String),
    /// Shares this file with the app, as Android's "Share" delivers it (a `content://` URI
    /// read through the ContentResolver); relative paths are from the script's folder.
    Open(PathBuf),
}

/// A step and the line it came from (1-based), with the line's text.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    pub number: usize,
    pub text: String,
    pub step: Step,
}

/// Parses a script; an error is one line naming the file and the line, the input escaped.
pub fn parse(path: &Path, text: &str) -> Result<Vec<Line>, String> {
    let mut lines = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let step = parse_step(content, path).map_err(|e| {
            input::one_line(&format!(
                "{}:{}: {e} in \"{}\" (see docs/phone-sim.md)",
                input::show_path(path),
                i + 1,
                input::escape_controls(content)
            ))
        })?;
        lines.push(Line {
            number: i + 1,
            text: content.to_string(),
            step,
        });
    }
    Ok(lines)
}

fn number(
    s: Option<&str>,
    what: &str,
    range: std::ops::RangeInclusive<f64>,
) -> Result<f64, String> {
    let s = s.ok_or_else(|| format!("missing {what}"))?;
    let v: f64 = s.parse().map_err(|_| format!("{what} is not a number"))?;
    if !v.is_finite() || !range.contains(&v) {
        return Err(format!(
            "{what} {} is outside {} to {}",
            input::show_number(v),
            range.start(),
            range.end()
        ));
    }
    Ok(v)
}

fn point(w: &mut std::str::SplitWhitespace<'_>, what: &str) -> Result<[f64; 2], String> {
    Ok([
        number(w.next(), &format!("{what} x"), 0.0..=1.0)?,
        number(w.next(), &format!("{what} y"), 0.0..=1.0)?,
    ])
}

fn parse_step(line: &str, script: &Path) -> Result<Step, String> {
    let mut w = line.split_whitespace();
    let verb = w.next().unwrap_or("");
    let step = match verb {
        "wait" => Step::Wait(number(w.next(), "seconds", 0.0..=600.0)?),
        "tap" => Step::Tap(point(&mut w, "the tap's")?),
        "drag" => {
            let from = point(&mut w, "the start's")?;
            let to = point(&mut w, "the end's")?;
            Step::Drag(from, to, number(w.next(), "seconds", 0.0..=60.0)?)
        }
        "pinch" => {
            let scale = number(w.next(), "scale", 0.05..=20.0)?;
            let twist = match w.next() {
                Some(d) => number(Some(d), "twist degrees", -180.0..=180.0)?,
                None => 0.0,
            };
            Step::Pinch(scale, twist)
        }
        "pause" => Step::Pause,
        "resume" => Step::Resume,
        "rotate" => {
            let d = number(w.next(), "degrees", 0.0..=270.0)?;
            if d % 90.0 != 0.0 {
                return Err("degrees must be 0, 90, 180 or 270".into());
            }
            Step::Rotate(d as u32)
        }
        "flip" => Step::Flip,
        "bars" => Step::Bars(
            number(w.next(), "the status bar's dp", 0.0..=200.0)?,
            number(w.next(), "the navigation bar's dp", 0.0..=200.0)?,
        ),
        "permission" => match w.next() {
            Some("grant") => Step::Permission(true),
            Some("deny") => Step::Permission(false),
            _ => return Err("permission takes deny or grant".into()),
        },
        "arcore" => Step::ArCore(match w.next() {
            Some("ok") => Availability::Ok,
            Some("missing") => Availability::Missing,
            Some("unsupported") => Availability::Unsupported,
            _ => return Err("arcore takes missing, unsupported or ok".into()),
        }),
        "tracking" => match (w.next(), w.next()) {
            (Some("ok"), None) => Step::Tracking(None),
            (Some("lost"), reason) => {
                let reason = reason.unwrap_or("none");
                let code = FAILURE_REASONS
                    .iter()
                    .find(|(n, _)| *n == reason)
                    .map(|(_, c)| *c)
                    .ok_or_else(|| {
                        let names: Vec<&str> = FAILURE_REASONS.iter().map(|(n, _)| *n).collect();
                        format!("tracking lost takes one of {}", names.join(", "))
                    })?;
                Step::Tracking(Some(code))
            }
            _ => return Err("tracking takes lost REASON or ok".into()),
        },
        "screenshot" => {
            let name = w.next().ok_or("missing the screenshot's name")?;
            if !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
            {
                return Err("a screenshot's name is letters, digits, - and _".into());
            }
            Step::Screenshot(name.to_string())
        }
        "record" => match w.next() {
            Some("start") => Step::Record(true),
            Some("stop") => Step::Record(false),
            _ => return Err("record takes start or stop".into()),
        },
        "race" => {
            let name = line["race".len()..].trim();
            if name.is_empty() {
                return Err("race takes the name of a race in the races folder".into());
            }
            // The name is the rest of the line (it may hold spaces).
            w.by_ref().for_each(drop);
            Step::Race(name.to_string())
        }
        "open" => {
            let file = line["open".len()..].trim();
            if file.is_empty() {
                return Err("open takes the path of a race file to share".into());
            }
            // The path is the rest of the line (it may hold spaces).
            w.by_ref().for_each(drop);
            let dir = script.parent().unwrap_or(Path::new(""));
            Step::Open(dir.join(file))
        }
        "scene" => match w.next() {
            Some("race") => Step::Scene(SceneChoice::Race),
            Some("pool") => Step::Scene(SceneChoice::Pool),
            _ => return Err("scene takes race or pool".into()),
        },
        _ => return Err("unknown step".into()),
    };
    match w.next() {
        Some(_) => Err("too many words".into()),
        None => Ok(step),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_step_parses_and_comments_are_skipped() {
        let text = "# a session\nwait 1.5\ntap 0.5 0.25 # centre\ndrag 0 0 1 1 2\npinch 2\npinch 0.5 30\npause\nresume\nrotate 90\npermission deny\narcore unsupported\ntracking lost excessive_motion\ntracking ok\nscreenshot a-1\nrecord start\nscene pool\nrace valencia p02\nopen ../races/my boat.gpx\nflip\nbars 24 48\n";
        let lines = parse(Path::new("tests/s.txt"), text).unwrap();
        let steps: Vec<Step> = lines.iter().map(|l| l.step.clone()).collect();
        assert_eq!(
            steps,
            [
                Step::Wait(1.5),
                Step::Tap([0.5, 0.25]),
                Step::Drag([0.0, 0.0], [1.0, 1.0], 2.0),
                Step::Pinch(2.0, 0.0),
                Step::Pinch(0.5, 30.0),
                Step::Pause,
                Step::Resume,
                Step::Rotate(90),
                Step::Permission(false),
                Step::ArCore(Availability::Unsupported),
                Step::Tracking(Some(3)),
                Step::Tracking(None),
                Step::Screenshot("a-1".into()),
                Step::Record(true),
                Step::Scene(SceneChoice::Pool),
                Step::Race("valencia p02".into()),
                Step::Open(PathBuf::from("tests/../races/my boat.gpx")),
                Step::Flip,
                Step::Bars(24.0, 48.0),
            ]
        );
        assert_eq!(lines[1].number, 3);
    }

    #[test]
    fn a_bad_line_is_one_escaped_line_naming_file_and_line() {
        for (text, line, words) in [
            ("wait 1\nfly 2\n", 2, "unknown step"),
            ("tap 1.5 0\n", 1, "outside"),
            ("tap 0.5\n", 1, "missing"),
            ("rotate 45\n", 1, "90"),
            ("wait 1 2\n", 1, "too many"),
            ("race\n", 1, "name of a race"),
            ("open  \n", 1, "path of a race file"),
            ("screenshot ../x\n", 1, "letters"),
            ("\n\ntap \u{1b}[31m 0\n", 3, "not a number"),
        ] {
            let e = parse(Path::new("dir/s.txt"), text).unwrap_err();
            assert!(e.starts_with(&format!("dir/s.txt:{line}: ")), "{e}");
            assert!(e.contains(words), "{e}");
            assert!(!e.contains('\u{1b}') && !e.contains('\n'), "{e:?}");
        }
    }
}
