//! Times the whole dressing of a job (the least of several runs) and writes
//! each step's removed area, for `scripts/dress_numpy.py` to compare with its
//! NumPy version of the same simulation.
//!
//! `cargo run --release -p formcam-dress --example dress_time -- JOB [STEP [RUNS [AREAS.csv]]]`

use std::error::Error;
use std::fmt::Write as _;
use std::time::Instant;

use formcam_dress::{DressJob, dress};

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .ok_or("usage: dress_time JOB [STEP [RUNS [AREAS.csv]]]")?;
    let mut job = DressJob::from_toml(&std::fs::read_to_string(path)?)?;
    if let Some(step) = args.get(2) {
        job.process.step = step.parse()?;
    }
    let runs: usize = args.get(3).map_or(Ok(5), |s| s.parse())?;
    let spec = job.spec(None)?;
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        let d = dress(&spec)?;
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(d);
    }
    let d = last.ok_or("no run")?;
    println!(
        "rust_seconds {best:.6} steps {} removed_mm2 {:.15e} ratio_uncontrolled {:.6} ratio_controlled {:.6}",
        d.forming.steps.len(),
        d.forming.removed(),
        d.feed.ratio_uncontrolled.unwrap_or(f64::NAN),
        d.feed.ratio_controlled.unwrap_or(f64::NAN),
    );
    if let Some(out) = args.get(4) {
        let mut s = String::from("area\n");
        for st in &d.forming.steps {
            writeln!(s, "{:.17e}", st.area)?;
        }
        std::fs::write(out, s)?;
    }
    Ok(())
}
