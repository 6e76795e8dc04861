//! Winding runs through the library: the values of `path.csv`, `eye.csv`,
//! `blocks.csv`, the programs and `summary.json` that `formcam wind` writes.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

mod common;

use std::path::Path;

use common::{examples, machines, scratch, summary, text};
use formcam_program::{EYE_CLEARANCE_MM, Stage};
use formcam_run::{RunOutput, wind, wind_file};

/// An example job run up to `stage`.
fn example(name: &str, stage: Stage) -> RunOutput {
    wind(&examples().join(name), Path::new("out"), stage).unwrap()
}

/// A job given as text (its machine paths made absolute) run as a program.
fn winds(name: &str, job: &str) -> serde_json::Value {
    let path = scratch(name).join("job.toml");
    std::fs::write(&path, job).unwrap();
    summary(&wind(&path, Path::new("out"), Stage::Program).unwrap())
}

/// FiberPath's tube, run as `formcam wind` runs a `.wind` document.
fn fiberpath() -> RunOutput {
    wind_file(
        &examples().join("tube-fiberpath.wind"),
        Path::new("out"),
        EYE_CLEARANCE_MM,
        &[],
    )
    .unwrap()
}

/// An example job's text with its machine paths made absolute.
fn example_text(name: &str) -> String {
    std::fs::read_to_string(examples().join(name))
        .unwrap()
        .replace("../machines/", &format!("{}/", machines().display()))
}

#[test]
fn a_geodesic_path_turns_as_the_closed_form_says() {
    let run = example("vessel-geodesic.toml", Stage::Path);
    let csv = text(&run, "path.csv");
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("s,z,r,v,alpha,c,mu"));
    assert_eq!(lines.count(), 2001);
    let summary = summary(&run);
    for key in [
        "turn_angle_pass_rad",
        "turn_angle_circuit_rad",
        "mu",
        "alpha_equator_rad",
        "circuits",
        "fibre_length_mm",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}");
    }
    let alpha = 0.3f64.asin();
    let expect = 2.0 * std::f64::consts::PI + 2.0 * 300.0 * alpha.tan() / 100.0;
    let got = summary["turn_angle_circuit_rad"].as_f64().unwrap();
    assert!((got - expect).abs() < 1e-9, "{got} vs {expect}");
    assert!((summary["alpha_equator_rad"].as_f64().unwrap() - alpha).abs() < 1e-9);
    assert_eq!(summary["mu"].as_f64().unwrap(), 0.0);
    let circuits = summary["circuits"].as_u64().unwrap() as f64;
    assert_eq!(
        circuits,
        (std::f64::consts::TAU * 100.0 * alpha.cos() / 10.0).ceil()
    );
}

#[test]
fn the_eye_stage_gives_the_trajectory_and_its_summary() {
    let run = example("vessel-eye-pull-speed.toml", Stage::Eye);
    let csv = text(&run, "eye.csv");
    let header = csv.lines().next().unwrap();
    assert!(
        header.starts_with("x,z,r,v,alpha,l,eye_z,eye_r,eye_v,lambda,u"),
        "{header}"
    );
    assert_eq!(csv.lines().count(), 1 + 1001);
    let summary = summary(&run);
    assert_eq!(summary["eye_mode"], "pull-speed");
    assert_eq!(summary["constraints_ok"], true);
    assert!(summary["violations"].as_array().unwrap().is_empty());
    let (lo, hi) = (
        summary["u_min"].as_f64().unwrap(),
        summary["u_max"].as_f64().unwrap(),
    );
    assert!(lo > 0.0 && lo <= 1.0 && hi >= 1.0, "{lo} {hi}");
    assert!(summary["u_rms_dev"].as_f64().unwrap() >= 0.0);
    // The path outputs come along.
    assert!(run.file("path.csv").is_some() && run.file("eye.svg").is_some());
}

#[test]
fn the_whole_program_is_timed_and_written() {
    let run = example("vessel-program-840d.toml", Stage::Program);
    let summary = summary(&run);
    for key in [
        "blocks",
        "program_time_s",
        "program_time_pairwise_s",
        "program_time_global_s",
        "layers",
        "fibre_length_mm",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}");
    }
    let global = summary["program_time_global_s"].as_f64().unwrap();
    let pairwise = summary["program_time_pairwise_s"].as_f64().unwrap();
    assert!(global <= pairwise * (1.0 + 1e-9));
    let blocks = summary["blocks"].as_u64().unwrap() as usize;
    let program = text(&run, "program.mpf");
    assert!(program.contains("G90 G94 G71") && program.trim_end().ends_with("M30"));
    assert_eq!(
        program.lines().filter(|l| l.contains(" G1 ")).count(),
        blocks
    );
    let csv = text(&run, "blocks.csv");
    assert!(csv.starts_with("block,t,A,X,Y,B,"));
    assert_eq!(csv.lines().count(), blocks + 1);
}

#[test]
fn a_multi_layer_job_grows_the_mandrel_and_writes_one_program() {
    let run = example("tube-layers-4axis.toml", Stage::Program);
    let summary = summary(&run);
    assert_eq!(summary["layers"], 4);
    let layers = summary["per_layer"].as_array().unwrap();
    let kinds: Vec<&str> = layers.iter().map(|l| l["kind"].as_str().unwrap()).collect();
    assert_eq!(kinds, ["hoop", "helical", "skip", "helical"]);
    // Each winding layer is planned on the mandrel grown by the ones before it.
    let t0 = layers[0]["thickness_mm"].as_f64().unwrap();
    let g1 = layers[1]["mandrel_growth_mm"].as_f64().unwrap();
    let t1 = layers[1]["thickness_mm"].as_f64().unwrap();
    let g3 = layers[3]["mandrel_growth_mm"].as_f64().unwrap();
    assert!((g1 - t0).abs() < 1e-12 && (g3 - (t0 + t1)).abs() < 1e-12);
    // A hoop layer lays one band width per turn.
    let hoop = layers[0]["alpha_equator_deg"].as_f64().unwrap();
    let expect = (std::f64::consts::TAU * 75.0 / 6.0).atan().to_degrees();
    assert!((hoop - expect).abs() < 1e-9, "{hoop} vs {expect}");
    let sum: f64 = layers.iter().map(|l| l["time_s"].as_f64().unwrap()).sum();
    let total = summary["program_time_s"].as_f64().unwrap();
    assert!(total >= sum - 1e-6, "{total} vs {sum}");
    let program = text(&run, "program.ngc");
    for label in [
        "layer 1 [hoop]",
        "layer 2 [helical]",
        "layer 3 [skip]",
        "layer 4 [helical]",
    ] {
        assert!(program.contains(label), "{label}");
    }
    let csv = text(&run, "blocks.csv");
    assert_eq!(
        csv.lines().count() - 1,
        summary["blocks"].as_u64().unwrap() as usize
    );
    // Path, eye and axes take one [winding].
    let e = wind(
        &examples().join("tube-layers-4axis.toml"),
        Path::new("out"),
        Stage::Axes,
    )
    .unwrap_err();
    assert!(e.to_string().contains("[[layer]]"), "{e}");
}

#[test]
fn a_wind_file_runs_on_the_xab_winder_and_writes_marlin() {
    let run = fiberpath();
    let summary = summary(&run);
    assert_eq!(summary["layers"], 3);
    assert_eq!(summary["machine"], "X/A/B winder");
    let layers = summary["per_layer"].as_array().unwrap();
    assert_eq!(
        layers[1]["alpha_equator_deg"].as_f64().unwrap().round(),
        45.0
    );
    let program = text(&run, "program.gcode");
    assert!(program.contains("G21") && program.contains("G90") && program.contains("G94"));
    assert!(
        program
            .lines()
            .any(|l| l.starts_with("G1 ") && l.contains('A') && l.contains('X'))
    );
    assert!(!program.contains('Y') && !program.contains("G93"));
}

#[test]
fn acceleration_limits_lengthen_the_program() {
    // Kept by default: slower than the velocity and jump limits alone.
    let kept = winds("acceleration", &example_text("vessel-program-840d.toml"));
    let with = kept["program_time_s"].as_f64().unwrap();
    let global = kept["program_time_global_s"].as_f64().unwrap();
    assert!(with > global, "{with} vs {global}");
    // Switched off: the program times of the velocity and jump limits.
    let job = example_text("vessel-program-840d.toml")
        .replace("# acceleration = true", "acceleration = false #");
    let free = winds("no-acceleration", &job);
    assert_eq!(free["program_time_s"], free["program_time_global_s"]);
    assert!(free["program_time_s"].as_f64().unwrap() < with);
}

#[test]
fn the_written_program_is_checked_on_its_machine() {
    let run = example("vessel-program-840d.toml", Stage::Program);
    assert_eq!(run.violations, Some(0), "{}", run.line);
    assert!(run.line.contains("; checked: clean ("), "{}", run.line);
    let report: serde_json::Value =
        serde_json::from_slice(&run.file("check.json").unwrap().bytes).unwrap();
    assert_eq!(report["program"], "out/program.mpf");
    assert_eq!(report["dialect"], "sinumerik-840d");
    let blocks = summary(&run)["blocks"].as_u64().unwrap();
    // The program's blocks and the rapid to the start (and any block the
    // post splits to keep the spindle's words within their turns).
    assert!(report["blocks"].as_u64().unwrap() > blocks, "{report}");
    // Without a program nothing is checked.
    let axes = example("vessel-program-840d.toml", Stage::Axes);
    assert_eq!(axes.violations, None);
    assert!(axes.file("check.json").is_none());
    // Nor when asked not to.
    let off = formcam_run::wind_checked_with(
        &examples().join("vessel-program-840d.toml"),
        Path::new("out"),
        Stage::Program,
        formcam_run::ProgramCheck::Off,
        &formcam_run::progress::Silent,
    )
    .unwrap();
    assert_eq!(off.violations, None);
    assert!(off.file("check.json").is_none());
    assert_eq!(off.file("program.mpf"), run.file("program.mpf"));
}

#[test]
fn a_one_way_hoop_lays_one_ply() {
    let both = example_text("tube-layers-4axis.toml");
    let one = both.replacen("kind = \"hoop\"\n", "kind = \"hoop\"\none_way = true\n", 1);
    let run = |name: &str, text: &str| winds(name, text)["per_layer"][0].clone();
    let (b, o) = (run("hoop-both", &both), run("hoop-one", &one));
    assert_eq!(o["one_way"], true);
    let (tb, to) = (
        b["thickness_mm"].as_f64().unwrap(),
        o["thickness_mm"].as_f64().unwrap(),
    );
    assert!((to - 0.5 * tb).abs() < 1e-12, "{to} vs {tb}");
    assert!(o["time_s"].as_f64().unwrap() < b["time_s"].as_f64().unwrap());
}

/// The largest |value| of the spindle's words (`A..`, `A=ACP(..)`, `A=ACN(..)`).
fn largest_spindle_angle(program: &str) -> f64 {
    program
        .lines()
        .filter(|l| !l.starts_with(';') && !l.starts_with('('))
        .flat_map(|l| l.split(' '))
        .filter_map(|w| {
            w.strip_prefix("A=ACP(")
                .or_else(|| w.strip_prefix("A=ACN("))
                .map(|v| v.trim_end_matches(')'))
                .or_else(|| w.strip_prefix('A'))
        })
        .map(|v| v.parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max)
}

#[test]
fn the_spindle_stays_within_100_turns() {
    // FiberPath's tube wound the spindle to A-291582.1534 on Marlin: now
    // re-zeroed by G92 between layers and before it would pass 100 turns.
    let run = fiberpath();
    let program = text(&run, "program.gcode");
    let largest = largest_spindle_angle(&program);
    assert!(largest <= 36000.0, "largest |A| {largest}");
    assert!(program.lines().filter(|l| l.starts_with("G92 A")).count() >= 3);
    // The spindle's unwound angle still runs far beyond: blocks.csv keeps it.
    let csv = text(&run, "blocks.csv");
    let unwound = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max);
    assert!(unwound > 100_000.0, "{unwound}");
    // Sinumerik 840D: a modulo axis, every angle within the turn.
    let run = example("vessel-layers-840d.toml", Stage::Program);
    let program = text(&run, "program.mpf");
    assert!(program.contains("A=ACP(") && program.contains("A=ACN("));
    assert!(largest_spindle_angle(&program) < 360.0);
}

/// A CSV's header and rows of numbers.
fn csv(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// `axis_ranges` spans every block of every layer: each block end of
/// `blocks.csv` lies within it.
fn ranges_cover_every_block(name: &str, run: &RunOutput) {
    let s = summary(run);
    let (header, rows) = csv(&text(run, "blocks.csv"));
    for r in s["axis_ranges"].as_array().unwrap() {
        let axis = r["axis"].as_str().unwrap();
        let col = header.iter().position(|h| h == axis).unwrap();
        let (lo, hi) = (r["min"].as_f64().unwrap(), r["max"].as_f64().unwrap());
        let (blo, bhi) = rows
            .iter()
            .map(|row| row[col])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        assert!(
            lo <= blo + 1e-9 && hi >= bhi - 1e-9,
            "{name}: {axis} [{lo}, {hi}] vs blocks [{blo}, {bhi}]"
        );
    }
}

#[test]
fn the_summary_and_the_files_describe_the_whole_program() {
    // One layer: the spindle's range covers every circuit, not one.
    let run = example("vessel-program-840d.toml", Stage::Program);
    ranges_cover_every_block("one-layer", &run);
    let s = summary(&run);
    let (header, circuit) = csv(&text(&run, "axes.csv"));
    let a = header.iter().position(|h| h == "A").unwrap();
    let circuit_span = circuit
        .iter()
        .map(|r| r[a])
        .fold(f64::NEG_INFINITY, f64::max)
        - circuit.iter().map(|r| r[a]).fold(f64::INFINITY, f64::min);
    let range = s["axis_ranges"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["axis"] == "A")
        .unwrap()
        .clone();
    let span = range["max"].as_f64().unwrap() - range["min"].as_f64().unwrap();
    assert!(
        s["circuits"].as_u64().unwrap() > 1 && span > 1.5 * circuit_span,
        "A spans {span} deg over the program, {circuit_span} deg over a circuit"
    );

    // Several layers: each layer's own outputs, and the axes over the program.
    let run = example("tube-layers-4axis.toml", Stage::Program);
    ranges_cover_every_block("layers", &run);
    let s = summary(&run);
    let mut wound = 0;
    for l in s["per_layer"].as_array().unwrap() {
        let dir = format!("layer-{:02}", l["layer"].as_u64().unwrap());
        if l["kind"] == "skip" {
            assert!(!run.files.iter().any(|f| f.name.starts_with(&dir)));
            continue;
        }
        wound += 1;
        for f in [
            "path.csv", "path.svg", "eye.csv", "eye.svg", "axes.csv", "band.csv",
        ] {
            assert!(run.file(&format!("{dir}/{f}")).is_some(), "{dir}/{f}");
        }
        let (h, rows) = csv(&text(&run, &format!("{dir}/axes.csv")));
        assert_eq!(h[0], "x");
        assert!(rows.len() > 100);
    }
    assert!(wound >= 2);
    let (h, rows) = csv(&text(&run, "axes.csv"));
    assert_eq!(h[0], "t");
    let (_, blocks) = csv(&text(&run, "blocks.csv"));
    // The start, every block, and a move between layers that do not join.
    assert!(
        rows.len() > blocks.len(),
        "{} vs {}",
        rows.len(),
        blocks.len()
    );
    let total = rows.last().unwrap()[0];
    let time = s["program_time_s"].as_f64().unwrap();
    assert!((total - time).abs() < 1e-6 * time, "{total} vs {time}");
    assert!(rows.windows(2).all(|w| w[1][0] >= w[0][0]));
}
