//! The small programs the tests write and read.

#![allow(dead_code)]

use formcam_nc::{AxisSpec, Block, Feed, Program};

/// A few rapid and linear blocks on X, A, Y, B: per-minute feeds, one
/// inverse-time block with linear travel and one of a rotary axis only, and
/// comments (one with parentheses).
pub fn xayb() -> Program {
    let mut p = Program::new(
        "WIND1",
        vec![
            AxisSpec::linear("X"),
            AxisSpec::rotary("A"),
            AxisSpec::linear("Y"),
            AxisSpec::rotary("B"),
        ],
    );
    p.header_comments = vec![
        "formcam test program".to_string(),
        "layer 1 (helical), 2 circuits".to_string(),
    ];
    p.blocks = vec![
        Block::rapid(vec![0.0, 0.0, 50.0, 0.0]).with_comment("start"),
        Block::linear(vec![100.0, 90.0, 50.0, 0.0], Feed::PerMinute(1200.0)),
        Block::linear(vec![150.5, 135.25, 48.125, -12.5], Feed::PerMinute(1200.0))
            .with_comment("turn"),
        Block::linear(
            vec![200.0, 180.00012, 48.125, -30.0],
            Feed::InverseTime(0.5),
        ),
        Block::linear(vec![200.0, 270.0, 48.125, -30.0], Feed::InverseTime(0.25)),
        Block::linear(vec![99.9996, 300.0, 50.0, 0.0], Feed::PerMinute(950.5)),
        Block::rapid(vec![0.0, 300.0, 60.0, 0.0]),
    ];
    p
}

/// The same program on X, A, B (Marlin): Y dropped.
pub fn xab() -> Program {
    let mut p = xayb();
    p.axes.remove(2);
    for b in &mut p.blocks {
        b.target.remove(2);
    }
    p
}

/// A longer program with values that need f64 (large rotary angles) and
/// negative values: a deterministic pseudo-random walk.
pub fn walk(axes: Vec<AxisSpec>, n: usize) -> Program {
    let mut p = Program::new("WALK", axes);
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut pos = vec![0.0; p.axes.len()];
    for i in 0..n {
        for (k, a) in p.axes.iter().enumerate() {
            let step = if a.rotary { 200.0 } else { 40.0 };
            pos[k] += (rnd() - 0.3) * step;
            if a.rotary && k == 1 {
                pos[k] += 1000.0; // winds on: tens of thousands of degrees
            }
        }
        let b = match i % 5 {
            0 => Block::rapid(pos.clone()),
            1 | 2 => Block::linear(pos.clone(), Feed::PerMinute(100.0 + 5000.0 * rnd())),
            _ => Block::linear(pos.clone(), Feed::InverseTime(0.001 + rnd())),
        };
        p.blocks.push(b);
    }
    p
}
