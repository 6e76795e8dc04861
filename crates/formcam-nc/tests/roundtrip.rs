//! Write every dialect, read it back: the same axis values to the printed
//! precision and the same motion kinds (and feeds where the dialect keeps them).

#![allow(clippy::unwrap_used)]

mod common;

use formcam_nc::{AxisSpec, Dialect, Feed, Program, read_cldata, read_gcode, write};

fn read(text: &str, dialect: Dialect, axes: &[AxisSpec]) -> Program {
    match dialect {
        Dialect::Cldata => read_cldata(text, axes).unwrap(),
        _ => read_gcode(text, axes).unwrap(),
    }
}

fn check(p: &Program, dialect: Dialect) {
    let mut text = String::new();
    write(p, dialect, &mut text).unwrap();
    let q = read(&text, dialect, &p.axes);
    assert_eq!(q.blocks.len(), p.blocks.len(), "{dialect}: block count");
    assert_eq!(q.name, p.name, "{dialect}: name");
    for (i, (a, b)) in p.blocks.iter().zip(&q.blocks).enumerate() {
        assert_eq!(a.kind, b.kind, "{dialect}: block {i} kind");
        for (k, axis) in p.axes.iter().enumerate() {
            // Half a printed unit, and the rounding of v * 10^d in f64.
            let tol = if axis.rotary { 0.5e-4 } else { 0.5e-3 } + 1e-9 + a.target[k].abs() * 1e-15;
            assert!(
                (a.target[k] - b.target[k]).abs() <= tol,
                "{dialect}: block {i} axis {}: {} read back as {}",
                axis.name,
                a.target[k],
                b.target[k]
            );
        }
        match (dialect, a.feed, b.feed) {
            (_, Feed::None, Feed::None) => {}
            (_, Feed::PerMinute(f), Feed::PerMinute(g)) => {
                assert!(
                    (f - g).abs() <= 0.05 + 1e-9,
                    "{dialect}: block {i} feed {f} vs {g}"
                );
            }
            (
                Dialect::Sinumerik840d | Dialect::Iso | Dialect::LinuxCnc,
                Feed::InverseTime(t),
                Feed::InverseTime(u),
            ) => {
                // F = 60 / t with 3 decimals.
                let f = 60.0 / t;
                assert!(
                    (f - 60.0 / u).abs() <= 0.5e-3 + 1e-9,
                    "{dialect}: block {i} time {t} vs {u}"
                );
            }
            // CLDATA and Marlin convert inverse time to a per-minute feed.
            (Dialect::Cldata | Dialect::MarlinXab, Feed::InverseTime(_), _) => {}
            (_, f, g) => panic!("{dialect}: block {i}: feed {f:?} read back as {g:?}"),
        }
    }
}

#[test]
fn small_program_every_dialect() {
    for d in Dialect::ALL {
        let p = if d == Dialect::MarlinXab {
            common::xab()
        } else {
            common::xayb()
        };
        check(&p, d);
    }
}

#[test]
fn comments_come_back() {
    for d in Dialect::ALL {
        let p = if d == Dialect::MarlinXab {
            common::xab()
        } else {
            common::xayb()
        };
        let mut text = String::new();
        write(&p, d, &mut text).unwrap();
        let q = read(&text, d, &p.axes);
        assert_eq!(q.blocks[0].comment.as_deref(), Some("start"), "{d}");
        assert_eq!(q.blocks[2].comment.as_deref(), Some("turn"), "{d}");
        assert_eq!(q.header_comments[0], "formcam test program", "{d}");
    }
}

#[test]
fn long_walk_every_dialect() {
    let xayb = vec![
        AxisSpec::linear("X"),
        AxisSpec::rotary("A"),
        AxisSpec::linear("Y"),
        AxisSpec::rotary("B"),
    ];
    for d in Dialect::ALL {
        let axes = if d == Dialect::MarlinXab {
            vec![
                AxisSpec::linear("X"),
                AxisSpec::rotary("A"),
                AxisSpec::rotary("B"),
            ]
        } else {
            xayb.clone()
        };
        check(&common::walk(axes, 2000), d);
    }
}

#[test]
fn sinumerik_named_axes() {
    let axes = vec![
        AxisSpec::linear("X"),
        AxisSpec::rotary("J1"),
        AxisSpec::linear("Z2"),
        AxisSpec::rotary("B"),
    ];
    let p = common::walk(axes, 500);
    let mut text = String::new();
    write(&p, Dialect::Sinumerik840d, &mut text).unwrap();
    assert!(text.contains(" J1="));
    check(&p, Dialect::Sinumerik840d);
}

#[test]
fn incremental_and_modal_input() {
    let axes = [AxisSpec::linear("X"), AxisSpec::rotary("A")];
    let text = "\
; hand written
N5 G21 G90 G94 G17
G0 X10 A5
G1 F600
X20 (modal G1, F600)
G91 X5 A-5
G90 G93 G01 X30 F120.
G4 P0.5
G94 G00 A0
";
    let p = read_gcode(text, &axes).unwrap();
    let t: Vec<Vec<f64>> = p.blocks.iter().map(|b| b.target.clone()).collect();
    assert_eq!(
        t,
        [
            [10.0, 5.0],
            [20.0, 5.0],
            [25.0, 0.0],
            [30.0, 0.0],
            [30.0, 0.0]
        ]
    );
    assert_eq!(p.blocks[1].feed, Feed::PerMinute(600.0));
    assert_eq!(p.blocks[1].comment.as_deref(), Some("modal G1, F600"));
    assert_eq!(p.blocks[3].feed, Feed::InverseTime(0.5));
    assert_eq!(p.blocks[4].feed, Feed::None);
    assert_eq!(p.header_comments, ["hand written"]);
}

#[test]
fn duration() {
    let p = common::xayb();
    // block 1: 100 mm at 1200 -> 5 s; block 2: hypot(50.5, 1.875) at 1200;
    // blocks 3 and 4: 0.5 + 0.25 s; block 5: hypot(100.0004, 1.875) at 950.5.
    let expected =
        5.0 + 50.5f64.hypot(1.875) / 1200.0 * 60.0 + 0.75 + 100.0004f64.hypot(1.875) / 950.5 * 60.0;
    assert!((p.duration_s().unwrap() - expected).abs() < 1e-9);
    assert_eq!(p.block_time_s(0), None);
    assert_eq!(p.block_time_s(4), Some(0.25));
    assert_eq!(Program::default().duration_s(), None);
}

#[test]
fn programs_long_enough_to_be_written_in_parallel() {
    let xayb = vec![
        AxisSpec::linear("X"),
        AxisSpec::rotary("A"),
        AxisSpec::linear("Y"),
        AxisSpec::rotary("B"),
    ];
    check(&common::walk(xayb, 70_000), Dialect::Sinumerik840d);
    let xab = vec![
        AxisSpec::linear("X"),
        AxisSpec::rotary("A"),
        AxisSpec::rotary("B"),
    ];
    check(&common::walk(xab, 70_000), Dialect::MarlinXab);
}

#[test]
fn long_cldata_records_continue_within_72_columns() {
    // Seven axes with large values: each GOTO needs a continuation line.
    let axes: Vec<AxisSpec> = ["A", "J1", "J2", "J3", "J4", "J5", "J6"]
        .iter()
        .map(|n| AxisSpec::rotary(*n))
        .collect();
    let mut p = common::walk(axes, 300);
    for b in &mut p.blocks {
        for v in &mut b.target {
            *v = *v * 1000.0 - 123_456.789_1;
        }
    }
    let mut text = String::new();
    write(&p, Dialect::Cldata, &mut text).unwrap();
    assert!(
        text.lines().all(|l| l.len() <= 72),
        "a record runs past column 72"
    );
    assert!(text.lines().any(|l| l.ends_with(",$")));
    check(&p, Dialect::Cldata);
}

/// Marlin has no inverse time: a timed block's time becomes a feed over its
/// travel, which a timed first block (from an unknown position) and a timed
/// block that moves nothing do not have. Written before any feed, such a
/// block takes the first feed of a later block (Marlin itself would move at
/// its default feed, `DEFAULT_FEEDRATE_MM_M`, not the program's), or
/// Marlin's default 4000 mm/min when no later block has one, and the program
/// reads back with Marlin's reader.
#[test]
fn marlin_timed_blocks_before_any_feed_read_back() {
    use formcam_nc::{Block, read_gcode_in};
    let axes = vec![
        AxisSpec::linear("X"),
        AxisSpec::rotary("A"),
        AxisSpec::rotary("B"),
    ];
    let timed = |q: [f64; 3], t: f64| Block::linear(q.to_vec(), Feed::InverseTime(t));
    let mut p = Program::new("MARLIN", axes.clone());
    // A timed first block, one that moves nothing, then 30 mm in 2 s: 900 mm/min.
    p.blocks.push(timed([10.0, 0.0, 0.0], 1.0));
    p.blocks.push(timed([10.0, 0.0, 0.0], 0.5));
    p.blocks.push(timed([40.0, 0.0, 0.0], 2.0));
    let mut text = String::new();
    write(&p, Dialect::MarlinXab, &mut text).unwrap();
    let q =
        read_gcode_in(&text, &axes, Dialect::MarlinXab).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let feeds: Vec<Feed> = q.blocks.iter().map(|b| b.feed).collect();
    assert_eq!(feeds, [Feed::PerMinute(900.0); 3], "{text}");
    // The feed is written once, on the first block.
    assert_eq!(text.matches(" F").count(), 1, "{text}");
    // No later block has a feed: Marlin's own default.
    let mut p = Program::new("STILL", axes.clone());
    p.blocks.push(timed([0.0, 0.0, 0.0], 1.0));
    p.blocks.push(timed([0.0, 0.0, 0.0], 1.0));
    let mut text = String::new();
    write(&p, Dialect::MarlinXab, &mut text).unwrap();
    let q =
        read_gcode_in(&text, &axes, Dialect::MarlinXab).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let feeds: Vec<Feed> = q.blocks.iter().map(|b| b.feed).collect();
    assert_eq!(feeds, [Feed::PerMinute(4000.0); 2], "{text}");
    // A feed in force is kept: a block that moves nothing after a feed
    // writes none.
    let mut p = Program::new("KEPT", axes.clone());
    p.blocks.push(Block::rapid(vec![0.0; 3]));
    p.blocks.push(timed([60.0, 0.0, 0.0], 6.0));
    p.blocks.push(timed([60.0, 0.0, 0.0], 1.0));
    let mut text = String::new();
    write(&p, Dialect::MarlinXab, &mut text).unwrap();
    let q = read_gcode_in(&text, &axes, Dialect::MarlinXab).unwrap();
    assert_eq!(q.blocks[2].feed, Feed::PerMinute(600.0), "{text}");
    assert_eq!(text.matches(" F").count(), 1, "{text}");
}
