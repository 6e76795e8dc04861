#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]
//! `formcam correct` and `formcam correct simulate` as result files: the
//! corrected program, the report and its history, the plots, the loop.

mod common;

use std::path::{Path, PathBuf};

use common::{examples, job, json, plate, plate_program, scratch, text};
use formcam_correct::{Interpolation, Options, Settings, Tool};
use formcam_results::correction::{NODE_STATUS, PREDICTED};
use formcam_run::{History, correct, correct_job, correct_simulate};

#[test]
fn a_node_table_is_corrected_and_its_report_lies_beside_it() {
    let dir = scratch("table");
    let m = plate(&dir, &[0.0, 40.0, 80.0, 120.0], |_| 0.1);
    let t = dir.join("nodes.csv");
    std::fs::write(
        &t,
        "x,y,z\n10.000,10.000,0.000\n60.000,50.000,0.000\n200.000,50.000,0.000\n",
    )
    .unwrap();
    let out = Path::new("out/nodes-corrected.csv");
    let done = correct(&job(m, t, Settings::default()), out, None).unwrap();
    assert_eq!(done.report, None);
    let names: Vec<&str> = done.run.files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "nodes-corrected.csv",
            "nodes-corrected.deviations.svg",
            "nodes-corrected.displacement.svg",
            "nodes-corrected.report.json"
        ]
    );
    assert_eq!(
        text(&done.run, "nodes-corrected.csv"),
        "x,y,z\n10.000,10.000,-0.100\n60.000,50.000,-0.100\n200.000,50.000,0.000\n"
    );
    let r = json(&done.run.file("nodes-corrected.report.json").unwrap().bytes);
    assert_eq!(r["nodes_outside"], 1);
    assert_eq!(r["outside_lines"], "3");
    assert_eq!(r["program_syntax"], "csv");
    assert_eq!(r["output"], "out/nodes-corrected.csv");
    assert_eq!(r["history"][0]["iteration"], 1);
    assert!(
        done.run
            .line
            .starts_with("out/nodes-corrected.csv: 3 nodes, 2 corrected, 1 outside")
    );
}

#[test]
fn the_report_history_is_extended_and_a_foreign_report_refused() {
    let dir = scratch("history");
    let m = plate(&dir, &[0.0, 40.0, 80.0, 120.0], |_| 0.1);
    let p = dir.join("line.nc");
    std::fs::write(&p, "G90 G0 X0 Y50 Z5\nG1 Z0 F600\nX100\n").unwrap();
    let j = job(m, p, Settings::default());
    let report = dir.join("report.json");
    let fresh = History {
        path: report.clone(),
        previous: None,
    };
    let first = correct(&j, &dir.join("a.nc"), Some(&fresh)).unwrap();
    let bytes = first.report.unwrap();
    assert!(first.run.file("a.report.json").is_none());
    let again = History {
        path: report.clone(),
        previous: Some(String::from_utf8(bytes).unwrap()),
    };
    let second = correct(&j, &dir.join("b.nc"), Some(&again)).unwrap();
    let r = json(&second.report.unwrap());
    let h = r["history"].as_array().unwrap();
    assert_eq!(h.len(), 2);
    assert_eq!(h[1]["iteration"], 2);
    assert!(h[0]["output"].as_str().unwrap().ends_with("a.nc"));
    for (previous, want) in [
        ("not json", "is not a JSON report"),
        ("{\"nodes\": 3}", "no `history`"),
    ] {
        let h = History {
            path: report.clone(),
            previous: Some(previous.into()),
        };
        let e = correct(&j, &dir.join("c.nc"), Some(&h)).unwrap_err();
        assert!(e.to_string().contains(want), "{e}");
        assert!(e.to_string().contains("give another --report"), "{e}");
    }
}

#[test]
fn long_moves_are_split_on_request_so_the_correction_bends_them() {
    let dir = scratch("split");
    // The part is high in the middle along x: 0.0001 x (120 - x).
    let m = plate(&dir, &[0.0, 30.0, 60.0, 90.0, 120.0], |x| {
        0.0001 * x * (120.0 - x)
    });
    let p = dir.join("line.nc");
    let prog = "G90 G0 X0.000 Y50.000 Z5.000\nG1 Z0.000 F600\nX120.000\nG0 Z5.000\n";
    std::fs::write(&p, prog).unwrap();
    // Whole: both ends of the long move are where the part is right.
    let whole = correct(
        &job(m.clone(), p.clone(), Settings::default()),
        Path::new("w.nc"),
        None,
    );
    assert_eq!(text(&whole.unwrap().run, "w.nc"), prog);
    let split = Settings {
        max_segment_mm: Some(10.0),
        ..Settings::default()
    };
    let done = correct(&job(m, p, split), Path::new("s.nc"), None).unwrap();
    let t = text(&done.run, "s.nc");
    assert!(t.starts_with("(formcam correct: 1 G1 moves split"), "{t}");
    assert!(t.contains("\nG1 X60.000 Z-0.360\n"), "{t}");
    assert_eq!(t.lines().filter(|l| l.starts_with("G1 X")).count(), 11);
    assert_eq!(
        json(&done.run.file("s.report.json").unwrap().bytes)["moves_split"],
        1
    );
}

#[test]
fn flags_and_job_files_name_the_setting_their_own_way() {
    let dir = scratch("names");
    let m = plate(&dir, &[0.0, 40.0, 80.0, 120.0], |_| 3.0);
    let p = dir.join("line.nc");
    std::fs::write(&p, "G90 G0 X0 Y50 Z5\nG1 Z0 F600\nX100\n").unwrap();
    let mut s = Settings::default();
    s.options.gain = 0.0;
    let e = correct(&job(m.clone(), p.clone(), s), Path::new("x.nc"), None).unwrap_err();
    assert_eq!(e.to_string(), "--gain 0: allowed (0, 2]");
    s.options.gain = 2.0;
    let e = correct(&job(m.clone(), p.clone(), s), Path::new("x.nc"), None).unwrap_err();
    assert!(
        e.to_string()
            .ends_with("line.nc: line 2: the node would move by 6.000 mm, beyond --max-deviation 5 mm (nothing written)"),
        "{e}"
    );
    let job_file = dir.join("job.toml");
    let job_text = "[correct]\nmeasurements = \"cmm.csv\"\nprogram = \"line.nc\"\ngain = 2.0\n";
    let e = correct_job(&job_file, job_text, &dir.join("out")).unwrap_err();
    assert!(
        e.to_string().contains(
            "line 2: the node would move by 6.000 mm, beyond correct.max_deviation_mm = 5 mm"
        ),
        "{e}"
    );
    let e = correct_job(&job_file, &job_text.replace("2.0", "0.0"), &dir.join("out")).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{}: correct.gain = 0: allowed (0, 2]", job_file.display())
    );
}

#[test]
fn the_bundled_job_gives_its_program_plots_and_a_fresh_report() {
    let path = examples().join("correct-mould.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let run = correct_job(&path, &text, Path::new("out")).unwrap();
    let names: Vec<&str> = run.files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "corrected.nc",
            "corrected.deviations.svg",
            "corrected.displacement.svg",
            "node-status.csv",
            "predicted-cmm.csv",
            "report.json",
            "job.toml"
        ]
    );
    // The job as it ran; the files it read by their absolute paths (the
    // job names them relative to its folder, here through `..`).
    assert_eq!(common::text(&run, "job.toml"), text);
    // formcam-correct writes these two: their headers are the descriptions'.
    let header = |name: &str| {
        let bytes = &run.file(name).unwrap().bytes;
        let text = String::from_utf8_lossy(bytes);
        text.lines().next().map(|l| format!("{l}\n")).unwrap()
    };
    assert_eq!(header(NODE_STATUS.file), NODE_STATUS.header());
    let predicted = header(PREDICTED.file);
    assert!(
        [false, true]
            .iter()
            .any(|&n| predicted == PREDICTED.header_with(&[], n)),
        "{predicted}"
    );
    let r = json(&run.file("report.json").unwrap().bytes);
    // A row per feed node, its placement counted as the report counts it.
    let status = common::text(&run, "node-status.csv");
    let rows: Vec<Vec<&str>> = status
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len() as u64, r["nodes_feed"].as_u64().unwrap());
    let count = |w: &str| rows.iter().filter(|c| c[4] == w).count() as u64;
    assert_eq!(
        count("extrapolated"),
        r["nodes_extrapolated"].as_u64().unwrap()
    );
    assert_eq!(count("outside"), r["nodes_outside"].as_u64().unwrap());
    let moved = rows
        .iter()
        .filter(|c| c[5..8].iter().any(|d| d.parse::<f64>().unwrap() != 0.0))
        .count() as u64;
    assert_eq!(moved, r["nodes_corrected"].as_u64().unwrap());
    // The next part predicted: the same points, far nearer their nominal.
    let before = formcam_correct::Measurements::from_csv(
        &std::fs::read_to_string(examples().join("correct/cmm.csv")).unwrap(),
    )
    .unwrap();
    let after =
        formcam_correct::Measurements::from_csv(&common::text(&run, "predicted-cmm.csv")).unwrap();
    assert_eq!(after.len(), before.len());
    let predicted = r["predicted_max_deviation_mm"].as_f64().unwrap();
    assert!((after.max_deviation() - predicted).abs() < 1e-12);
    assert!(predicted < 0.25 * before.max_deviation(), "{predicted}");
    assert_eq!(r["interpolation"], "bicubic");
    assert_eq!(r["tool"]["radius_mm"], 6.0);
    assert_eq!(r["arcs_linearised"], 30);
    // The U-turns beyond the panel's ends lie within its 5 mm margin.
    assert_eq!(r["nodes_outside"], 0);
    assert!(r["nodes_extrapolated"].as_u64().unwrap() > 1000);
    assert_eq!(r["nodes_rapid_unchanged"], 2);
    assert!(r["smoothing"]["noise_mm"].as_f64().unwrap() > 0.0);
    assert_eq!(r["history"].as_array().unwrap().len(), 1);
    for (key, file) in [("measurements", "cmm.csv"), ("program", "mould.nc")] {
        let named = examples()
            .join("correct")
            .join(file)
            .canonicalize()
            .unwrap();
        assert_eq!(
            r[key].as_str().map(PathBuf::from),
            Some(named.clone()),
            "{key}"
        );
        assert_eq!(r["history"][0][key], r[key], "{key}");
    }
}

/// The texts of an SVG document with their `text-anchor`.
fn texts(svg: &str) -> Vec<(String, String)> {
    svg.split("<text")
        .skip(1)
        .filter_map(|e| {
            let (head, rest) = e.split_once('>')?;
            let body = rest.split("</text>").next()?.trim().to_string();
            let anchor = head
                .split("text-anchor=\"")
                .nth(1)
                .and_then(|a| a.split('"').next())
                .unwrap_or("start")
                .to_string();
            Some((anchor, body))
        })
        .collect()
}

#[test]
fn the_closed_loop_converges() {
    let scenario = "[surface]\nkind = \"nose-cone\"\nlength = 240.0\nwidth = 120.0\nradius_start = 150.0\nradius_end = 260.0\n\
         [program]\ntool = \"ball:5\"\nstep = 2.0\nstep_over = 2.0\nfeed = 2000.0\n\
         [warp]\namplitude = 0.4\n\
         [cmm]\nsections = 13\npoints = 9\nnoise = 0.0\n\
         [loop]\niterations = 2\ninterpolation = \"bicubic\"\nmargin_mm = 2.0\nsection_study = [5, 13]\n";
    let run = correct_simulate(Path::new("loop.toml"), scenario, Path::new("out")).unwrap();
    let r = json(&run.file("report.json").unwrap().bytes);
    let before = r["max_deviation_before_mm"].as_f64().unwrap();
    let after = r["max_deviation_after_mm"].as_f64().unwrap();
    assert!(before > 0.25, "{before}");
    assert!(after < 0.02, "{after}");
    assert_eq!(r["rounds"].as_array().unwrap().len(), 3);
    // Finer sections leave less; bicubic less than bilinear.
    let study = r["section_study"].as_array().unwrap();
    let at = |n: u64, kind: &str| {
        study
            .iter()
            .find(|x| x["sections"] == n && x["interpolation"] == kind)
            .unwrap()["true_max_mm"]
            .as_f64()
            .unwrap()
    };
    assert!(at(13, "bilinear") < at(5, "bilinear"));
    assert!(at(5, "bicubic") < at(5, "bilinear"));
    for f in [
        "program-0.nc",
        "program-2.nc",
        "cmm-0.csv",
        "convergence.svg",
        "deviations-before.svg",
        "deviations-after.svg",
    ] {
        assert!(run.file(f).is_some(), "{f}");
    }
    // Rounds are whole numbers: the x axis is labelled 0, 1, 2 only.
    let svg = text(&run, "convergence.svg");
    let mut rounds_axis: Vec<String> = texts(&svg)
        .into_iter()
        .filter(|(anchor, t)| anchor == "middle" && t.parse::<f64>().is_ok())
        .map(|(_, t)| t)
        .collect();
    rounds_axis.dedup();
    assert_eq!(rounds_axis, ["0", "1", "2"]);
    assert!(run.line.starts_with("out: 2 rounds"), "{}", run.line);
    // A bad scenario names the file and the field.
    let e = correct_simulate(
        Path::new("loop.toml"),
        &scenario.replace("step = 2.0", "step = 0.0"),
        Path::new("out"),
    )
    .unwrap_err();
    assert!(
        e.to_string().starts_with("loop.toml: program.step = 0"),
        "{e}"
    );
}

#[test]
fn a_constant_error_is_removed_and_other_lines_are_kept() {
    let dir = scratch("constant");
    let m = plate(&dir, &[0.0, 40.0, 80.0, 120.0], |_| 0.1);
    let p = plate_program(&dir);
    let done = correct(
        &job(m.clone(), p, Settings::default()),
        &dir.join("out/corrected.nc"),
        None,
    )
    .unwrap();
    let corrected = text(&done.run, "corrected.nc");
    let lines: Vec<&str> = corrected.lines().collect();
    // The header says the arc was linearised (after % and the O line).
    assert!(
        lines[2].starts_with("(formcam correct: 1 arc blocks"),
        "{corrected}"
    );
    // Every line that is not a motion block is kept byte for byte.
    for keep in [
        "%",
        "O100 (PLATE)",
        "N10 G21 G90 G17",
        "N20 T1 M6 (TOOL)",
        "N30 G0 X10. Y10. Z20.",
        "N80 G0 Z20.",
        "M30",
    ] {
        assert!(lines.contains(&keep), "{keep} missing:\n{corrected}");
    }
    // Feed moves go 0.1 mm down, in the program's number format.
    assert!(
        lines.contains(&"N40 G1 Z-.1 F800.") || lines.contains(&"N40 G1 Z-0.1 F800."),
        "{corrected}"
    );
    assert!(lines.contains(&"N50 X100."), "{corrected}");
    assert!(
        lines.iter().any(|l| l.starts_with("N60 G1 X")),
        "{corrected}"
    );
    assert!(lines.contains(&"N70 G1 X10. ; back"), "{corrected}");
    let r = json(&done.run.file("corrected.report.json").unwrap().bytes);
    for key in [
        "nodes",
        "nodes_corrected",
        "nodes_outside",
        "max_deviation_mm",
        "rms_deviation_mm",
        "max_displacement_mm",
    ] {
        assert!(r.get(key).is_some(), "report lacks {key}");
    }
    assert_eq!(r["nodes_outside"], 0);
    assert!((r["max_deviation_mm"].as_f64().unwrap() - 0.1).abs() < 1e-12);
    assert!((r["max_displacement_mm"].as_f64().unwrap() - 0.1).abs() < 1e-12);
    assert_eq!(r["arcs_linearised"], 1);
    assert!(done.run.file("corrected.deviations.svg").is_some());
    assert!(done.run.file("corrected.displacement.svg").is_some());
    // Every node of the corrected program is at z = -0.1 except rapids.
    for l in &lines {
        if l.contains('Z') && !l.contains("G0") {
            assert!(l.contains("Z-.1") || l.contains("Z-0.1"), "{l}");
        }
    }
    // Iterating: the corrected program corrected again from the next part,
    // with bicubic patches, goes down by as much again.
    let first = dir.join("corrected.nc");
    std::fs::write(&first, &corrected).unwrap();
    let bicubic = Settings {
        options: Options {
            interpolation: Interpolation::Bicubic,
            ..Options::default()
        },
        ..Settings::default()
    };
    let again = correct(&job(m, first, bicubic), Path::new("corrected-2.nc"), None).unwrap();
    let second = text(&again.run, "corrected-2.nc");
    assert!(
        second.contains("N50 X100. Z-.2") || second.contains("Z-0.2"),
        "{second}"
    );
}

#[test]
fn the_bundled_correction_example_leaves_the_u_turns_alone() {
    let ball = Settings {
        options: Options {
            tool: Tool::Ball { radius: 6.0 },
            ..Options::default()
        },
        ..Settings::default()
    };
    let j = job(
        examples().join("correct/cmm.csv"),
        examples().join("correct/mould.nc"),
        ball,
    );
    let done = correct(&j, Path::new("corrected.nc"), None).unwrap();
    let r = json(&done.run.file("corrected.report.json").unwrap().bytes);
    // The U-turns beyond the panel's ends are outside and left alone.
    assert_eq!(r["arcs_linearised"], 30);
    assert!(r["nodes_outside"].as_u64().unwrap() > 1000);
}

#[test]
fn the_bundled_jobs_plots_say_what_they_show() {
    let path = examples().join("correct-mould.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let run = correct_job(&path, &text, Path::new("out")).unwrap();
    let svg = |name: &str| String::from_utf8(run.file(name).unwrap().bytes.clone()).unwrap();
    // The deviation plot's legend names sections; the displacement map has
    // a colour bar and a legend for its markers.
    let has = |svg: &str, want: &str| texts(svg).iter().any(|(_, t)| t == want);
    let dev = svg("corrected.deviations.svg");
    assert!(has(&dev, "section X0.0"), "{dev}");
    let map = svg("corrected.displacement.svg");
    for want in ["displacement, mm", "measured point"] {
        assert!(has(&map, want), "{want} missing");
    }
    // The colour bar's labels are distinct numbers.
    let bar: Vec<String> = texts(&map)
        .into_iter()
        .filter(|(a, t)| a == "end" && t.parse::<f64>().is_ok())
        .map(|(_, t)| t)
        .collect();
    let mut unique = bar.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), bar.len(), "{bar:?}");
}
