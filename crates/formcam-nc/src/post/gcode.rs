//! The G-code writers (Sinumerik 840D, ISO, LinuxCNC, Marlin): one engine,
//! one [`Style`] per dialect.

use rayon::prelude::*;

use crate::modulo::{self, TURN};
use crate::num::{self, DEG, FEED, FEED_FINE, MM, Out, Word};
use crate::post::push_comment_text;
use crate::program::nc_travel;
use crate::{Block, Feed, Motion, NcError, Program};

/// Which program heading and end a dialect writes.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Frame {
    Sinumerik,
    Iso,
    LinuxCnc,
    Marlin,
}

/// How inverse-time blocks are written.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Inverse {
    /// `G93` with `F = 60 / t` (1/min), `G94` again at the next per-minute block.
    G93,
    /// Converted to a per-minute feed `F = travel / t * 60`, the travel being
    /// the Euclidean norm of the axis deltas in NC units (FiberPath's way).
    Convert,
}

/// How a modulo rotary axis is written.
#[derive(Clone, Copy, PartialEq, Eq)]
enum ModWrite {
    /// `G92 A..` before a re-zeroed block; the angle less the re-zeroed turns.
    Rezero,
    /// `A=ACP(v)` / `A=ACN(v)`, `v` in `[0, 360)` (Sinumerik).
    Acp,
    /// `A v` / `A-v`, `v` in `[0, 360)`: LinuxCNC's wrapped rotary axes.
    Signed,
}

/// Which axis names a dialect can address.
#[derive(Clone, Copy)]
enum Axes {
    /// Exactly these single letters.
    Letters(&'static [&'static str], &'static str),
    /// Sinumerik: a free single letter (`X12.5`) or an identifier (`J1=12.5`).
    Sinumerik,
}

/// A G-code dialect's conventions.
pub(super) struct Style {
    name: &'static str,
    frame: Frame,
    axes: Axes,
    line_numbers: bool,
    motion: [&'static str; 2],
    parens: bool,
    keep_point: bool,
    inverse: Inverse,
    modulo: ModWrite,
}

const NINE: &[&str] = &["X", "Y", "Z", "A", "B", "C", "U", "V", "W"];
const NINE_TEXT: &str = "X, Y, Z, A, B, C, U, V, W";

/// Sinumerik 840D.
pub(super) const SINUMERIK: Style = Style {
    name: "sinumerik-840d",
    frame: Frame::Sinumerik,
    axes: Axes::Sinumerik,
    line_numbers: true,
    motion: ["G0", "G1"],
    parens: false,
    keep_point: false,
    inverse: Inverse::G93,
    modulo: ModWrite::Acp,
};

/// ISO 6983 / Fanuc.
pub(super) const ISO: Style = Style {
    name: "iso",
    frame: Frame::Iso,
    axes: Axes::Letters(NINE, NINE_TEXT),
    line_numbers: false,
    motion: ["G00", "G01"],
    parens: true,
    keep_point: true,
    inverse: Inverse::G93,
    modulo: ModWrite::Rezero,
};

/// LinuxCNC.
pub(super) const LINUXCNC: Style = Style {
    name: "linuxcnc",
    frame: Frame::LinuxCnc,
    axes: Axes::Letters(NINE, NINE_TEXT),
    line_numbers: false,
    motion: ["G0", "G1"],
    parens: true,
    keep_point: false,
    inverse: Inverse::G93,
    modulo: ModWrite::Signed,
};

/// Marlin with X, A, B (and Y, Z, C).
pub(super) const MARLIN: Style = Style {
    name: "marlin-xab",
    frame: Frame::Marlin,
    axes: Axes::Letters(&["X", "Y", "Z", "A", "B", "C"], "X, Y, Z, A, B, C"),
    line_numbers: false,
    motion: ["G0", "G1"],
    parens: false,
    keep_point: false,
    inverse: Inverse::Convert,
    modulo: ModWrite::Rezero,
};

impl Style {
    /// Comments in parentheses (`(…)`), which cannot hold `(` or `)`.
    pub(super) fn parens(&self) -> bool {
        self.parens
    }
}

/// Single letters Sinumerik reserves for other addresses.
const SINUMERIK_RESERVED: &str = "DFGHLMNOPRST";
const SINUMERIK_TEXT: &str = "a single letter other than D F G H L M N O P R S T, \
     or an identifier like J1 (written J1=value)";

/// The word written before each axis value (`" X"`, `" J1="`) and its decimals.
fn axis_words(p: &Program, st: &Style) -> Result<Vec<(AxisWord, u32)>, NcError> {
    p.axes
        .iter()
        .map(|a| {
            let unsupported = |allowed| NcError::UnsupportedAxis {
                dialect: st.name,
                axis: a.name.clone(),
                allowed,
            };
            let word = match st.axes {
                Axes::Letters(list, text) => {
                    if !list.contains(&a.name.as_str()) {
                        return Err(unsupported(text));
                    }
                    a.name.clone()
                }
                Axes::Sinumerik => {
                    let mut chars = a.name.chars();
                    let first_ok = chars.next().is_some_and(|c| c.is_ascii_uppercase());
                    let rest_ok =
                        chars.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_');
                    if !(first_ok && rest_ok) {
                        return Err(unsupported(SINUMERIK_TEXT));
                    }
                    if a.name.len() == 1 {
                        if SINUMERIK_RESERVED.contains(a.name.as_str()) {
                            return Err(unsupported(SINUMERIK_TEXT));
                        }
                        a.name.clone()
                    } else {
                        format!("{}=", a.name)
                    }
                }
            };
            let word = format!(" {word}");
            let word = match Word::new(&word) {
                Some(w) => AxisWord::Short(w),
                None => AxisWord::Long(word),
            };
            Ok((word, if a.rotary { DEG } else { MM }))
        })
        .collect()
}

/// The text before an axis value: short ones are written in one store.
enum AxisWord {
    Short(Word),
    Long(String),
}

impl AxisWord {
    #[inline(always)]
    fn push(&self, out: &mut Out) {
        match self {
            AxisWord::Short(w) => out.word(w),
            AxisWord::Long(s) => out.s(s),
        }
    }
}

/// N numbers 10, 20, … when the dialect numbers its blocks.
struct LineNo {
    on: bool,
    next: u64,
}

impl LineNo {
    fn push(&mut self, out: &mut Out) {
        if self.on {
            out.c('N');
            num::push_uint(out, self.next);
            out.c(' ');
            self.next += 10;
        }
    }
}

fn comment_line(out: &mut Out, st: &Style, text: &str) {
    if st.parens {
        out.c('(');
        push_comment_text(out, text, true);
        out.s(")\n");
    } else {
        out.s("; ");
        push_comment_text(out, text, false);
        out.c('\n');
    }
}

fn header(out: &mut Out, p: &Program, st: &Style, ln: &mut LineNo) {
    if st.frame == Frame::Iso {
        out.s("%\nO0001");
        if !p.name.is_empty() {
            out.s(" (");
            push_comment_text(out, &p.name, true);
            out.c(')');
        }
        out.c('\n');
    } else if !p.name.is_empty() {
        comment_line(out, st, &format!("PROGRAM {}", p.name));
    }
    for c in &p.header_comments {
        comment_line(out, st, c);
    }
    let plane = |out: &mut Out, sep: char| {
        if let Some(pl) = p.plane {
            out.s(pl.code());
            out.c(sep);
        }
    };
    match st.frame {
        Frame::Sinumerik => {
            ln.push(out);
            plane(out, ' ');
            out.s("G90 G94 G71\n");
        }
        Frame::Iso | Frame::LinuxCnc => {
            plane(out, ' ');
            out.s("G21 G90 G94\n");
        }
        Frame::Marlin => {
            plane(out, '\n');
            out.s("G21\nG90\nG94\n");
        }
    }
}

fn footer(out: &mut Out, st: &Style, ln: &mut LineNo) {
    match st.frame {
        Frame::Sinumerik => {
            ln.push(out);
            out.s("M30\n");
        }
        Frame::Iso => out.s("M30\n%\n"),
        Frame::LinuxCnc => out.s("M2\n"),
        Frame::Marlin => {}
    }
}

/// Programs with at least this many blocks are written in several runs.
const PARALLEL_MIN: usize = 1 << 16;

/// The most runs a program is cut into.
const RUNS_MAX: usize = 8;

/// Writes `p` (already validated) in the style `st`.
pub(super) fn write(p: &Program, st: &Style, out: &mut Out) -> Result<(), NcError> {
    let runs = if p.blocks.len() >= PARALLEL_MIN {
        rayon::current_num_threads().min(RUNS_MAX)
    } else {
        1
    };
    write_in(p, st, out, runs)
}

/// Writes `p` with the blocks cut into `runs` runs written in parallel on
/// rayon's global pool. Each run starts from the modal state the runs before
/// it leave ([`state_before`]), so the text is the same for any number of
/// runs.
fn write_in(p: &Program, st: &Style, out: &mut Out, runs: usize) -> Result<(), NcError> {
    let words = Words::new(p, st)?;
    let per_block = 16 + 12 * words.axes.len();
    out.reserve(256 + p.blocks.len() * per_block);
    let mut ln = LineNo {
        on: st.line_numbers,
        next: 10,
    };
    header(out, p, st, &mut ln);
    let first_n = ln.next;
    let len = p.blocks.len();
    let chunk = len.div_ceil(runs.clamp(1, len.max(1))).max(1);
    let ranges: Vec<_> = (0..len.div_ceil(chunk).max(1))
        .map(|c| c * chunk..((c + 1) * chunk).min(len))
        .collect();
    let write_run = |range: std::ops::Range<usize>, out: &mut Out| {
        let mut state = state_before(p, st, range.start, first_n);
        write_blocks(p, st, &words, range, &mut state, out);
    };
    // The first run goes straight into `out`, the others into buffers of
    // their own, appended after it in order.
    let (first, rest) = ranges
        .split_first()
        .map_or((0..0, &[][..]), |(f, r)| (f.clone(), r));
    let (_, parts): ((), Vec<Vec<u8>>) = rayon::join(
        || write_run(first, out),
        || {
            rest.par_iter()
                .map(|range| {
                    let mut o = Out::new(Vec::with_capacity(range.len() * per_block));
                    write_run(range.clone(), &mut o);
                    o.finish()
                })
                .collect()
        },
    );
    for part in &parts {
        out.append(part);
    }
    ln.next = first_n + 10 * len as u64;
    footer(out, st, &mut ln);
    Ok(())
}

/// The words written before axis values: per axis its word and decimals,
/// and for a modulo axis the text before its value (`" A"`, Sinumerik `" A="`).
struct Words {
    axes: Vec<(AxisWord, u32)>,
    modulo: Vec<Option<String>>,
}

impl Words {
    fn new(p: &Program, st: &Style) -> Result<Self, NcError> {
        let modulo = p
            .axes
            .iter()
            .map(|a| {
                a.modulo.then(|| match st.modulo {
                    ModWrite::Acp => format!(" {}=", a.name),
                    ModWrite::Rezero | ModWrite::Signed => format!(" {}", a.name),
                })
            })
            .collect();
        Ok(Self {
            axes: axis_words(p, st)?,
            modulo,
        })
    }
}

/// The modal state of the writer between blocks.
struct State<'a> {
    /// Last printed scaled axis values; `i64::MIN` (never a scaled value): none.
    last: Vec<i64>,
    /// `G93` is active.
    g93: bool,
    /// The last per-minute feed written (scaled, decimals).
    last_feed: Option<(i64, u32)>,
    /// The previous block's end point.
    prev: Option<&'a [f64]>,
    /// The whole turns (printed units) of the last re-zero, per axis.
    off: Vec<i64>,
    ln: LineNo,
}

/// The feed word of a block: (value, decimals, written even when unchanged).
fn block_feed(st: &Style, b: &Block, prev: Option<&[f64]>) -> Option<(f64, u32, bool)> {
    match (b.kind, b.feed) {
        (Motion::Linear, Feed::PerMinute(f)) => Some((f, FEED, false)),
        (Motion::Linear, Feed::InverseTime(t)) => match st.inverse {
            Inverse::G93 => Some((60.0 / t, FEED_FINE, true)),
            Inverse::Convert => {
                let travel = prev.map_or(0.0, |q| nc_travel(q, &b.target));
                (travel > 0.0).then(|| (travel / t * 60.0, FEED_FINE, false))
            }
        },
        _ => None,
    }
}

/// Marlin's own feed before any `F` (`DEFAULT_FEEDRATE_MM_M`, 4000 mm/min
/// in Marlin 2): the feed a program of timed blocks that move nothing is
/// written with, so that its first feed move has an `F`.
const MARLIN_DEFAULT_FEED: f64 = 4000.0;

/// The feed written on a feed move that has none of its own (in the
/// converting dialects: a timed first block, from an unknown position, or a
/// timed block that moves nothing) while no feed is in force: the first feed
/// of a later block, so that the block moves at the speed the program goes
/// on with and that block needs no `F` of its own; else Marlin's default.
fn feed_ahead(p: &Program, st: &Style, from: usize) -> (f64, u32) {
    (from + 1..p.blocks.len())
        .find_map(
            |k| match block_feed(st, &p.blocks[k], Some(&p.blocks[k - 1].target)) {
                Some((f, dec, false)) => Some((f, dec)),
                _ => None,
            },
        )
        .unwrap_or((MARLIN_DEFAULT_FEED, FEED))
}

/// The state the writer is in before block `start` (`first_n`: the first
/// block's N number). After any block every axis's last printed value is
/// that block's rounded value; `G93` is on when the last linear block was
/// inverse time (in the `G93` dialects); the remembered feed is the last
/// per-minute feed written since.
fn state_before<'a>(p: &'a Program, st: &Style, start: usize, first_n: u64) -> State<'a> {
    let n = p.axes.len();
    let prev = start.checked_sub(1).map(|i| p.blocks[i].target.as_slice());
    let last = match prev {
        Some(t) => p
            .axes
            .iter()
            .zip(t)
            .map(|(a, v)| num::scaled(*v, if a.rotary { DEG } else { MM }).unwrap_or(i64::MIN))
            .collect(),
        None => vec![i64::MIN; n],
    };
    let mut g93 = false;
    let mut last_feed = None;
    for i in (0..start).rev() {
        let b = &p.blocks[i];
        if b.kind != Motion::Linear {
            continue;
        }
        if st.inverse == Inverse::G93 && matches!(b.feed, Feed::InverseTime(_)) {
            g93 = true;
            break;
        }
        let before = i.checked_sub(1).map(|j| p.blocks[j].target.as_slice());
        if let Some((f, dec, false)) = block_feed(st, b, before) {
            last_feed = num::scaled(f, dec).map(|s| (s, dec));
            break;
        }
        if last_feed.is_none() {
            // A feed move without a feed of its own: if no block before it
            // has one either, it was written with the feed ahead (the same
            // for every such block: the first feed at or after `start`).
            let (f, dec) = feed_ahead(p, st, i);
            last_feed = num::scaled(f, dec).map(|s| (s, dec));
        }
    }
    let off = if st.modulo == ModWrite::Rezero {
        modulo::offsets_before(p, start)
    } else {
        vec![0; n]
    };
    State {
        last,
        g93,
        last_feed,
        prev,
        off,
        ln: LineNo {
            on: st.line_numbers,
            next: first_n + 10 * start as u64,
        },
    }
}

/// Writes blocks `range` of `p` from `state`.
fn write_blocks<'a>(
    p: &'a Program,
    st: &Style,
    words: &Words,
    range: std::ops::Range<usize>,
    state: &mut State<'a>,
    out: &mut Out,
) {
    let Words {
        axes: words,
        modulo: mod_words,
    } = words;
    let n = words.len();
    let State {
        last,
        g93,
        last_feed,
        prev,
        off,
        ln,
    } = state;
    let last = &mut last[..n];
    let first = range.start;
    for (i, b) in p.blocks[range].iter().enumerate() {
        if let (true, ModWrite::Rezero, Some(before)) = (b.rezero, st.modulo, *prev) {
            rezero_line(out, st, mod_words, before, off);
        }
        ln.push(out);
        let feed = match block_feed(st, b, *prev) {
            None if b.kind == Motion::Linear && last_feed.is_none() => {
                let (f, dec) = feed_ahead(p, st, first + i);
                Some((f, dec, false))
            }
            feed => feed,
        };
        match b.kind {
            Motion::Rapid => out.s(st.motion[0]),
            Motion::Linear => {
                match (b.feed, st.inverse) {
                    (Feed::PerMinute(_), _) if *g93 => {
                        out.s("G94 ");
                        *g93 = false;
                        *last_feed = None;
                    }
                    (Feed::InverseTime(_), Inverse::G93) if !*g93 => {
                        out.s("G93 ");
                        *g93 = true;
                    }
                    _ => {}
                }
                out.s(st.motion[1]);
            }
        }
        let mut any = false;
        let target = &b.target[..n];
        for k in 0..n {
            let v = target[k];
            let (word, dec) = &words[k];
            match num::scaled(v, *dec) {
                Some(s) if s == last[k] => continue,
                Some(s) => {
                    match &mod_words[k] {
                        Some(mw) => push_modulo(out, st, mw, s, last[k], off[k]),
                        None => {
                            word.push(out);
                            num::push_scaled(out, s, *dec, st.keep_point);
                        }
                    }
                    last[k] = s;
                }
                None => {
                    word.push(out);
                    num::push(out, v, *dec, st.keep_point);
                    last[k] = i64::MIN;
                }
            }
            any = true;
        }
        if !any {
            // Nothing moved: still write one axis word, so the block stays a move.
            match (words.first(), b.target.first(), mod_words.first()) {
                (Some(_), Some(_), Some(Some(mw))) => {
                    push_modulo(out, st, mw, last[0], last[0], off[0]);
                }
                (Some((word, dec)), Some(v), _) => {
                    word.push(out);
                    num::push(out, *v, *dec, st.keep_point);
                }
                _ => {}
            }
        }
        if let Some((f, dec, always)) = feed {
            let key = num::scaled(f, dec).map(|s| (s, dec));
            if always || key.is_none() || key != *last_feed {
                out.s(" F");
                num::push(out, f, dec, st.keep_point);
                if !always {
                    *last_feed = key;
                }
            }
        }
        if let Some(c) = &b.comment {
            if st.parens {
                out.s(" (");
                push_comment_text(out, c, true);
                out.c(')');
            } else {
                out.s(" ; ");
                push_comment_text(out, c, false);
            }
        }
        out.c('\n');
        *prev = Some(&b.target);
    }
}

/// `G92` with every modulo axis at its angle within the turn, `before` the
/// block; the re-zeroed turns go to `off`.
fn rezero_line(
    out: &mut Out,
    st: &Style,
    mod_words: &[Option<String>],
    before: &[f64],
    off: &mut [i64],
) {
    if mod_words.iter().all(Option::is_none) {
        return;
    }
    out.s("G92");
    for ((mw, v), o) in mod_words.iter().zip(before).zip(off.iter_mut()) {
        let (Some(mw), Some(s)) = (mw, modulo::scaled(*v)) else {
            continue;
        };
        *o = modulo::turns_below(s);
        out.s(mw);
        num::push_scaled(out, s - *o, DEG, st.keep_point);
    }
    out.c('\n');
}

/// A modulo axis at `s` (printed units) after `last`: re-zeroing, the angle
/// less the turns `off`; modulo, the angle within the turn and the direction.
fn push_modulo(out: &mut Out, st: &Style, word: &str, s: i64, last: i64, off: i64) {
    out.s(word);
    let negative = last != i64::MIN && s < last;
    match st.modulo {
        ModWrite::Rezero => num::push_scaled(out, s - off, DEG, st.keep_point),
        ModWrite::Acp => {
            out.s(if negative { "ACN(" } else { "ACP(" });
            num::push_scaled(out, s.rem_euclid(TURN), DEG, false);
            out.c(')');
        }
        ModWrite::Signed => {
            if negative {
                out.c('-');
            }
            num::push_scaled(out, s.rem_euclid(TURN), DEG, st.keep_point);
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::AxisSpec;

    /// Mixed blocks: rapids, per-minute and inverse-time runs, blocks that
    /// move nothing, huge values, comments.
    fn mixed(n: usize) -> Program {
        let mut p = Program::new(
            "MIXED",
            vec![
                AxisSpec::linear("X"),
                AxisSpec::rotary("A"),
                AxisSpec::linear("Y"),
            ],
        );
        let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut pos = [0.0f64; 3];
        for i in 0..n {
            let r = rnd();
            if r % 7 != 0 {
                pos[(r % 3) as usize] += ((r >> 8) % 2000) as f64 * 0.0137 - 13.0;
            }
            if r % 997 == 0 {
                pos[1] = 1e300;
            } else if pos[1] > 1e200 {
                pos[1] = 0.0;
            }
            let feed = (r >> 20) % 100;
            let mut b = match (r >> 40) % 10 {
                0 => Block::rapid(pos.to_vec()),
                1..=4 => Block::linear(pos.to_vec(), Feed::PerMinute(100.0 + (feed / 30) as f64)),
                _ => Block::linear(pos.to_vec(), Feed::InverseTime(0.01 + (feed / 50) as f64)),
            };
            if i % 1000 == 0 {
                b.comment = Some(format!("c{i}"));
            }
            p.blocks.push(b);
        }
        p
    }

    #[test]
    fn the_same_text_for_any_number_of_runs() {
        let p = mixed(20_000);
        for st in [&SINUMERIK, &ISO, &LINUXCNC] {
            let one = {
                let mut o = Out::new(Vec::new());
                write_in(&p, st, &mut o, 1).unwrap();
                o.finish()
            };
            for threads in [2, 3, 7, 64] {
                let mut o = Out::new(Vec::new());
                write_in(&p, st, &mut o, threads).unwrap();
                assert!(o.finish() == one, "{} in {threads} runs", st.name);
            }
        }
        let mut p = p;
        p.axes = vec![
            AxisSpec::linear("X"),
            AxisSpec::rotary("A"),
            AxisSpec::rotary("B"),
        ];
        let mut o = Out::new(Vec::new());
        write_in(&p, &MARLIN, &mut o, 1).unwrap();
        let one = o.finish();
        for threads in [2, 5, 16] {
            let mut o = Out::new(Vec::new());
            write_in(&p, &MARLIN, &mut o, threads).unwrap();
            assert!(o.finish() == one, "marlin in {threads} runs");
        }
    }

    /// Marlin: timed blocks without a travel before any feed take the feed
    /// ahead, the same whichever run writes them.
    #[test]
    fn marlin_feed_ahead_is_the_same_for_any_number_of_runs() {
        let mut p = Program::new(
            "AHEAD",
            vec![
                AxisSpec::linear("X"),
                AxisSpec::rotary("A"),
                AxisSpec::rotary("B"),
            ],
        );
        for k in 0..40 {
            let x = if k < 25 { 5.0 } else { 5.0 + k as f64 };
            p.blocks
                .push(Block::linear(vec![x, 0.0, 0.0], Feed::InverseTime(0.5)));
        }
        let one = {
            let mut o = Out::new(Vec::new());
            write_in(&p, &MARLIN, &mut o, 1).unwrap();
            o.finish()
        };
        let text = String::from_utf8(one.clone()).unwrap();
        assert!(text.contains("G1 X5 A0 B0 F3000\n"), "{text}");
        for threads in [2, 3, 7, 40] {
            let mut o = Out::new(Vec::new());
            write_in(&p, &MARLIN, &mut o, threads).unwrap();
            assert!(o.finish() == one, "marlin in {threads} runs");
        }
    }

    #[test]
    fn the_working_plane_opens_the_setup_line() {
        let mut p = Program::new("ZX", vec![AxisSpec::linear("Z"), AxisSpec::linear("X")]);
        p.blocks
            .push(Block::linear(vec![1.0, 2.0], Feed::PerMinute(100.0)));
        p.plane = Some(crate::Plane::Zx);
        let text = |p: &Program, st: &Style| {
            let mut o = Out::new(Vec::new());
            write_in(p, st, &mut o, 1).unwrap();
            String::from_utf8(o.finish()).unwrap()
        };
        assert!(text(&p, &SINUMERIK).contains("N10 G18 G90 G94 G71\n"));
        assert!(text(&p, &ISO).contains("G18 G21 G90 G94\n"));
        assert!(text(&p, &MARLIN).contains("\nG18\nG21\n"));
        p.plane = None;
        assert!(text(&p, &SINUMERIK).contains("N10 G90 G94 G71\n"));
    }
}
