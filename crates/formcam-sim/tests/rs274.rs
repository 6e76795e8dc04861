//! The LinuxCNC timeline against LinuxCNC's own interpreter: `rs274 -g`
//! (Debian's `linuxcnc-uspace`) reads a program formcam's LinuxCNC writer
//! wrote (inverse-time and per-minute blocks, rotary and linear axes
//! together, the spindle a wrapped rotary axis); its canonical traverse and
//! feed calls end where our blocks end, and the time of each is our block's
//! duration. The interpreter hands inverse-time blocks to the canonical
//! machine as a per-minute rate over the length of its own rule (the
//! length over the block time), so the time of every feed call, its length
//! by LinuxCNC's documented rule over the rate printed, checks our rule and
//! our reading of `G93` both.
//!
//! Without `rs274` on the PATH the test says it was skipped, unless
//! `FORMCAM_REQUIRE_RS274=1` (set by `.ci/run`), when it fails.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use formcam_machine::shipped::shipped;
use formcam_nc::{Block, Dialect, Feed, Motion, Program, write};
use formcam_sim::{FeedRule, Timeline, program_axes, read_program};

#[path = "../../formcam-nc/tests/support/rs274.rs"]
mod rs274;

use rs274::{rs274_present, run_rs274};

/// A canonical move: traverse or feed, its end (x y z a b c u v w), the
/// feed mode (inverse time) and rate in force.
#[derive(Debug)]
struct Move {
    feed: bool,
    end: Vec<f64>,
    inverse: bool,
    rate: f64,
}

fn numbers(args: &str) -> Vec<f64> {
    args.split(',')
        .filter_map(|a| a.trim().parse::<f64>().ok())
        .collect()
}

/// The moves of `rs274 -g`'s output.
fn moves(text: &str) -> Vec<Move> {
    let (mut inverse, mut rate) = (false, 0.0);
    let mut out = Vec::new();
    for line in text.lines() {
        let Some(call) = line.split("N..... ").nth(1) else {
            continue;
        };
        let (name, rest) = call.split_once('(').unwrap_or((call, ""));
        let args = rest.rsplit_once(')').map_or(rest, |(a, _)| a);
        match name {
            // SET_FEED_MODE(spindle, mode) or SET_FEED_MODE(mode): 1 inverse time.
            "SET_FEED_MODE" => inverse = numbers(args).last() == Some(&1.0),
            "SET_FEED_RATE" => rate = numbers(args)[0],
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => out.push(Move {
                feed: name == "STRAIGHT_FEED",
                // u, v, w only where the machine has them.
                end: {
                    let mut v = numbers(args);
                    v.resize(9, 0.0);
                    v
                },
                inverse,
                rate,
            }),
            _ => {}
        }
    }
    out
}

/// LinuxCNC's time of a feed move (its manual, "Feed Rate"): inverse time
/// `60 / F`; per minute along X, Y, Z, else U, V, W, else A, B, C.
fn feed_time(from: &[f64], m: &Move) -> f64 {
    if m.inverse {
        return 60.0 / m.rate;
    }
    let norm =
        |r: std::ops::Range<usize>| r.map(|i| (m.end[i] - from[i]).powi(2)).sum::<f64>().sqrt();
    let len = [norm(0..3), norm(6..9), norm(3..6)]
        .into_iter()
        .find(|l| *l > 0.0)
        .unwrap_or(0.0);
    len / m.rate * 60.0
}

#[test]
fn linuxcnc_times_our_linuxcnc_program_as_we_do() {
    if !rs274_present() {
        return;
    }
    let m = shipped("winder-4axis").unwrap().machine().unwrap();
    // A (modulo), X, Y, B.
    let mut p = Program::new("RS274", program_axes(&m));
    p.blocks.push(Block::rapid(vec![0.0, 100.0, 250.0, 0.0]));
    let mut a = 0.0;
    for i in 0..60 {
        let s = f64::from(i);
        a += 37.0 + 5.0 * (0.3 * s).sin();
        let target = vec![
            a,
            100.0 + 200.0 * (0.1 * s).sin(),
            250.0 + 40.0 * (0.2 * s).cos(),
            if i % 7 == 3 {
                0.0
            } else {
                20.0 * (0.15 * s).sin()
            },
        ];
        let feed = match i % 4 {
            0 | 1 => Feed::InverseTime(0.05 + 0.01 * f64::from(i % 5)),
            2 => Feed::PerMinute(3000.0 + 100.0 * s),
            _ => Feed::PerMinute(1500.0),
        };
        p.blocks.push(Block::linear(target, feed));
        if i == 20 {
            // A block of rotary axes alone, per minute (degrees per minute).
            let mut t = p.blocks.last().unwrap().target.clone();
            t[0] += 90.0;
            t[3] += 5.0;
            a = t[0];
            p.blocks.push(Block::linear(t, Feed::PerMinute(2400.0)));
        }
    }
    let mut text = String::new();
    write(&p, Dialect::LinuxCnc, &mut text).unwrap();

    let printed = canon(&text, "feeds");
    let calls = moves(&printed);

    let (read, lines, d) = read_program(Path::new("program.ngc"), &text, &m).unwrap();
    let tl = Timeline::new(&read, &lines, FeedRule::of(d), &m).unwrap();
    assert_eq!(calls.len(), tl.len(), "moves:\n{printed}");
    // rs274 starts at 0 on every axis; our timeline at the machine's home,
    // which only the first block (a rapid) sees.
    let mut here = vec![0.0; 9];
    let mut feeds = 0;
    for (c, b) in calls.iter().zip(tl.blocks()) {
        assert_eq!(c.feed, b.kind == Motion::Linear, "block {}", b.index);
        // Ours A, X, Y, B; theirs x y z a b c u v w (A unwound by the
        // wrapped rotary axis, as our reader unwinds it).
        let theirs = [c.end[3], c.end[0], c.end[1], c.end[4]];
        for (k, (t, o)) in theirs.iter().zip(b.to).enumerate() {
            let wrapped = if k == 0 {
                (t - o).rem_euclid(360.0)
            } else {
                t - o
            };
            let off = wrapped.min(360.0 - wrapped.abs()).abs();
            assert!(
                if k == 0 {
                    off < 1e-6
                } else {
                    (t - o).abs() < 1e-6
                },
                "block {} axis {k}: rs274 {t}, ours {o}",
                b.index
            );
        }
        if c.feed {
            let t = feed_time(&here, c);
            // rs274 prints the rate with 4 decimals.
            let printed = t * 0.5e-4 / c.rate;
            assert!(
                (t - b.duration_s).abs() <= printed + 1e-12,
                "block {} (line {}): rs274 {t} s, ours {} s",
                b.index,
                b.line,
                b.duration_s
            );
            feeds += 1;
        }
        here.clone_from(&c.end);
    }
    assert!(feeds > 60);
}

/// `rs274 -g` of the LinuxCNC program `text` on the 4-axis winder's
/// configuration (A a wrapped rotary axis): the canonical calls printed.
fn canon(text: &str, name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("formcam-sim-rs274-{name}-{}", std::process::id()));
    let (run, printed) = run_rs274(&dir, text);
    assert!(
        run.status.success(),
        "rs274 failed ({}): {}{}",
        run.status,
        String::from_utf8_lossy(&run.stderr),
        String::from_utf8_lossy(&run.stdout)
    );
    std::fs::remove_dir_all(&dir).ok();
    printed
}

/// The dwells and moves of `rs274 -g`'s output in order: `Some(seconds)`
/// for a `DWELL`, `None` for a traverse or feed.
fn dwells(text: &str) -> Vec<Option<f64>> {
    text.lines()
        .filter_map(|line| line.split("N..... ").nth(1))
        .filter_map(|call| {
            let (name, rest) = call.split_once('(').unwrap_or((call, ""));
            match name {
                "DWELL" => Some(Some(numbers(rest.trim_end_matches(')'))[0])),
                "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => Some(None),
                _ => None,
            }
        })
        .collect()
}

#[test]
fn linuxcnc_dwells_as_long_as_our_dwell_blocks() {
    if !rs274_present() {
        return;
    }
    let m = shipped("winder-4axis").unwrap().machine().unwrap();
    let mut p = Program::new("DWELL", program_axes(&m));
    p.blocks.push(Block::rapid(vec![0.0, 100.0, 250.0, 0.0]));
    for i in 0..6 {
        let s = f64::from(i);
        p.blocks.push(Block::linear(
            vec![30.0 * s, 100.0 + 10.0 * s, 250.0, 2.0 * s],
            Feed::InverseTime(0.5),
        ));
    }
    let mut text = String::new();
    write(&p, Dialect::LinuxCnc, &mut text).unwrap();
    // A dwell after every second feed block: `G4 P` seconds.
    let mut with = String::new();
    let mut feeds = 0;
    for line in text.lines() {
        with.push_str(line);
        with.push('\n');
        if line.contains("G1") || line.starts_with('X') || line.starts_with('A') {
            feeds += 1;
            if feeds % 2 == 0 {
                with.push_str(&format!("G4 P{}\n", 0.25 * f64::from(feeds)));
            }
        }
    }
    let calls = dwells(&canon(&with, "dwell"));
    let (read, lines, d) = read_program(Path::new("program.ngc"), &with, &m).unwrap();
    let tl = Timeline::new(&read, &lines, FeedRule::of(d), &m).unwrap();
    assert_eq!(calls.len(), tl.len(), "{with}");
    assert_eq!(calls.iter().filter(|c| c.is_some()).count(), 3);
    for (c, b) in calls.iter().zip(tl.blocks()) {
        assert_eq!(c.is_some(), b.dwell, "block {} (line {})", b.index, b.line);
        if let Some(t) = c {
            assert!(
                (t - b.duration_s).abs() <= 0.5e-4,
                "line {}: {t} vs {}",
                b.line,
                b.duration_s
            );
            assert_eq!(b.from, b.to);
        }
    }
}
