//! Modulo rotary axes: every dialect writes the spindle within 100 turns
//! (one turn for the modulo dialects), keeps every block's time, and reads
//! back the unwound angles.

#![allow(clippy::unwrap_used)]

use formcam_nc::{
    AxisSpec, BOUND_DEG, Block, Dialect, Feed, ModuloStyle, NcError, Program, keep_within_turns,
    read_cldata, read_gcode_in, write,
};
use proptest::prelude::*;

/// A winder program on A (modulo), X, B: `steps` of (A turn, X move, time or
/// feed) from a start angle.
fn winder(start_a: f64, steps: &[(f64, f64, f64, bool)], rezero_at: &[usize]) -> Program {
    let mut p = Program::new(
        "SPIN",
        vec![
            AxisSpec::rotary_modulo("A"),
            AxisSpec::linear("X"),
            AxisSpec::rotary("B"),
        ],
    );
    let mut pos = [start_a, 0.0, 0.0];
    p.blocks
        .push(Block::rapid(pos.to_vec()).with_comment("start"));
    for (i, &(da, dx, t, inverse)) in steps.iter().enumerate() {
        pos[0] += da;
        pos[1] += dx;
        pos[2] = (i % 7) as f64 * 3.5 - 10.0;
        let feed = if inverse {
            Feed::InverseTime(t)
        } else {
            Feed::PerMinute(100.0 + 1000.0 * t)
        };
        let mut b = Block::linear(pos.to_vec(), feed);
        b.rezero = rezero_at.contains(&(i + 1));
        p.blocks.push(b);
    }
    p
}

/// The largest |value| written for axis A (`A12.5`, `A-3`, `A=ACP(3)`,
/// CLDATA: the first `GOTO` value), and whether every value lies in a turn.
fn largest_written_a(text: &str, dialect: Dialect) -> f64 {
    let mut m: f64 = 0.0;
    for line in text.lines() {
        if dialect == Dialect::Cldata {
            if let Some(v) = line.strip_prefix("GOTO/") {
                m = m.max(v.split(',').next().unwrap().parse::<f64>().unwrap().abs());
            }
            continue;
        }
        if line.starts_with(';') || line.starts_with('(') {
            continue;
        }
        for w in line.split(' ') {
            let v = w
                .strip_prefix("A=ACP(")
                .or_else(|| w.strip_prefix("A=ACN("))
                .map(|v| v.trim_end_matches(')'))
                .or_else(|| w.strip_prefix('A'));
            if let Some(v) = v {
                m = m.max(v.parse::<f64>().unwrap().abs());
            }
        }
    }
    m
}

fn read(text: &str, dialect: Dialect, axes: &[AxisSpec]) -> Program {
    match dialect {
        Dialect::Cldata => read_cldata(text, axes).unwrap(),
        d => read_gcode_in(text, axes, d).unwrap(),
    }
}

/// Prepares, writes and reads back `p` in every dialect and checks the
/// bound, the times and the angles.
fn check_all(p: &Program) {
    let before = p.duration_s().unwrap();
    for dialect in Dialect::ALL {
        let style = ModuloStyle::of(dialect);
        let q = keep_within_turns(p, style).unwrap();
        // The same time, block by block where nothing was split.
        let after = q.duration_s().unwrap();
        assert!(
            (after - before).abs() <= 1e-9 * before,
            "{dialect}: {after} s vs {before} s"
        );
        // The first angle within its first turn, the rest moved by whole turns.
        let shift = p.blocks[0].target[0] - q.blocks[0].target[0];
        assert!((0.0..360.0).contains(&q.blocks[0].target[0]), "{dialect}");
        assert!((shift / 360.0 - (shift / 360.0).round()).abs() < 1e-9);
        let last = |p: &Program| p.blocks.last().unwrap().target.clone();
        assert!((last(p)[0] - shift - last(&q)[0]).abs() < 1e-6 * last(p)[0].abs().max(1.0));
        let mut text = String::new();
        write(&q, dialect, &mut text).unwrap();
        let largest = largest_written_a(&text, dialect);
        match style {
            ModuloStyle::Rezero => assert!(largest <= BOUND_DEG, "{dialect}: {largest}"),
            ModuloStyle::Modulo => assert!(largest < 360.0, "{dialect}: {largest}"),
        }
        let r = read(&text, dialect, &q.axes);
        assert_eq!(r.blocks.len(), q.blocks.len(), "{dialect}: blocks");
        for (i, (a, b)) in q.blocks.iter().zip(&r.blocks).enumerate() {
            for k in 0..3 {
                let tol = if k == 1 { 0.6e-3 } else { 0.6e-4 } + 1e-9 * a.target[k].abs();
                assert!(
                    (a.target[k] - b.target[k]).abs() <= tol,
                    "{dialect}: block {i} axis {k}: {} read back as {}",
                    a.target[k],
                    b.target[k]
                );
            }
            if style == ModuloStyle::Rezero && i > 0 {
                assert_eq!(a.rezero, b.rezero, "{dialect}: block {i} re-zero");
            }
        }
    }
}

#[test]
fn a_spindle_wound_up_past_the_bound_is_written_within_it() {
    // FiberPath's bundled tube wound the spindle to -291582°: many short
    // blocks and a few of several hundred turns.
    let mut steps = Vec::new();
    for i in 0..3000 {
        steps.push((-97.2, if i % 2 == 0 { 5.0 } else { -5.0 }, 0.05, true));
    }
    steps.push((-150_000.0, 800.0, 120.0, true));
    steps.push((20_000.5, 0.0, 10.0, true));
    steps.push((45.0, 0.0, 0.5, false));
    let p = winder(-1234.5, &steps, &[1000]);
    assert!(p.blocks.iter().any(|b| b.target[0].abs() > 400_000.0));
    check_all(&p);
}

#[test]
fn a_program_not_prepared_is_refused() {
    let p = winder(0.0, &[(40_000.0, 1.0, 1.0, true)], &[]);
    for dialect in Dialect::ALL {
        let mut text = String::new();
        let e = write(&p, dialect, &mut text).unwrap_err();
        assert!(matches!(e, NcError::Program(_)), "{dialect}: {e}");
        assert!(
            e.to_string().contains("keep_within_turns"),
            "{dialect}: {e}"
        );
        assert!(text.is_empty());
    }
    // Without the modulo flag the same program is written as it is.
    let mut q = p.clone();
    q.axes[0].modulo = false;
    let mut text = String::new();
    write(&q, Dialect::Iso, &mut text).unwrap();
    assert!(text.contains("A40000."));
}

#[test]
fn the_dialects_write_the_documented_words() {
    let p = winder(
        10.0,
        &[(350.0, 1.0, 1.0, true), (-20.0, 1.0, 1.0, true)],
        &[2],
    );
    let text = |d: Dialect| {
        let q = keep_within_turns(&p, ModuloStyle::of(d)).unwrap();
        let mut t = String::new();
        write(&q, d, &mut t).unwrap();
        t
    };
    // 10 -> 360 -> 340: modulo 0 positive, then 340 negative.
    let s = text(Dialect::Sinumerik840d);
    assert!(s.contains("A=ACP(10)") && s.contains("A=ACP(0)") && s.contains("A=ACN(340)"));
    let l = text(Dialect::LinuxCnc);
    assert!(l.contains("G0 A10 ") && l.contains("G1 A0 X1") && l.contains("G1 A-340 X2"));
    // Re-zeroed before block 2, standing at 360: G92 A0, then 340.
    let m = text(Dialect::MarlinXab);
    assert!(m.contains("\nG92 A0\nG1 A-20 X2"), "{m}");
    let i = text(Dialect::Iso);
    assert!(i.contains("\nG92 A0.\nG01 A-20. X2."), "{i}");
    let c = text(Dialect::Cldata);
    assert!(c.contains("\nORIGIN/A,360\nGOTO/-20,2,"), "{c}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn any_winding_keeps_time_bound_and_angles(
        start in -1.0e6..1.0e6f64,
        steps in proptest::collection::vec(
            (-40_000.0..40_000.0f64, -50.0..50.0f64, 0.001..30.0f64, any::<bool>()),
            1..60,
        ),
        rezero in proptest::collection::vec(1usize..60, 0..4),
    ) {
        check_all(&winder(start, &steps, &rezero));
    }
}

#[test]
fn a_template_with_a_rezero_field_re_zeroes() {
    use formcam_nc::{Template, write_template};
    let p = winder(
        5.0,
        &[(50_000.0, 1.0, 1.0, true), (10.0, 1.0, 1.0, true)],
        &[],
    );
    let t = Template::from_toml(
        "extension = \"t\"\nblock = \"L {axes} F{f}\"\nrezero = \"PRESET {axes} ({A})\"\n",
    )
    .unwrap();
    assert_eq!(t.modulo_style(), Some(ModuloStyle::Rezero));
    let q = keep_within_turns(&p, ModuloStyle::Rezero).unwrap();
    let mut text = String::new();
    write_template(&q, &t, &mut text).unwrap();
    let presets: Vec<&str> = text.lines().filter(|l| l.starts_with("PRESET")).collect();
    assert!(!presets.is_empty(), "{text}");
    let largest = text
        .lines()
        .flat_map(|l| l.split(' '))
        .filter_map(|w| w.strip_prefix('A'))
        .map(|v| v.parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max);
    assert!(largest <= BOUND_DEG, "{largest}");
    // The re-zeroed angle is the one within the turn where the axis stands.
    let k = q.blocks.iter().position(|b| b.rezero).unwrap();
    let within = q.blocks[k - 1].target[0].rem_euclid(360.0);
    let shown: f64 = presets[0]
        .split(['A', ' '])
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    assert!((shown - within).abs() < 1e-4, "{shown} vs {within}");
    // Not prepared: refused; without the field: written unwound.
    assert!(write_template(&p, &t, &mut String::new()).is_err());
    let plain = Template::from_toml("extension = \"t\"\nblock = \"L {axes}\"\n").unwrap();
    assert_eq!(plain.modulo_style(), None);
    let mut text = String::new();
    write_template(&p, &plain, &mut text).unwrap();
    assert!(text.contains("A50005"));
}
