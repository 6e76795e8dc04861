//! Timelines against closed forms: programs of known feeds written by
//! formcam's writers in every dialect, read back from the text, timed by
//! each controller's rule to 1e-9 s; limits broken on purpose found at the
//! right block and line.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use formcam_machine::Machine;
use formcam_machine::shipped::shipped;
use formcam_nc::{Block, Dialect, Feed, Program, write};
use formcam_sim::{FeedRule, Timeline, ViolationKind, check_text, program_axes, read_program};

fn machine(name: &str) -> Machine {
    shipped(name).unwrap().machine().unwrap()
}

/// The program's text in `dialect`, read back: its timeline on `m`.
fn written(p: &Program, dialect: Dialect, m: &Machine) -> (String, Timeline) {
    let mut text = String::new();
    write(p, dialect, &mut text).unwrap();
    let path = format!("program.{}", dialect.extension());
    let (read, lines, d) = read_program(Path::new(&path), &text, m).unwrap();
    assert_eq!(d, dialect);
    (
        text.clone(),
        Timeline::new(&read, &lines, FeedRule::of(d), m).unwrap(),
    )
}

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() <= 1e-9, "{what}: {a} vs {b}");
}

/// On the 4-axis winder (A modulo spindle, X carriage, Y cross feed, B eye;
/// home Y = 250): a rapid, inverse-time blocks, per-minute blocks moving X
/// alone, A alone and X with A, B with Y (each turn under a turn, as the
/// modulo dialects can write it in one block).
fn four_axis_program(m: &Machine) -> Program {
    let mut p = Program::new("TIMES", program_axes(m));
    let b = |t: [f64; 4], f: Feed| Block::linear(t.to_vec(), f);
    p.blocks.push(Block::rapid(vec![0.0, 100.0, 250.0, 0.0]));
    p.blocks
        .push(b([90.0, 150.0, 250.0, 10.0], Feed::InverseTime(0.5)));
    p.blocks
        .push(b([90.0, 450.0, 250.0, 10.0], Feed::PerMinute(6000.0)));
    p.blocks
        .push(b([390.0, 450.0, 250.0, 10.0], Feed::PerMinute(6000.0)));
    p.blocks
        .push(b([690.0, 750.0, 250.0, 10.0], Feed::PerMinute(6000.0)));
    p.blocks
        .push(b([690.0, 750.0, 280.0, 50.0], Feed::PerMinute(600.0)));
    p.blocks
        .push(b([720.0, 760.0, 300.0, 40.0], Feed::InverseTime(0.25)));
    p
}

#[test]
fn block_times_follow_each_controllers_feed_rule() {
    let m = machine("winder-4axis");
    let p = four_axis_program(&m);
    // Rapid: X 100 mm at 60000 mm/min is 0.1 s (A, Y, B do not move).
    // Per minute: X 300 mm at 6000 mm/min = 3 s; A 300° at 6000°/min = 3 s;
    // X 300 mm with A 300° at 6000: 3 s where only X counts; Y 30 mm with
    // B 40° at 600: 3 s where only Y counts.
    let by_xyz = [0.1, 0.5, 3.0, 3.0, 3.0, 3.0, 0.25];
    for dialect in [Dialect::LinuxCnc, Dialect::Sinumerik840d, Dialect::Iso] {
        let (_, tl) = written(&p, dialect, &m);
        assert_eq!(tl.len(), by_xyz.len(), "{dialect:?}");
        for (b, want) in tl.blocks().zip(by_xyz) {
            close(
                b.duration_s,
                want,
                &format!("{dialect:?} block {}", b.index),
            );
        }
        close(tl.duration_s(), by_xyz.iter().sum(), "total");
    }
    // CLDATA writes the inverse-time blocks as FEDRAT over the linear
    // travel (or INVERS where only rotary axes move): the same times within
    // the rounding of FEDRAT (3 decimals).
    let (_, tl) = written(&p, Dialect::Cldata, &m);
    for (b, want) in tl.blocks().zip(by_xyz) {
        assert!(
            (b.duration_s - want).abs() < 1e-6,
            "cldata block {}",
            b.index
        );
    }
}

#[test]
fn marlin_counts_every_axis_as_a_length() {
    // The X/A/B winder: A spindle, X carriage, B eye.
    let m = machine("winder-xab");
    let axes = program_axes(&m);
    let names: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
    let mut p = Program::new("XAB", axes.clone());
    let at = |a: f64, x: f64, b: f64| {
        names
            .iter()
            .map(|n| match *n {
                "A" => a,
                "X" => x,
                _ => b,
            })
            .collect::<Vec<f64>>()
    };
    p.blocks.push(Block::rapid(at(0.0, 0.0, 0.0)));
    // 300 mm, 300°, 40°: the norm of all three at 6000/min.
    p.blocks.push(Block::linear(
        at(300.0, 300.0, 40.0),
        Feed::PerMinute(6000.0),
    ));
    p.blocks.push(Block::linear(
        at(600.0, 300.0, 40.0),
        Feed::PerMinute(3000.0),
    ));
    let (_, tl) = written(&p, Dialect::MarlinXab, &m);
    let len = (300.0f64 * 300.0 + 300.0 * 300.0 + 40.0 * 40.0).sqrt();
    close(
        tl.block(1).unwrap().duration_s,
        len / 6000.0 * 60.0,
        "mixed",
    );
    close(tl.block(2).unwrap().duration_s, 6.0, "A alone");
}

#[test]
fn sample_and_poses_follow_the_written_blocks() {
    let m = machine("winder-4axis");
    let p = four_axis_program(&m);
    let (_, tl) = written(&p, Dialect::Sinumerik840d, &m);
    // Half-way through block 2 (0.6 s to 3.6 s): X at 300.
    let t = 0.6 + 1.5;
    assert_eq!(tl.block_at(t), Some(2));
    let q = tl.sample(t);
    close(q[1], 300.0, "X");
    let poses = tl.poses_at(&m, t);
    let rad: Vec<f64> = m
        .axes
        .iter()
        .zip(&q)
        .map(|(a, v)| if a.is_rotary() { v.to_radians() } else { *v })
        .collect();
    let fk = m.key_points(&rad);
    for (a, b) in poses.points.iter().zip(&fk) {
        assert!((a - b).norm() < 1e-9);
    }
    assert_eq!(poses.links.len(), m.links.len());
}

#[test]
fn a_limit_and_a_too_fast_block_are_found_at_their_block_and_line() {
    let m = machine("winder-4axis");
    let mut p = Program::new("BAD", program_axes(&m));
    let b = |a: f64, x: f64, t: f64| Block::linear(vec![a, x, 250.0, 0.0], Feed::InverseTime(t));
    p.blocks.push(Block::rapid(vec![0.0, 0.0, 250.0, 0.0]));
    p.blocks.push(b(36.0, 10.0, 1.0));
    p.blocks.push(b(72.0, 20.0, 1.0));
    // 500 mm in 0.25 s: 120000 mm/min on X (limit 60000).
    p.blocks
        .push(b(108.0, 520.0, 0.25).with_comment("too fast"));
    p.blocks.push(b(144.0, 530.0, 1.0));
    // X beyond its 3000 mm.
    p.blocks
        .push(b(180.0, 3010.5, 100.0).with_comment("too far"));
    p.blocks.push(b(216.0, 3000.0, 100.0));
    for dialect in [Dialect::Sinumerik840d, Dialect::LinuxCnc, Dialect::Cldata] {
        let mut text = String::new();
        write(&p, dialect, &mut text).unwrap();
        let line_of = |needle: &str, after: &str| {
            let start = text.lines().position(|l| l.contains(after)).unwrap();
            start
                + 1
                + text
                    .lines()
                    .skip(start)
                    .position(|l| l.contains(needle))
                    .unwrap()
        };
        let path = format!("bad.{}", dialect.extension());
        let r = check_text(Path::new(&path), &text, &m, "winder-4axis").unwrap();
        assert!(!r.clean);
        let find = |k: ViolationKind| {
            r.violations
                .iter()
                .find(|v| v.kind == k && v.axis == "X")
                .unwrap_or_else(|| panic!("{dialect:?}: no {k:?} in {:?}", r.violations))
        };
        let fast = find(ViolationKind::Velocity);
        assert_eq!((fast.block, fast.count), (4, 1), "{dialect:?}");
        assert_eq!(fast.line, line_of("520", "too fast"), "{dialect:?}\n{text}");
        close(fast.value, 120_000.0, "velocity");
        assert_eq!(fast.limit, 60_000.0);
        close(fast.time_s, 2.0 + 0.0, "velocity time");
        let far = find(ViolationKind::Position);
        assert_eq!((far.block, far.count), (6, 1), "{dialect:?}");
        assert_eq!(far.line, line_of("3010.5", "too far"), "{dialect:?}");
        assert_eq!((far.value, far.limit), (3010.5, 3000.0));
        // The first violation leads the line.
        assert!(
            r.line()
                .starts_with(&format!("{} violations: velocity", r.violations.len())),
            "{}",
            r.line()
        );
    }
}

#[test]
fn a_program_within_every_limit_is_clean() {
    let m = machine("winder-4axis");
    let mut p = Program::new("OK", program_axes(&m));
    p.blocks.push(Block::rapid(vec![0.0, 0.0, 250.0, 0.0]));
    // 60 mm/min steps up and down, far below every limit.
    for (i, x) in [1.0, 3.0, 6.0, 8.0, 9.0].iter().enumerate() {
        let a = 10.0 * (i + 1) as f64;
        p.blocks.push(Block::linear(
            vec![a, *x, 250.0, 0.0],
            Feed::InverseTime(1.0),
        ));
    }
    for dialect in [
        Dialect::Sinumerik840d,
        Dialect::Iso,
        Dialect::Cldata,
        Dialect::LinuxCnc,
    ] {
        let mut text = String::new();
        write(&p, dialect, &mut text).unwrap();
        let path = format!("ok.{}", dialect.extension());
        let r = check_text(Path::new(&path), &text, &m, "winder-4axis").unwrap();
        assert!(r.clean, "{dialect:?}: {:?}", r.violations);
        assert_eq!(r.line(), format!("clean: 6 blocks, {:.3} s", r.duration_s));
    }
}

#[test]
fn a_dwell_is_a_block_that_moves_nothing_for_its_time_in_each_dialect() {
    let m = machine("winder-4axis");
    let p = four_axis_program(&m);
    // Each dialect's way of writing 1.5 s, and the time without dwells.
    for (dialect, dwell) in [
        (Dialect::LinuxCnc, "G4 P1.5"),
        (Dialect::Sinumerik840d, "G4 F1.5"),
        (Dialect::Iso, "G04 P1500"),
        (Dialect::Iso, "G04 X1.5"),
        (Dialect::MarlinXab, "G4 P1500"),
        (Dialect::MarlinXab, "G4 S1.5"),
    ] {
        let (text, plain) = written(&p, dialect, &m);
        // After the third motion line, and at the end.
        let mut with = String::new();
        let mut motions = 0;
        let mut third = 0;
        for (i, line) in text.lines().enumerate() {
            with.push_str(line);
            with.push('\n');
            let l = line.trim_start_matches(|c: char| c == 'N' || c.is_ascii_digit() || c == ' ');
            if l.starts_with("G0")
                || l.starts_with("G1")
                || l.starts_with('X')
                || l.starts_with('A')
            {
                motions += 1;
                if motions == 3 {
                    with.push_str(dwell);
                    with.push('\n');
                    third = i + 2;
                }
            }
        }
        assert!(third > 0, "{dialect:?}");
        with.push_str(dwell);
        with.push('\n');
        let path = format!("program.{}", dialect.extension());
        let (read, lines, d) = read_program(Path::new(&path), &with, &m).unwrap();
        let tl = Timeline::new(&read, &lines, FeedRule::of(d), &m).unwrap();
        let what = format!("{dialect:?} {dwell}");
        assert_eq!(tl.len(), plain.len() + 2, "{what}");
        close(tl.duration_s(), plain.duration_s() + 3.0, &what);
        let dwells: Vec<_> = tl.blocks().filter(|b| b.dwell).collect();
        assert_eq!(dwells.len(), 2, "{what}");
        let first = dwells[0];
        assert_eq!(first.line, third, "{what}");
        close(first.duration_s, 1.5, &what);
        assert_eq!(first.from, first.to);
        // It follows the third block, where that one ended.
        let before = tl.block(first.index - 1).unwrap();
        close(first.start_s, before.start_s + before.duration_s, &what);
        assert_eq!(first.from, before.to);
        let mid = tl.sample(first.start_s + 0.75);
        assert_eq!(mid, before.to, "{what}");
        assert_eq!(tl.block_at(first.start_s + 0.75), Some(first.index));
        // The last: after every block.
        close(dwells[1].start_s, plain.duration_s() + 1.5, &what);
    }
}
