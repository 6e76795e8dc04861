//! `formcam correct` as users meet it: the corrected program, the report and
//! its history, one-line errors; `formcam correct simulate`.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn formcam() -> Command {
    Command::new(env!("CARGO_BIN_EXE_formcam"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("formcam-correct-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn run(args: &[&str]) -> Output {
    formcam().args(args).output().unwrap()
}

fn json(path: impl AsRef<Path>) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The texts of an SVG document with their `text-anchor` (`middle` for the
/// x axis' tick labels, `end` for the y axis').
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

/// A flat plate z = 0 measured in 3 sections x 4 points, everything 0.1 mm
/// high along z; an ISO program with comments, modal words, an arc and a
/// rapid move.
fn plate(dir: &Path) -> (PathBuf, PathBuf) {
    let mut cmm = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n");
    for (j, y) in [0.0, 50.0, 100.0].iter().enumerate() {
        for (i, x) in [0.0, 40.0, 80.0, 120.0].iter().enumerate() {
            cmm.push_str(&format!("S{j},{i},{x},{y},0,{x},{y},0.1\n"));
        }
    }
    let m = dir.join("cmm.csv");
    std::fs::write(&m, cmm).unwrap();
    let prog = "%\nO100 (PLATE)\nN10 G21 G90 G17\nN20 T1 M6 (TOOL)\nN30 G0 X10. Y10. Z20.\n\
                N40 G1 Z0. F800.\nN50 X100.\nN60 G3 X100. Y30. I0. J10.\nN70 G1 X10. ; back\n\
                N80 G0 Z20.\nM30\n%\n";
    let p = dir.join("plate.nc");
    std::fs::write(&p, prog).unwrap();
    (m, p)
}

#[test]
fn a_constant_error_is_removed_and_other_lines_are_kept() {
    let dir = scratch("plate");
    let (m, p) = plate(&dir);
    let before = std::fs::read_to_string(&p).unwrap();
    let out = dir.join("out/corrected.nc");
    let report = dir.join("out/report.json");
    let o = run(&[
        "correct",
        "--measurements",
        s(&m),
        "--program",
        s(&p),
        "-o",
        s(&out),
        "--report",
        s(&report),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The input is untouched.
    assert_eq!(std::fs::read_to_string(&p).unwrap(), before);
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    // The header says the arc was linearised (after % and the O line).
    assert!(
        lines[2].starts_with("(formcam correct: 1 arc blocks"),
        "{text}"
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
        assert!(lines.contains(&keep), "{keep} missing:\n{text}");
    }
    // Feed moves go 0.1 mm down, in the program's number format.
    assert!(
        lines.contains(&"N40 G1 Z-.1 F800.") || lines.contains(&"N40 G1 Z-0.1 F800."),
        "{text}"
    );
    assert!(lines.contains(&"N50 X100."), "{text}");
    assert!(lines.iter().any(|l| l.starts_with("N60 G1 X")), "{text}");
    assert!(lines.contains(&"N70 G1 X10. ; back"), "{text}");
    // The arc's chords and Z.
    let r: serde_json::Value = json(&report);
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
    assert!(dir.join("out/corrected.deviations.svg").exists());
    assert!(dir.join("out/corrected.displacement.svg").exists());
    // Every node of the corrected program is at z = -0.1 except rapids.
    for l in &lines {
        if l.contains('Z') && !l.contains("G0") {
            assert!(l.contains("Z-.1") || l.contains("Z-0.1"), "{l}");
        }
    }

    // Iterating: the corrected program corrected again from the next part;
    // the report keeps its history.
    let out2 = dir.join("out/corrected-2.nc");
    let o = run(&[
        "correct",
        "--measurements",
        s(&m),
        "--program",
        s(&out),
        "-o",
        s(&out2),
        "--report",
        s(&report),
        "--interpolation",
        "bicubic",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = json(&report);
    let h = r["history"].as_array().unwrap();
    assert_eq!(h.len(), 2);
    assert_eq!(h[1]["iteration"], 2);
    assert!(
        std::fs::read_to_string(&out2)
            .unwrap()
            .contains("N50 X100. Z-.2")
            || std::fs::read_to_string(&out2).unwrap().contains("Z-0.2")
    );
}

#[test]
fn bad_input_gives_one_line_errors_and_no_program() {
    let dir = scratch("bad");
    let (m, p) = plate(&dir);
    let head = "section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n";
    let write = |name: &str, text: &str| {
        let f = dir.join(name);
        std::fs::write(&f, text).unwrap();
        f
    };
    let one = write(
        "one.csv",
        &format!("{head}A,1,0,0,0,0,0,0\nA,2,1,0,0,1,0,0\nB,1,0,1,0,0,1,0\n"),
    );
    let rev = write(
        "rev.csv",
        &format!("{head}A,1,0,0,0,0,0,0\nA,2,1,0,0,1,0,0\nB,1,1,1,0,1,1,0\nB,2,0,1,0,0,1,0\n"),
    );
    let dup = write(
        "dup.csv",
        &format!("{head}A,1,0,0,0,0,0,0\nA,1,1,0,0,1,0,0\n"),
    );
    let nan = write("nan.csv", &format!("{head}A,1,0,0,0,0,0,NaN\n"));
    let bad_prog = write("bad.nc", "G0 X0 Y0 Z0\nG1 X1.2.3\n");
    let empty = write("empty.nc", "");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![s(&one).into(), s(&p).into()],
            "section `B` has 1 point",
        ),
        (vec![s(&rev).into(), s(&p).into()], "runs the other way"),
        (vec![s(&dup).into(), s(&p).into()], "given twice"),
        (vec![s(&nan).into(), s(&p).into()], "is not finite"),
        (
            vec![s(&m).into(), s(&bad_prog).into()],
            "line 2: `G1 X1.2.3`",
        ),
        (vec![s(&m).into(), s(&empty).into()], "empty"),
    ];
    for (k, (files, want)) in cases.iter().enumerate() {
        let out = dir.join(format!("out-{k}/corrected.nc"));
        let o = run(&[
            "correct",
            "--measurements",
            &files[0],
            "--program",
            &files[1],
            "-o",
            s(&out),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "case {k} succeeded");
        assert!(err.contains(want), "case {k}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "case {k}: {err}");
        assert!(!out.exists(), "case {k} left a program");
    }
    // The input program is never overwritten.
    let o = run(&[
        "correct",
        "--measurements",
        s(&m),
        "--program",
        s(&p),
        "-o",
        s(&p),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("overwrite the input"));
    let cmm_before = std::fs::read_to_string(&m).unwrap();
    let o = run(&[
        "correct",
        "--measurements",
        s(&m),
        "--program",
        s(&p),
        "-o",
        s(&m),
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("overwrite the input measurements"));
    let x = dir.join("x.nc");
    let o = run(&[
        "correct",
        "--measurements",
        s(&m),
        "--program",
        s(&p),
        "-o",
        s(&x),
        "--report",
        s(&x),
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("the same file"));
    assert!(!x.exists());
    assert_eq!(std::fs::read_to_string(&m).unwrap(), cmm_before);
    // Options out of range name the option.
    for (flag, value, want) in [
        ("--gain", "0", "--gain 0: allowed (0, 2]"),
        ("--tool", "ball:-2", "ball radius"),
        ("--interpolation", "spline", "allowed bilinear, bicubic"),
    ] {
        let o = run(&[
            "correct",
            "--measurements",
            s(&m),
            "--program",
            s(&p),
            "-o",
            s(&dir.join("x.nc")),
            flag,
            value,
        ]);
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(want),
            "{flag} {value}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn the_closed_loop_writes_its_rounds_and_names_a_bad_field() {
    // The loop's figures are checked in formcam-run's tests; here the
    // command: its files and its one-line error.
    let dir = scratch("loop");
    let scenario = dir.join("loop.toml");
    std::fs::write(
        &scenario,
        "[surface]\nkind = \"panel\"\nlength = 60.0\nwidth = 40.0\nradius_x = 500.0\nradius_y = 400.0\n\
         [program]\ntool = \"ball:5\"\nstep = 2.0\nstep_over = 2.0\nfeed = 2000.0\n\
         [warp]\namplitude = 0.2\n\
         [cmm]\nsections = 5\npoints = 5\n\
         [loop]\niterations = 1\n",
    )
    .unwrap();
    let out = dir.join("out");
    let o = run(&["correct", "simulate", s(&scenario), "-o", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "program-0.nc",
        "program-1.nc",
        "cmm-0.csv",
        "cmm-1.csv",
        "convergence.svg",
        "deviations-before.svg",
        "deviations-after.svg",
        "report.json",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    assert_eq!(
        json(out.join("report.json"))["rounds"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    std::fs::write(
        &scenario,
        std::fs::read_to_string(&scenario)
            .unwrap()
            .replace("step = 2.0", "step = 0.0"),
    )
    .unwrap();
    let o = run(&[
        "correct",
        "simulate",
        s(&scenario),
        "-o",
        s(&dir.join("bad")),
    ]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(e.contains("loop.toml: program.step = 0"), "{e}");
    assert!(!dir.join("bad").exists());
}

#[test]
fn the_bundled_correction_example_runs() {
    let dir = scratch("example");
    let out = dir.join("corrected.nc");
    let o = run(&[
        "correct",
        "--measurements",
        s(&examples().join("correct/cmm.csv")),
        "--program",
        s(&examples().join("correct/mould.nc")),
        "-o",
        s(&out),
        "--tool",
        "ball:6",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = json(dir.join("corrected.report.json"));
    // The U-turns beyond the panel's ends are outside and left alone.
    assert_eq!(r["arcs_linearised"], 30);
    assert!(r["nodes_outside"].as_u64().unwrap() > 1000);
}

#[test]
fn a_job_file_runs_and_its_plots_say_what_they_show() {
    let dir = scratch("job");
    let out = dir.join("out");
    let o = run(&[
        "correct",
        s(&examples().join("correct-mould.toml")),
        "-o",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = json(out.join("report.json"));
    assert_eq!(r["interpolation"], "bicubic");
    assert_eq!(r["tool"]["radius_mm"], 6.0);
    assert!(r["smoothing"]["noise_mm"].as_f64().unwrap() > 0.0);
    assert!(out.join("corrected.nc").exists());
    // The deviation plot's legend names sections; the displacement map has
    // a colour bar and a legend for its markers.
    let has = |svg: &str, want: &str| texts(svg).iter().any(|(_, t)| t == want);
    let dev = std::fs::read_to_string(out.join("corrected.deviations.svg")).unwrap();
    assert!(has(&dev, "section X0.0"), "{dev}");
    let map = std::fs::read_to_string(out.join("corrected.displacement.svg")).unwrap();
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
    // A job without [correct], and a job without -o, are one-line errors.
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[mandrel]\nkind = \"cylinder\"\n").unwrap();
    let o = run(&["correct", s(&bad), "-o", s(&out)]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && e.contains("no [correct] table"),
        "{e}"
    );
    let o = run(&["correct", s(&examples().join("correct-mould.toml"))]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("give -o"), "{e}");
}

#[test]
fn a_typing_error_in_the_report_stops_the_run() {
    // 7.4206 typed as 74.206 in the first point of section X0.0.
    let dir = scratch("typo");
    let cmm = std::fs::read_to_string(examples().join("correct/cmm.csv")).unwrap();
    let line = cmm.lines().nth(1).unwrap();
    assert!(line.contains(",7.4206,"), "{line}");
    let typo = cmm.replacen(",7.4206,", ",74.206,", 1);
    let m = dir.join("cmm.csv");
    std::fs::write(&m, typo).unwrap();
    let out = dir.join("corrected.nc");
    let args = |extra: &[&'static str]| {
        let mut v = vec![
            "correct".to_string(),
            "--measurements".into(),
            s(&m).into(),
            "--program".into(),
            s(&examples().join("correct/mould.nc")).into(),
            "-o".into(),
            s(&out).into(),
            "--tool".into(),
            "ball:6".into(),
        ];
        v.extend(extra.iter().map(|x| x.to_string()));
        v
    };
    let o = formcam().args(args(&[])).output().unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("section `X0.0`, point `1`: deviation 66.")
            && e.contains("--max-deviation 5 mm"),
        "{e}"
    );
    assert!(!out.exists());
    // The limit is the user's: 100 mm lets it through (and nodes move by
    // tens of millimetres), 50 mm does not.
    let o = formcam()
        .args(args(&["--max-deviation", "100"]))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = json(dir.join("corrected.report.json"));
    assert!(r["max_displacement_mm"].as_f64().unwrap() > 10.0, "{r}");
    let o = formcam()
        .args(args(&["--max-deviation", "50"]))
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("cmm.csv: section `X0.0`, point `1`"), "{e}");
}

#[test]
fn a_displacement_beyond_the_limit_names_the_program_line() {
    // Every point 3 mm high (within 5 mm), corrected with gain 2: the nodes
    // would move by 6 mm.
    let dir = scratch("limit");
    let (m, p) = plate(&dir);
    let cmm = std::fs::read_to_string(&m)
        .unwrap()
        .replace(",0.1\n", ",3\n");
    std::fs::write(&m, cmm).unwrap();
    let out = dir.join("corrected.nc");
    let base = [
        "correct",
        "--measurements",
        s(&m),
        "--program",
        s(&p),
        "-o",
        s(&out),
        "--gain",
        "2",
    ];
    let o = run(&base);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("plate.nc: line 6: the node would move by 6.000 mm"),
        "{e}"
    );
    assert!(!out.exists());
    let mut more = base.to_vec();
    more.extend(["--max-deviation", "7"]);
    let o = run(&more);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
