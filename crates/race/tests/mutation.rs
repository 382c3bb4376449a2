//! The byte mutations the fuzz tests apply to a file (`fuzz.rs`, `fuzz_formats.rs`): flips,
//! deletions, insertions of syntax, truncation, duplication, digit changes, swapped and
//! repeated lines. Each test passes the syntax its formats are made of.

use proptest::prelude::*;

#[derive(Debug, Clone)]
pub enum Edit {
    Flip(usize, u8),
    Delete(usize, usize),
    Insert(usize, Vec<u8>),
    Truncate(usize),
    Duplicate(usize, usize),
    /// Change one digit to another: keeps the syntax, moves a point or a time.
    Digit(usize, u8),
    /// Swap two lines: out-of-order samples, misplaced elements.
    SwapLines(usize, usize),
    /// Repeat a line: duplicate timestamps, frozen fixes.
    RepeatLine(usize),
}

/// One edit: random bytes or one of `syntax` inserted, or any of the others (digit changes and
/// line swaps twice as often: they keep a file parseable and move its data).
pub fn edit(syntax: &'static [&'static [u8]]) -> impl Strategy<Value = Edit> {
    let insert = prop_oneof![
        prop::collection::vec(any::<u8>(), 1..8),
        prop::sample::select(syntax).prop_map(<[u8]>::to_vec),
    ];
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Flip(i, b)),
        (any::<usize>(), 1usize..40).prop_map(|(i, n)| Edit::Delete(i, n)),
        (any::<usize>(), insert).prop_map(|(i, v)| Edit::Insert(i, v)),
        any::<usize>().prop_map(Edit::Truncate),
        (any::<usize>(), 1usize..200).prop_map(|(i, n)| Edit::Duplicate(i, n)),
        (any::<usize>(), 0u8..10).prop_map(|(i, d)| Edit::Digit(i, d)),
        (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::SwapLines(i, j)),
        any::<usize>().prop_map(Edit::RepeatLine),
        (any::<usize>(), 0u8..10).prop_map(|(i, d)| Edit::Digit(i, d)),
        (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::SwapLines(i, j)),
    ]
}

/// `b` with `edits` applied in turn (positions taken modulo the current length).
pub fn apply(mut b: Vec<u8>, edits: &[Edit]) -> Vec<u8> {
    let lines =
        |b: &[u8]| -> Vec<Vec<u8>> { b.split(|&c| c == b'\n').map(<[u8]>::to_vec).collect() };
    for e in edits {
        let n = b.len().max(1);
        match e {
            Edit::Flip(i, x) => {
                if !b.is_empty() {
                    b[i % n] = *x;
                }
            }
            Edit::Delete(i, k) => {
                let s = (i % n).min(b.len());
                b.drain(s..(s + k).min(b.len()));
            }
            Edit::Insert(i, v) => {
                let s = (i % n).min(b.len());
                b.splice(s..s, v.iter().copied());
            }
            Edit::Truncate(i) => b.truncate(i % n),
            Edit::Duplicate(i, k) => {
                let s = (i % n).min(b.len());
                let e = (s + k).min(b.len());
                let piece = b[s..e].to_vec();
                b.splice(e..e, piece);
            }
            Edit::Digit(i, d) => {
                let digits: Vec<usize> = (0..b.len()).filter(|&k| b[k].is_ascii_digit()).collect();
                if !digits.is_empty() {
                    b[digits[i % digits.len()]] = b'0' + d;
                }
            }
            Edit::SwapLines(i, j) => {
                let mut l = lines(&b);
                let k = l.len();
                l.swap(i % k, j % k);
                b = l.join(&b'\n');
            }
            Edit::RepeatLine(i) => {
                let mut l = lines(&b);
                let k = i % l.len();
                let x = l[k].clone();
                l.insert(k, x);
                b = l.join(&b'\n');
            }
        }
    }
    b
}
