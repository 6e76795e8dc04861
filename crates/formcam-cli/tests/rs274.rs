//! LinuxCNC's own interpreter reads the LinuxCNC programs formcam writes:
//! `rs274 -g` (Debian's `linuxcnc-uspace`) runs the multi-layer example with
//! the spindle a wrapped rotary axis, and the canonical positions it prints
//! are formcam's block ends (the spindle unwound), the block times from its
//! feeds add up to formcam's program time.
//!
//! Without `rs274` on the PATH the test says it was skipped, unless
//! `FORMCAM_REQUIRE_RS274=1` (set by `.ci/run`), when it fails.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{examples, scratch};
use formcam_nc::{AxisSpec, Dialect, read_gcode_in};

#[path = "../../formcam-nc/tests/support/rs274.rs"]
mod rs274;

use rs274::{rs274_present, run_rs274};

/// One canonical call of `rs274 -g`.
#[derive(Debug)]
enum Canon {
    /// `SET_FEED_RATE(r)`: units per minute.
    Rate(f64),
    /// `STRAIGHT_TRAVERSE(x, y, z, a, b, c, ..)`.
    Traverse([f64; 6]),
    /// `STRAIGHT_FEED(x, y, z, a, b, c, ..)`.
    Feed([f64; 6]),
    /// `SET_G92_OFFSET`, `SET_G5X_OFFSET` with a non-zero value.
    Offset,
    /// `PROGRAM_END()`.
    End,
}

fn numbers(args: &str) -> Vec<f64> {
    args.split(',')
        .filter_map(|a| a.trim().parse::<f64>().ok())
        .collect()
}

/// The canonical calls in the output of `rs274 -g`.
fn canon(text: &str) -> Vec<Canon> {
    let mut out = Vec::new();
    for line in text.lines() {
        let Some(call) = line.split("N..... ").nth(1) else {
            continue;
        };
        let (name, rest) = call.split_once('(').unwrap_or((call, ""));
        let args = rest.rsplit_once(')').map_or(rest, |(a, _)| a);
        let xyzabc = || {
            let v = numbers(args);
            [v[0], v[1], v[2], v[3], v[4], v[5]]
        };
        match name {
            "SET_FEED_RATE" => out.push(Canon::Rate(numbers(args)[0])),
            "STRAIGHT_TRAVERSE" => out.push(Canon::Traverse(xyzabc())),
            "STRAIGHT_FEED" => out.push(Canon::Feed(xyzabc())),
            "SET_G92_OFFSET" | "SET_G5X_OFFSET" => {
                // SET_G5X_OFFSET(index, x, ..): the index is no offset.
                let skip = usize::from(name == "SET_G5X_OFFSET");
                if numbers(args).iter().skip(skip).any(|x| *x != 0.0) {
                    out.push(Canon::Offset);
                }
            }
            "PROGRAM_END" => out.push(Canon::End),
            _ => {}
        }
    }
    out
}

/// LinuxCNC's length of a move for feeds: the linear axes' distance, or the
/// rotary axes' when no linear axis moves.
fn feed_length(p: &[f64; 6], q: &[f64; 6]) -> f64 {
    let d = |i: usize| q[i] - p[i];
    let lin = (d(0) * d(0) + d(1) * d(1) + d(2) * d(2)).sqrt();
    if lin > 0.0 {
        lin
    } else {
        (d(3) * d(3) + d(4) * d(4) + d(5) * d(5)).sqrt()
    }
}

#[test]
fn linuxcnc_reads_our_program_to_the_same_positions_and_time() {
    if !rs274_present() {
        return;
    }
    let dir = scratch("layers");
    let out = dir.join("out");
    let job = examples().join("tube-layers-4axis.toml");
    common::wind_ok(&job, &out);
    let program = std::fs::read_to_string(out.join("program.ngc")).unwrap();

    // The machine: A a wrapped rotary axis.
    let (run, printed) = run_rs274(&dir, &program);
    let calls = canon(&printed);
    assert!(
        run.status.success() && matches!(calls.last(), Some(Canon::End)),
        "rs274 stopped before the end: {}\n{}",
        String::from_utf8_lossy(&run.stderr),
        printed.lines().rev().take(5).collect::<Vec<_>>().join("\n")
    );
    assert!(
        !calls.iter().any(|c| matches!(c, Canon::Offset)),
        "a wrapped rotary axis needs no offsets"
    );

    // Every written spindle angle lies within one turn.
    let written = program
        .lines()
        .filter(|l| !l.starts_with('('))
        .flat_map(|l| l.split(' ').filter_map(|w| w.strip_prefix('A')))
        .map(|v| v.parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max);
    assert!(
        written > 300.0 && written < 360.0,
        "largest |A| written: {written}"
    );
    let axes = [
        AxisSpec::rotary_modulo("A"),
        AxisSpec::linear("X"),
        AxisSpec::linear("Y"),
        AxisSpec::rotary("B"),
    ];
    let ours = read_gcode_in(&program, &axes, Dialect::LinuxCnc).unwrap();
    // The canonical positions, in our axis order A, X, Y, B.
    let mut positions: Vec<[f64; 4]> = Vec::new();
    let mut time = 0.0;
    let mut rate = 0.0;
    let mut here: Option<[f64; 6]> = None;
    for c in &calls {
        match c {
            Canon::Rate(r) => rate = *r,
            Canon::Traverse(p) | Canon::Feed(p) => {
                if let (Canon::Feed(_), Some(h)) = (c, here) {
                    let len = feed_length(&h, p);
                    assert!(rate > 0.0 || len == 0.0, "a feed move without a rate");
                    if len > 0.0 {
                        time += len / rate * 60.0;
                    }
                }
                positions.push([p[3], p[0], p[1], p[4]]);
                here = Some(*p);
            }
            _ => {}
        }
    }
    // The same blocks and positions as our reader (the spindle unwound).
    assert_eq!(positions.len(), ours.blocks.len(), "block count");
    for (i, (p, b)) in positions.iter().zip(&ours.blocks).enumerate() {
        for k in 0..4 {
            assert!(
                (p[k] - b.target[k]).abs() < 2e-4,
                "block {i} axis {}: rs274 {} vs ours {}",
                axes[k].name,
                p[k],
                b.target[k]
            );
        }
    }
    // formcam's block ends (blocks.csv, before blocks are split and the
    // spindle moved by whole turns) appear in that order.
    let csv = std::fs::read_to_string(out.join("blocks.csv")).unwrap();
    let mut from = 0;
    let mut turns: Option<f64> = None;
    let mut rows = 0;
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (a, x, y, b) = (v[2], v[3], v[4], v[5]);
        let near = |p: &[f64; 4], shift: f64| {
            (p[0] - a - shift).abs() < 2e-4
                && (p[1] - x).abs() < 2e-3
                && (p[2] - y).abs() < 2e-3
                && (p[3] - b).abs() < 2e-4
        };
        let found = positions[from..].iter().position(|p| {
            let shift = turns.unwrap_or(360.0 * ((p[0] - a) / 360.0).round());
            near(p, shift)
        });
        let j = found.unwrap_or_else(|| panic!("block {} of blocks.csv not reached", v[0]));
        let p = positions[from + j];
        turns.get_or_insert(360.0 * ((p[0] - a) / 360.0).round());
        from += j + 1;
        rows += 1;
    }
    assert!(
        rows > 1000 && from == positions.len(),
        "{rows} rows, {from} of {}",
        positions.len()
    );
    // The same program time.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let total = summary["program_time_s"].as_f64().unwrap();
    assert!(
        (time - total).abs() < 1e-4 * total,
        "rs274: {time} s, formcam: {total} s"
    );
    eprintln!(
        "rs274: {} moves, {time:.4} s; formcam: {} blocks, {total:.4} s",
        positions.len(),
        rows
    );
}
