//! Numbered frame sequences: the `%05d` file-name pattern, the `a..b` frame range, the `i/n` shard, and the plan of a
//! (possibly resumed) run — which frames this shard owns, which are already complete on disk, which are left to do.
//!
//! A frame counts as complete when its final file exists and is not empty: frames are written atomically
//! ([`crate::output::png::write_atomic`]), so a final file is always whole, and rerunning the same command after an
//! interruption renders only what is missing. Shards partition the range: frame `f` belongs to shard
//! `(f − start) mod n`, so `n` jobs with indices `0..n` (a Slurm array, a Kubernetes Indexed Job, GNU parallel) cover
//! every frame exactly once and can share one output directory.

use std::fmt;
use std::fs;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use crate::output::png::partial_path;

/// A file-name pattern with one printf-style frame number: `%d` or `%0Nd` (zero-padded to N digits); `%%` is a
/// literal `%`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FramePattern {
    prefix: String,
    /// Minimum digits; 0 means no padding.
    width: usize,
    suffix: String,
}

/// A pattern or range that cannot be read; the message says what was expected.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct SyntaxError(pub String);

impl FramePattern {
    /// Where the settings a sequence was drawn with are kept: beside its frames, named after the pattern
    /// (`frames/%05d.png` → `frames/sequence.png.settings`).
    pub fn settings_path(&self) -> PathBuf {
        PathBuf::from(format!("{}sequence{}.settings", self.prefix, self.suffix))
    }

    /// Reads a pattern such as `frames/%05d.png`; it must hold exactly one frame number.
    pub fn parse(pattern: &str) -> Result<FramePattern, SyntaxError> {
        let mut prefix = None;
        let mut current = String::new();
        let mut width = None;
        let mut chars = pattern.chars().peekable();
        while let Some(c) = chars.next() {
            if c != '%' {
                current.push(c);
                continue;
            }
            if chars.peek() == Some(&'%') {
                chars.next();
                current.push('%');
                continue;
            }
            let mut digits = String::new();
            while let Some(d) = chars.peek().copied().filter(char::is_ascii_digit) {
                digits.push(d);
                chars.next();
            }
            if chars.next() != Some('d') {
                return Err(SyntaxError(format!(
                    "output pattern `{pattern}`: only %d, %0Nd (frame number) and %% (a literal %) are understood"
                )));
            }
            if width.is_some() {
                return Err(SyntaxError(format!("output pattern `{pattern}` has more than one frame number")));
            }
            // printf reads the width as decimal after the zero flag; a width above 20 cannot be a u64's padding.
            let digits = digits.trim_start_matches('0');
            let w: usize = if digits.is_empty() { 0 } else { digits.parse().unwrap_or(usize::MAX) };
            if w > 20 {
                return Err(SyntaxError(format!("output pattern `{pattern}`: a frame number is at most 20 digits")));
            }
            width = Some(w);
            prefix = Some(std::mem::take(&mut current));
        }
        let (Some(width), Some(prefix)) = (width, prefix) else {
            return Err(SyntaxError(format!(
                "output `{pattern}` has no frame number: a sequence needs a pattern such as frames/%05d.png"
            )));
        };
        Ok(FramePattern { prefix, width, suffix: current })
    }

    /// Whether `text` holds a frame-number conversion (so it is meant as a pattern).
    pub fn looks_like_pattern(text: &str) -> bool {
        text.replace("%%", "").contains('%')
    }

    /// The file name of `frame`.
    pub fn path(&self, frame: u64) -> PathBuf {
        PathBuf::from(format!("{}{:0width$}{}", self.prefix, frame, self.suffix, width = self.width))
    }

    /// The text after the frame number (its extension, e.g. `.png`).
    pub fn suffix(&self) -> &str {
        &self.suffix
    }
}

impl fmt::Display for FramePattern {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let escape = |s: &str| s.replace('%', "%%");
        match self.width {
            0 => write!(f, "{}%d{}", escape(&self.prefix), escape(&self.suffix)),
            w => write!(f, "{}%0{w}d{}", escape(&self.prefix), escape(&self.suffix)),
        }
    }
}

/// Frames `start..end` (end exclusive), read from `a..b` or `a..=b` as in Rust.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    pub start: u64,
    pub end: u64,
}

impl FrameRange {
    pub fn len(&self) -> u64 {
        self.end - self.start
    }
    pub fn is_empty(&self) -> bool {
        self.end <= self.start
    }
    pub fn iter(&self) -> std::ops::Range<u64> {
        self.start..self.end
    }
}

/// Most frames one `render --frames` run takes: 4.6 hours at 60 fps. A larger range would be listed and scanned
/// before the first frame is drawn.
pub const MAX_FRAMES: u64 = 1_000_000;

impl FromStr for FrameRange {
    type Err = SyntaxError;
    fn from_str(s: &str) -> Result<FrameRange, SyntaxError> {
        let expected = || SyntaxError(format!("frame range `{s}`: expected START..END or START..=END, e.g. 0..240"));
        let (a, b, inclusive) = if let Some((a, b)) = s.split_once("..=") {
            (a, b, true)
        } else if let Some((a, b)) = s.split_once("..") {
            (a, b, false)
        } else {
            return Err(expected());
        };
        let number = |t: &str| t.trim().parse::<u64>().map_err(|_| expected());
        let (start, last) = (number(a)?, number(b)?);
        let end = if inclusive { last.checked_add(1).ok_or_else(expected)? } else { last };
        if end <= start {
            return Err(SyntaxError(format!("frame range `{s}` is empty: END must be greater than START")));
        }
        if end - start > MAX_FRAMES {
            return Err(SyntaxError(format!(
                "frame range `{s}` has {} frames; at most {MAX_FRAMES} are rendered in one run (split it into ranges)",
                end - start
            )));
        }
        Ok(FrameRange { start, end })
    }
}

impl fmt::Display for FrameRange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{}", self.start, self.end)
    }
}

/// Shard `index` of `count`: the frames `f` with `(f − start) mod count = index`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: u64,
    pub count: u64,
}

impl Shard {
    /// The whole range as one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    pub fn owns(&self, range: &FrameRange, frame: u64) -> bool {
        range.iter().contains(&frame) && (frame - range.start) % self.count == self.index
    }

    /// The frames of `range` this shard renders, in order.
    pub fn frames(self, range: FrameRange) -> impl Iterator<Item = u64> {
        let first = range.start.saturating_add(self.index);
        (first..range.end).step_by(usize::try_from(self.count).unwrap_or(usize::MAX))
    }
}

impl FromStr for Shard {
    type Err = SyntaxError;
    fn from_str(s: &str) -> Result<Shard, SyntaxError> {
        let expected = || SyntaxError(format!("shard `{s}`: expected INDEX/COUNT with 0 <= INDEX < COUNT, e.g. 0/4"));
        let (i, n) = s.split_once('/').ok_or_else(expected)?;
        let index = i.trim().parse::<u64>().map_err(|_| expected())?;
        let count = n.trim().parse::<u64>().map_err(|_| expected())?;
        if count == 0 || index >= count {
            return Err(expected());
        }
        Ok(Shard { index, count })
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// What a sequence run has to do.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SequencePlan {
    /// Frames of this shard whose files are missing, in order.
    pub todo: Vec<u64>,
    /// Frames of this shard already complete on disk.
    pub done: Vec<u64>,
}

/// Whether `path` holds a finished frame.
pub fn is_complete(path: &Path) -> bool {
    fs::metadata(path).is_ok_and(|m| m.is_file() && m.len() > 0)
}

/// Looks at the disk: which frames of `shard` are done and which are left. Leftover `.partial` files of frames that
/// are complete (a run killed between two writes of the same frame by concurrent reruns) are removed; those of
/// missing frames are overwritten when the frame is written.
pub fn plan(pattern: &FramePattern, range: FrameRange, shard: Shard) -> SequencePlan {
    let (mut todo, mut done) = (Vec::new(), Vec::new());
    for frame in shard.frames(range) {
        let path = pattern.path(frame);
        if is_complete(&path) {
            let _ = fs::remove_file(partial_path(&path));
            done.push(frame);
        } else {
            todo.push(frame);
        }
    }
    SequencePlan { todo, done }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_format_like_printf() {
        let p = FramePattern::parse("frames/%05d.png").unwrap();
        assert_eq!(p.path(42), PathBuf::from("frames/00042.png"));
        assert_eq!(p.path(1234567), PathBuf::from("frames/1234567.png"));
        assert_eq!(p.to_string(), "frames/%05d.png");
        let p = FramePattern::parse("100%%_%d.png").unwrap();
        assert_eq!(p.path(7), PathBuf::from("100%_7.png"));
        assert_eq!(p.to_string(), "100%%_%d.png");
        assert_eq!(FramePattern::parse("a%4d").unwrap().path(3), PathBuf::from("a0003"));
        assert!(FramePattern::looks_like_pattern("x%03d.png"));
        assert!(!FramePattern::looks_like_pattern("100%%.png"));
    }

    #[test]
    fn bad_patterns_say_why() {
        for (text, why) in [
            ("out.png", "no frame number"),
            ("%d_%d.png", "more than one"),
            ("%s.png", "only %d"),
            ("%05x.png", "only %d"),
            ("%099d.png", "at most 20 digits"),
        ] {
            let err = FramePattern::parse(text).unwrap_err();
            assert!(err.0.contains(why), "{text}: {err}");
        }
    }

    #[test]
    fn ranges_read_like_rust() {
        assert_eq!("0..240".parse(), Ok(FrameRange { start: 0, end: 240 }));
        assert_eq!("10..=12".parse(), Ok(FrameRange { start: 10, end: 13 }));
        for bad in ["", "5", "a..b", "3..3", "4..2", "-1..3", "0...4", "1..=18446744073709551615"] {
            assert!(bad.parse::<FrameRange>().is_err(), "{bad}");
        }
    }

    #[test]
    fn shards_partition_the_range() {
        assert_eq!("1/4".parse(), Ok(Shard { index: 1, count: 4 }));
        for bad in ["", "1", "4/4", "0/0", "-1/2", "a/b", "1/2/3"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        let range = FrameRange { start: 5, end: 17 };
        for count in 1..6 {
            let mut seen = vec![0; 17];
            for index in 0..count {
                let shard = Shard { index, count };
                for f in shard.frames(range) {
                    assert!(shard.owns(&range, f));
                    seen[f as usize] += 1;
                }
            }
            assert!(seen[..5].iter().all(|&n| n == 0));
            assert!(seen[5..].iter().all(|&n| n == 1), "{count} shards: {seen:?}");
        }
        assert_eq!(Shard { index: 2, count: 3 }.frames(range).collect::<Vec<_>>(), vec![7, 10, 13, 16]);
    }

    #[test]
    fn plans_skip_complete_frames_and_clear_their_partials() {
        let dir = std::env::temp_dir().join(format!("fractal-plan-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        let pattern = FramePattern::parse(&format!("{}/%03d.png", dir.display())).unwrap();
        fs::write(pattern.path(1), b"png").unwrap();
        fs::write(partial_path(&pattern.path(1)), b"stale").unwrap();
        fs::write(pattern.path(2), b"").unwrap();
        fs::write(partial_path(&pattern.path(3)), b"half").unwrap();
        let plan = plan(&pattern, FrameRange { start: 0, end: 5 }, Shard::ALL);
        assert_eq!(plan.done, vec![1]);
        assert_eq!(plan.todo, vec![0, 2, 3, 4]);
        assert!(!partial_path(&pattern.path(1)).exists());
        fs::remove_dir_all(dir).unwrap();
    }
}
