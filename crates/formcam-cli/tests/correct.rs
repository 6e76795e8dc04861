//! `formcam correct` as users meet it: the files it writes, the report it
//! extends, the inputs it never overwrites, its options and one-line errors;
//! `formcam correct simulate`. What the corrections compute is tested in
//! formcam-run.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::{examples, json, ok, one_line_error, run, s, scratch, stderr};

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

/// `formcam correct --measurements M --program P -o OUT EXTRA...`.
fn correct(m: &Path, p: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "correct",
        "--measurements",
        s(m),
        "--program",
        s(p),
        "-o",
        s(out),
    ];
    args.extend_from_slice(extra);
    run(&args)
}

#[test]
fn a_correction_writes_its_files_and_extends_its_report() {
    let dir = scratch("plate");
    let (m, p) = plate(&dir);
    let before = std::fs::read_to_string(&p).unwrap();
    let out = dir.join("out/corrected.nc");
    let report = dir.join("out/report.json");
    let args =
        |program: &Path, output: &Path| correct(&m, program, output, &["--report", s(&report)]);
    ok("plate", &args(&p, &out));
    // The input is untouched; the program, its plots and the report written.
    assert_eq!(std::fs::read_to_string(&p).unwrap(), before);
    assert!(std::fs::read_to_string(&out).unwrap().contains("N50 X100."));
    assert!(dir.join("out/corrected.deviations.svg").exists());
    assert!(dir.join("out/corrected.displacement.svg").exists());
    assert_eq!(json(&report)["history"].as_array().unwrap().len(), 1);
    // Iterating: the corrected program corrected again from the next part;
    // the report file keeps its history.
    let out2 = dir.join("out/corrected-2.nc");
    ok("again", &args(&out, &out2));
    let r = json(&report);
    let h = r["history"].as_array().unwrap();
    assert_eq!(h.len(), 2);
    assert_eq!(h[1]["iteration"], 2);
    assert!(out2.exists());
}

#[test]
fn bad_input_gives_one_line_and_no_program() {
    let dir = scratch("bad");
    let (m, p) = plate(&dir);
    let bad_prog = dir.join("bad.nc");
    std::fs::write(&bad_prog, "G0 X0 Y0 Z0\nG1 X1.2.3\n").unwrap();
    let out = dir.join("out-bad/corrected.nc");
    let o = correct(&m, &bad_prog, &out, &[]);
    let err = one_line_error("bad program", &o, &out);
    assert!(
        err.contains("bad.nc") && err.contains("line 2: `G1 X1.2.3`"),
        "{err}"
    );
    // The input program is never overwritten.
    let o = correct(&m, &p, &p, &[]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("overwrite the input"));
    let cmm_before = std::fs::read_to_string(&m).unwrap();
    let o = correct(&m, &p, &m, &[]);
    assert!(stderr(&o).contains("overwrite the input measurements"));
    let x = dir.join("x.nc");
    let o = correct(&m, &p, &x, &["--report", s(&x)]);
    assert!(stderr(&o).contains("the same file"));
    assert!(!x.exists());
    assert_eq!(std::fs::read_to_string(&m).unwrap(), cmm_before);
    // Options out of range name the option.
    for (flag, value, want) in [
        ("--gain", "0", "--gain 0: allowed (0, 2]"),
        ("--tool", "ball:-2", "ball radius"),
        ("--interpolation", "spline", "allowed bilinear, bicubic"),
    ] {
        let o = correct(&m, &p, &dir.join("x.nc"), &[flag, value]);
        assert!(stderr(&o).contains(want), "{flag} {value}: {}", stderr(&o));
    }
}

#[test]
fn a_program_the_correction_does_not_understand_writes_nothing() {
    let dir = scratch("refused");
    let (m, _) = plate(&dir);
    let prog = dir.join("polar.mpf");
    std::fs::write(
        &prog,
        "G90 G0 X10 Y10 Z20\nG1 Z0 F800\nG1 AP=45 RP=10\nM30\n",
    )
    .unwrap();
    let out = dir.join("out-refused/corrected.mpf");
    let report = dir.join("out-refused/report.json");
    let o = correct(&m, &prog, &out, &["--report", s(&report)]);
    let err = one_line_error("polar", &o, &out);
    assert!(
        err.contains("polar.mpf: line 3: `G1 AP=45 RP=10`: polar coordinates (`AP`)"),
        "{err}"
    );
    assert!(
        !dir.join("out-refused").exists(),
        "a refused run wrote files"
    );
    // `--dialect` names the option and the words allowed, as the job
    // file's field does.
    for bad in ["foo", "cldata"] {
        let x = dir.join("x.mpf");
        let o = correct(&m, &prog, &x, &["--dialect", bad]);
        let err = one_line_error(bad, &o, &x);
        assert!(
            err.contains(&format!(
                "--dialect \"{bad}\": allowed iso, fanuc, sinumerik-840d, sinumerik, 840d, \
                 linuxcnc, marlin-xab"
            )),
            "{err}"
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
    ok("loop", &o);
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
fn a_job_file_runs_and_needs_its_table_and_an_output() {
    let dir = scratch("job");
    let out = dir.join("out");
    let job = examples().join("correct-mould.toml");
    ok("job", &run(&["correct", s(&job), "-o", s(&out)]));
    for f in [
        "corrected.nc",
        "corrected.deviations.svg",
        "corrected.displacement.svg",
        "report.json",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    // A job without [correct], and a job without -o, are one-line errors.
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[mandrel]\nkind = \"cylinder\"\n").unwrap();
    let o = run(&["correct", s(&bad), "-o", s(&out)]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("no [correct] table"),
        "{e}"
    );
    let o = run(&["correct", s(&job)]);
    let e = stderr(&o);
    assert!(!o.status.success() && e.contains("give -o"), "{e}");
}

#[test]
fn a_typing_error_in_the_report_stops_the_run_unless_the_limit_allows() {
    // 7.4206 typed as 74.206 in the first point of section X0.0.
    let dir = scratch("typo");
    let cmm = std::fs::read_to_string(examples().join("correct/cmm.csv")).unwrap();
    let m = dir.join("cmm.csv");
    std::fs::write(&m, cmm.replacen(",7.4206,", ",74.206,", 1)).unwrap();
    let out = dir.join("corrected.nc");
    let mould = examples().join("correct/mould.nc");
    let args = |extra: &[&str]| {
        let mut v = vec!["--tool", "ball:6"];
        v.extend_from_slice(extra);
        correct(&m, &mould, &out, &v)
    };
    let e = one_line_error("typo", &args(&[]), &out);
    assert!(
        e.contains("cmm.csv: section `X0.0`, point `1`: deviation 66."),
        "{e}"
    );
    // The limit is the user's.
    ok("limit 100", &args(&["--max-deviation", "100"]));
    assert!(out.exists() && dir.join("corrected.report.json").exists());
}
