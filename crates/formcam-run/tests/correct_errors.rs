//! Corrections the library refuses, each with one line naming the file, the
//! place and the limit: bad reports and programs, a typing error in the
//! report, a displacement beyond the limit.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

mod common;

use std::path::Path;

use common::{examples, job, json, plate, plate_program, scratch};
use formcam_correct::{CorrectionJob, Options, Settings, Tool};
use formcam_run::correct;

/// The error of a correction that must fail, checked to be one line.
fn refused(job: &CorrectionJob, output: &Path) -> String {
    let e = match correct(job, output, None) {
        Ok(_) => panic!("{}: accepted", output.display()),
        Err(e) => e.to_string(),
    };
    assert_eq!(e.lines().count(), 1, "{e}");
    e
}

#[test]
fn bad_input_is_refused_with_one_line_naming_the_problem() {
    let dir = scratch("bad");
    let m = plate(&dir, &[0.0, 40.0, 80.0, 120.0], |_| 0.1);
    let p = plate_program(&dir);
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
    let cases = [
        (one, p.clone(), "section `B` has 1 point"),
        (rev, p.clone(), "runs the other way"),
        (dup, p.clone(), "given twice"),
        (nan, p, "is not finite"),
        (m.clone(), bad_prog, "line 2: `G1 X1.2.3`"),
        (m, empty, "empty"),
    ];
    for (k, (meas, prog, want)) in cases.into_iter().enumerate() {
        let e = refused(&job(meas, prog, Settings::default()), Path::new("x.nc"));
        assert!(e.contains(want), "case {k}: {e}");
    }
}

#[test]
fn a_typing_error_in_the_report_stops_the_run() {
    // 7.4206 typed as 74.206 in the first point of section X0.0.
    let dir = scratch("typo");
    let cmm = std::fs::read_to_string(examples().join("correct/cmm.csv")).unwrap();
    let line = cmm.lines().nth(1).unwrap();
    assert!(line.contains(",7.4206,"), "{line}");
    let m = dir.join("cmm.csv");
    std::fs::write(&m, cmm.replacen(",7.4206,", ",74.206,", 1)).unwrap();
    let with_limit = |max_deviation_mm: f64| {
        let settings = Settings {
            options: Options {
                tool: Tool::Ball { radius: 6.0 },
                ..Options::default()
            },
            max_deviation_mm,
            ..Settings::default()
        };
        job(m.clone(), examples().join("correct/mould.nc"), settings)
    };
    let out = Path::new("corrected.nc");
    let e = refused(&with_limit(5.0), out);
    assert!(
        e.contains("section `X0.0`, point `1`: deviation 66.")
            && e.contains("--max-deviation 5 mm"),
        "{e}"
    );
    // The limit is the user's: 100 mm lets it through (and nodes move by
    // tens of millimetres), 50 mm does not.
    let done = correct(&with_limit(100.0), out, None).unwrap();
    let r = json(&done.run.file("corrected.report.json").unwrap().bytes);
    assert!(r["max_displacement_mm"].as_f64().unwrap() > 10.0, "{r}");
    let e = refused(&with_limit(50.0), out);
    assert!(e.contains("cmm.csv: section `X0.0`, point `1`"), "{e}");
}

#[test]
fn a_displacement_beyond_the_limit_names_the_program_line() {
    // Every point 3 mm high (within 5 mm), corrected with gain 2: the nodes
    // would move by 6 mm.
    let dir = scratch("limit");
    let m = plate(&dir, &[0.0, 40.0, 80.0, 120.0], |_| 3.0);
    let p = plate_program(&dir);
    let mut settings = Settings::default();
    settings.options.gain = 2.0;
    let e = refused(&job(m.clone(), p.clone(), settings), Path::new("c.nc"));
    assert!(
        e.contains("plate.nc: line 6: the node would move by 6.000 mm"),
        "{e}"
    );
    settings.max_deviation_mm = 7.0;
    assert!(correct(&job(m, p, settings), Path::new("c.nc"), None).is_ok());
}

#[test]
fn a_range_is_refused_in_the_same_words_from_a_job_file_and_an_option() {
    let dir = scratch("same-words");
    let m = plate(&dir, &[0.0, 40.0, 80.0, 120.0], |_| 0.1);
    let p = plate_program(&dir);
    let job_file = dir.join("job.toml");
    type Set = fn(&mut Settings);
    let cases: [(&str, &str, Set); 7] = [
        ("gain = 0.0", "--gain 0", |s| s.options.gain = 0.0),
        ("gain = 2.5", "--gain 2.5", |s| s.options.gain = 2.5),
        ("margin_mm = -1.0", "--margin -1", |s| {
            s.options.margin_mm = -1.0
        }),
        ("noise_mm = -0.5", "--noise -0.5", |s| s.noise_mm = -0.5),
        ("arc_tolerance_mm = 0.0", "--arc-tolerance 0", |s| {
            s.arc_tolerance_mm = 0.0
        }),
        ("points_per_section = 1", "--points-per-section 1", |s| {
            s.points_per_section = Some(1)
        }),
        ("max_deviation_mm = 0.0", "--max-deviation 0", |s| {
            s.max_deviation_mm = 0.0
        }),
    ];
    for (line, flag, set) in cases {
        let mut settings = Settings::default();
        set(&mut settings);
        let by_flag = refused(&job(m.clone(), p.clone(), settings), Path::new("x.nc"));
        let text = format!(
            "[correct]\nmeasurements = \"{}\"\nprogram = \"{}\"\n{line}\n",
            m.display(),
            p.display()
        );
        let by_job = match formcam_run::correct_job(&job_file, &text, &dir.join("out")) {
            Ok(_) => panic!("{line}: accepted"),
            Err(e) => e.to_string(),
        };
        // The job names its file and field, never the option; the option
        // names itself; the rule after the value is one text.
        let key = line.split(" = ").next().unwrap();
        let field = format!("{}: correct.{key} = ", job_file.display());
        assert!(by_job.starts_with(&field), "{line}: {by_job}");
        assert!(!by_job.contains("--"), "{line}: {by_job}");
        assert!(
            by_flag.starts_with(&format!("{flag}: ")),
            "{line}: {by_flag}"
        );
        let rule_of = |e: &str| e.split_once(": ").map(|(_, r)| r.to_string());
        let job_rule = by_job[field.len()..].split_once(": ").map(|(_, r)| r);
        assert_eq!(job_rule, rule_of(&by_flag).as_deref(), "{line}");
        assert!(
            job_rule.is_some_and(|r| r.starts_with("allowed ") || r.starts_with("must be ")),
            "{line}: {by_job}"
        );
    }
}
