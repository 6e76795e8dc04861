//! temporary
#![allow(missing_docs, clippy::unwrap_used)]
use formcam_nc::{AxisSpec, Block, Dialect, Feed, Program, write};
fn program(n: usize, axes: &[(&str, bool)]) -> Program {
    let axes = axes
        .iter()
        .map(|(name, rotary)| AxisSpec {
            name: (*name).to_string(),
            rotary: *rotary,
        })
        .collect::<Vec<_>>();
    let mut p = Program::new("BENCH", axes);
    p.blocks.push(Block::rapid(vec![0.0; p.axes.len()]));
    for i in 1..n {
        let s = i as f64 * 1e-3;
        let target = p
            .axes
            .iter()
            .enumerate()
            .map(|(k, a)| {
                if a.rotary {
                    s * 360.0 / (k as f64 + 1.0)
                } else {
                    200.0 * (s * 0.7 + k as f64).sin()
                }
            })
            .collect();
        p.blocks
            .push(Block::linear(target, Feed::InverseTime(0.01)));
    }
    p
}
fn main() {
    let which = std::env::args().nth(1).unwrap();
    let n: usize = std::env::args()
        .nth(2)
        .map_or(1_000_000, |s| s.parse().unwrap());
    let iters: usize = std::env::args().nth(3).map_or(10, |s| s.parse().unwrap());
    let (d, p) = if which == "s" {
        (
            Dialect::Sinumerik840d,
            program(n, &[("X", false), ("A", true), ("Y", false), ("B", true)]),
        )
    } else {
        (
            Dialect::MarlinXab,
            program(n, &[("X", false), ("A", true), ("B", true)]),
        )
    };
    let mut out = String::new();
    write(&p, d, &mut out).unwrap();
    let mut best = f64::MAX;
    for _ in 0..iters {
        out.clear();
        let t = std::time::Instant::now();
        write(&p, d, &mut out).unwrap();
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!("{which}: best {:.1} ms, {} bytes", best * 1e3, out.len());
}
