//! The benches' two 10^5-block checks alone, for profilers: the 840D
//! vessel program repeated to 10^5 blocks checked for collisions with its
//! mandrel, and the snag check of a many-layer helical job. Prints the CPU
//! time of each run (every thread's, from `/proc/self/stat`, so that a
//! loaded machine's waits do not count) and the wall time.
//!
//! `cargo run --release -p formcam-program --example check_1e5 -- [collisions|snag|both] [runs]`
//! (`exhaustive` instead: both, and each check without bounds once,
//! compared).

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use formcam_sim::{SnagOptions, check_snag, check_snag_exhaustive};

// Each target uses part of the shared cases.
#[allow(dead_code)]
#[path = "../benches/support/cases.rs"]
mod cases;

/// The process's CPU time so far (every thread's, user and system), s, at
/// the kernel's 100 ticks a second (0 where the kernel does not say).
fn cpu_s() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // The fields after the command's closing parenthesis: utime and stime
    // are the 12th and 13th.
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let ticks: f64 = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|v| v.parse::<f64>().ok())
        .sum();
    ticks / 100.0
}

/// Runs `f` `runs` times; prints each run's CPU and wall time and the medians.
fn time<T>(name: &str, runs: usize, mut f: impl FnMut() -> T) {
    let (mut cpu, mut wall) = (Vec::new(), Vec::new());
    for _ in 0..runs {
        let (c0, w0) = (cpu_s(), Instant::now());
        std::hint::black_box(f());
        cpu.push(cpu_s() - c0);
        wall.push(w0.elapsed().as_secs_f64());
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    eprintln!(
        "{name}: median cpu {:.3} s, wall {:.3} s over {runs} runs",
        median(&mut cpu),
        median(&mut wall)
    );
}

fn collisions(runs: usize, exhaustive: bool) {
    let cases::VesselCase {
        machine: m,
        timeline: tl,
        collisions: c,
        ..
    } = cases::vessel(100_000);
    let found = c.check(&tl, &m);
    for v in &found {
        eprintln!(
            "{v} (worst {} mm at block {})",
            v.worst_value, v.worst_block
        );
    }
    if exhaustive {
        let (c0, w0) = (cpu_s(), Instant::now());
        let every = c.check_exhaustive(&tl, &m);
        eprintln!(
            "exhaustive: cpu {:.3} s, wall {:.3} s, the same findings: {}",
            cpu_s() - c0,
            w0.elapsed().as_secs_f64(),
            every == found
        );
    }
    time("collisions, 1e5 blocks", runs, || c.check(&tl, &m));
}

fn snag(runs: usize, exhaustive: bool) {
    let (tl, fibre, layers) = cases::helical(100_000);
    let opts = SnagOptions::default();
    eprintln!("{} blocks, {layers} layers", tl.len());
    for v in check_snag(&tl, &fibre, &opts).unwrap() {
        eprintln!(
            "{v} (worst {} mm at block {})",
            v.worst_value, v.worst_block
        );
    }
    if exhaustive {
        let (c0, w0) = (cpu_s(), Instant::now());
        let every = check_snag_exhaustive(&tl, &fibre, &opts).unwrap();
        eprintln!(
            "exhaustive: cpu {:.3} s, wall {:.3} s, the same findings: {}",
            cpu_s() - c0,
            w0.elapsed().as_secs_f64(),
            every == check_snag(&tl, &fibre, &opts).unwrap()
        );
    }
    time("snag, 1e5 blocks", runs, || {
        check_snag(&tl, &fibre, &opts).unwrap()
    });
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let what = args.get(1).map_or("both", String::as_str);
    let runs = args.get(2).and_then(|r| r.parse().ok()).unwrap_or(5);
    if what != "snag" {
        collisions(runs, what == "exhaustive");
    }
    if what != "collisions" {
        snag(runs, what == "exhaustive");
    }
}
