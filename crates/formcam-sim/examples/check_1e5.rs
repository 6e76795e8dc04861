//! The benches' two 10^5-block checks alone, for profilers: the 840D
//! vessel program repeated to 10^5 blocks checked for collisions with its
//! mandrel, and the snag check of a many-layer helical job. Prints the CPU
//! time of each run (every thread's, from `/proc/self/stat`, so that a
//! loaded machine's waits do not count) and the wall time.
//!
//! `cargo run --release -p formcam-sim --example check_1e5 -- [collisions|snag|both] [runs]`
//! (`exhaustive` instead: both, and each check without bounds once,
//! compared).

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use std::time::Instant;

use formcam_nc::Program;
use formcam_program::{Stage, WindJob, plan_until, write_program};
use formcam_sim::{
    Collisions, FeedRule, FreeFibre, Laminate, SnagOptions, Timeline, check_snag,
    check_snag_exhaustive, program_axes, read_program,
};

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
    let n = 100_000;
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let job_path = examples.join("vessel-program-840d.toml");
    let job = WindJob::from_toml(&std::fs::read_to_string(&job_path).unwrap(), &examples).unwrap();
    let m = job.machine.as_ref().unwrap().machine.clone();
    let planned = plan_until(&job, Stage::Program).unwrap();
    let mut text = Vec::new();
    write_program(&planned, &mut text).unwrap();
    let text = String::from_utf8(text).unwrap();
    let (one, _, _) = read_program(Path::new("program.mpf"), &text, &m).unwrap();
    let spindle = m.axis("A").unwrap();
    let turn = one.blocks.last().unwrap().target[spindle];
    let mut p = Program::new("VESSEL", program_axes(&m));
    let mut copy = 0.0;
    while p.blocks.len() < n {
        for b in one.blocks.iter().take(n - p.blocks.len()) {
            let mut b = b.clone();
            b.target[spindle] += copy * turn;
            p.blocks.push(b);
        }
        copy += 1.0;
    }
    let lines: Vec<usize> = (1..=n).collect();
    let laminate = Laminate::of_job(&job).unwrap();
    let stages = laminate.stage_of_blocks(p.blocks.iter().map(|b| b.comment.as_deref()));
    let c = Collisions::with_mandrel(&m, None, &laminate, stages).unwrap();
    let tl = Timeline::new(&p, &lines, FeedRule::Sinumerik840d, &m).unwrap();
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
    let layer = "[[layer]]\nband_width = 10.0\nband_thickness = 0.5\n\n";
    let job = |layers: usize| {
        let mut text = String::from(
            "[mandrel]\nkind = \"vessel\"\nradius = 100.0\ncylinder_length = 300.0\n\
             dome = \"hemisphere\"\npolar_opening = 30.0\n\n",
        );
        text.push_str(&layer.repeat(layers));
        text.push_str(
            "[eye]\nmode = \"axis-parallel\"\nradius = 160.0\nclearance = 20.0\nl_max = 600.0\n\n\
             [machine]\nname = \"winder-4axis\"\n\n\
             [motion]\ntolerance_mm = 0.002\ntolerance_deg = 0.002\n\n\
             [checks]\nallow = [\"slack\", \"clearance\", \"l_max\", \"reverse-rotation\"]\n\n\
             [post]\ndialect = \"sinumerik-840d\"\n",
        );
        WindJob::from_toml(&text, Path::new(".")).unwrap()
    };
    let one = plan_until(&job(1), Stage::Program).unwrap();
    let per_layer = one.program.as_ref().unwrap().program.blocks.len();
    let layers = 100_000usize.div_ceil(per_layer).max(1);
    let wound = plan_until(&job(layers), Stage::Program).unwrap();
    let mut bytes = Vec::new();
    write_program(&wound, &mut bytes).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    let m = wound.machine.clone().unwrap();
    let (p, lines, d) = read_program(Path::new("program.mpf"), &text, &m).unwrap();
    let tl = Timeline::new(&p, &lines, FeedRule::of(d), &m).unwrap();
    let fibre = FreeFibre::from_wound(&wound).unwrap();
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
