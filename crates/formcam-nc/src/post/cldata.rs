//! CLDATA as ISO 4343 APT text, with machine-axis `GOTO` records.
//!
//! ```text
//! PARTNO/NAME
//! $$ header comment
//! UNITS/MM
//! RAPID
//! GOTO/0,0,0,0
//! FEDRAT/1200,MMPM
//! GOTO/10,30,0,0
//! FINI
//! ```
//!
//! `GOTO` carries every axis value in the program's axis order (mm, degrees),
//! not a tool tip and tool axis: the file is already post-kinematics. `RAPID`
//! applies to the next `GOTO` only; `FEDRAT` is modal and written when it
//! changes. A block comment is a `$$` line before the block. An inverse-time
//! block of time `t` is written as the equivalent feed of its linear axes,
//! `FEDRAT/L/t*60,MMPM` (`L` the Euclidean travel of the linear axes), so that
//! APT consumers that only know per-minute feeds keep the block time; when no
//! linear axis moves (or the block is the first) it is `FEDRAT/60/t,INVERS`
//! (1/min). A record longer than 72 columns is continued on the next line
//! after a `$` (APT's continuation mark).
//!
//! A modulo rotary axis ([`crate::modulo`]) is re-zeroed: before a re-zeroed
//! block, `ORIGIN/A,o` (APT's shift of the output origin, here of one named
//! machine axis) says that the axis's `GOTO` values from there on are
//! measured from `o` degrees, a whole number of turns; every value written
//! stays within the bound.

use crate::modulo;
use crate::num::{self, DEG, FEED, FEED_FINE, MM, Out};
use crate::post::push_comment_text;
use crate::program::linear_travel;
use crate::{Feed, Motion, Program};

/// Columns of an APT record (a punched card's).
const CARD: usize = 72;

/// Writes `p` (already validated).
pub(super) fn write(p: &Program, out: &mut Out) {
    let n = p.axes.len();
    let decs: Vec<u32> = p
        .axes
        .iter()
        .map(|a| if a.rotary { DEG } else { MM })
        .collect();
    out.reserve(256 + p.blocks.len() * (12 + 12 * n));
    out.s("PARTNO/");
    push_comment_text(out, &p.name, false);
    out.c('\n');
    for c in &p.header_comments {
        comment(out, c);
    }
    out.s("UNITS/MM\n");

    // (scaled value, decimals, inverse)
    let mut last_feed: Option<(i64, u32, bool)> = None;
    let mut prev: Option<&[f64]> = None;
    let mods = modulo::modulo_axes(p);
    // The whole turns of the last re-zero (printed units), per axis.
    let mut off = vec![0i64; n];
    for b in &p.blocks {
        if let (true, Some(q)) = (b.rezero, prev) {
            for &k in &mods {
                if let Some(s) = modulo::scaled(q[k]) {
                    off[k] = modulo::turns_below(s);
                    out.s("ORIGIN/");
                    push_comment_text(out, &p.axes[k].name, false);
                    out.c(',');
                    num::push_scaled(out, off[k], DEG, false);
                    out.c('\n');
                }
            }
        }
        if let Some(c) = &b.comment {
            comment(out, c);
        }
        match (b.kind, b.feed) {
            (Motion::Rapid, _) => out.s("RAPID\n"),
            (Motion::Linear, Feed::PerMinute(f)) => fedrat(out, &mut last_feed, f, FEED, false),
            (Motion::Linear, Feed::InverseTime(t)) => {
                let travel = prev.map_or(0.0, |q| linear_travel(&p.axes, q, &b.target));
                if travel > 0.0 {
                    fedrat(out, &mut last_feed, travel / t * 60.0, FEED_FINE, false);
                } else {
                    fedrat(out, &mut last_feed, 60.0 / t, FEED_FINE, true);
                }
            }
            (Motion::Linear, Feed::None) => {}
        }
        out.s("GOTO/");
        if n <= 4 {
            // At most 5 + 4 * 14 columns: never longer than a card.
            for (k, (v, d)) in b.target.iter().zip(&decs).enumerate() {
                if k > 0 {
                    out.c(',');
                }
                value(out, *v, *d, off[k]);
            }
        } else {
            let mut col = 5;
            for (k, (v, d)) in b.target.iter().zip(&decs).enumerate() {
                let mut one = Out::new(Vec::with_capacity(24));
                value(&mut one, *v, *d, off[k]);
                let bytes = one.finish();
                // The value, its comma, and room for a `$` must fit in 72 columns.
                if k > 0 {
                    if col + 1 + bytes.len() + 2 > CARD {
                        out.s(",$\n");
                        col = 0;
                    } else {
                        out.c(',');
                        col += 1;
                    }
                }
                out.append(&bytes);
                col += bytes.len();
            }
        }
        out.c('\n');
        prev = Some(&b.target);
    }
    out.s("FINI\n");
}

/// An axis value less the re-zeroed turns `off` (printed units; 0 for the
/// axes that are not re-zeroed).
fn value(out: &mut Out, v: f64, dec: u32, off: i64) {
    match num::scaled(v, dec) {
        Some(s) if off != 0 => num::push_scaled(out, s - off, dec, false),
        _ => num::push(out, v, dec, false),
    }
}

fn comment(out: &mut Out, text: &str) {
    out.s("$$ ");
    push_comment_text(out, text, false);
    out.c('\n');
}

fn fedrat(out: &mut Out, last: &mut Option<(i64, u32, bool)>, f: f64, dec: u32, inverse: bool) {
    let key = num::scaled(f, dec).map(|s| (s, dec, inverse));
    if key.is_some() && key == *last {
        return;
    }
    out.s("FEDRAT/");
    num::push(out, f, dec, false);
    out.s(if inverse { ",INVERS\n" } else { ",MMPM\n" });
    *last = key;
}
