//! `formcam_run::dress` on the bundled example: its files checked against
//! each other, the initial contour read from a file in either header, and
//! every column and `summary.json` key it writes documented in
//! `docs/dressing.md`.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

mod common;

use std::path::{Path, PathBuf};

use common::{examples, scratch, summary, text};
use formcam_run::{dress, dress_text};

const EXAMPLE: &str = include_str!("../../../examples/dress-ballscrew-nut.toml");
const DOCS: &str = include_str!("../../../docs/dressing.md");

fn example_path() -> PathBuf {
    examples().join("dress-ballscrew-nut.toml")
}

/// A CSV's header and rows.
fn csv(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

fn col(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

#[test]
fn the_example_writes_consistent_outputs() {
    let run = dress(&example_path()).unwrap();
    assert!(
        run.line.contains("900 points") && run.line.contains("feed control"),
        "{}",
        run.line
    );
    assert!(run.warnings.is_empty(), "{:?}", run.warnings);
    let s = summary(&run);
    let num = |k: &str| s[k].as_f64().unwrap_or_else(|| panic!("summary.{k}"));
    let (u, c) = (num("mrr_ratio_uncontrolled"), num("mrr_ratio_controlled"));
    assert!(u > c && c >= 1.0, "{u} {c}");
    assert!(num("area_identity_rel_error").abs() < 1e-9);
    assert!(num("final_deviation_max_mm") <= num("scallop_bound_mm"));
    assert!(num("final_deviation_min_mm") > -1e-9);
    let [a, b] = [0, 1].map(|i| s["contact_angles_deg"][i].as_f64().unwrap());
    assert!((a - 45.0).abs() < 1e-9 && (b - 135.0).abs() < 1e-9);
    assert_eq!(s["steps_off_target_feed_free"], 0);

    // The CLDATA program: one GOTO per point, a feed within the limits.
    let cls = text(&run, "program.cls");
    assert!(cls.starts_with("PARTNO/") && cls.trim_end().ends_with("FINI"));
    let gotos = cls.lines().filter(|l| l.starts_with("GOTO/")).count();
    assert_eq!(gotos as u64, s["points"].as_u64().unwrap());
    let feeds: Vec<f64> = cls
        .lines()
        .filter_map(|l| l.strip_prefix("FEDRAT/"))
        .map(|l| l.trim_end_matches(",MMPM").parse().unwrap())
        .collect();
    assert!(feeds.len() > 10);
    assert!(
        feeds.iter().all(|f| (50.0..=300.0).contains(f)),
        "{feeds:?}"
    );

    // The 840D program: plane G18, G1 blocks with F, as many points.
    let mpf = text(&run, "program.mpf");
    assert!(mpf.contains("G18 G90 G94 G71"));
    assert!(mpf.lines().any(|l| l.contains(" G1 ") && l.contains(" F")));
    let blocks = mpf
        .lines()
        .filter(|l| l.contains(" G0 ") || l.contains(" G1 ") || l.contains("G1 "))
        .count();
    assert!(blocks >= gotos - 2, "{blocks} {gotos}");

    // mrr.csv: rate = area per mm x feed; time = path over feed.
    let (h, rows) = csv(&text(&run, "mrr.csv"));
    let (ia, il, im, iff) = (
        col(&h, "area"),
        col(&h, "length"),
        col(&h, "mrr"),
        col(&h, "feed"),
    );
    let mut time = 0.0;
    for r in &rows {
        let v = |i: usize| r[i].parse::<f64>().unwrap();
        let (area, len, mrr, feed) = (v(ia), v(il), v(im), v(iff));
        assert!(
            (area / len * feed - mrr).abs() <= 1e-5 * mrr.max(1.0),
            "{r:?}"
        );
        time += len / feed * 60.0;
    }
    assert!((time / num("dressing_time_s") - 1.0).abs() < 1e-4);
    assert_eq!(rows.len() as u64, s["steps"].as_u64().unwrap());

    // The profile starts at the wheel's left edge, Z = -B/2.
    let (_, rows) = csv(&text(&run, "profile.csv"));
    let first: f64 = rows[0][0].parse().unwrap();
    assert!((first + 3.0).abs() < 1e-9);
    // Path points and the four rapid moves, less the steps merged because
    // they would print as zero-length moves.
    let (_, rows) = csv(&text(&run, "dresser.csv"));
    let merged = s["steps_merged_below_resolution"].as_u64().unwrap() as usize;
    assert_eq!(rows.len() + 4 - merged, gotos);
    for svg in ["profile.svg", "mrr.svg"] {
        assert!(text(&run, svg).contains("<svg"), "{svg}");
    }
}

#[test]
fn the_contour_after_each_pass_ends_with_the_final_contour() {
    let run = dress(&example_path()).unwrap();
    let s = summary(&run);
    let (h, rows) = csv(&text(&run, "contour_passes.csv"));
    assert_eq!(h, ["z", "x", "pass"]);
    let pass = col(&h, "pass");
    let passes: Vec<&str> = rows.iter().map(|r| r[pass].as_str()).collect();
    assert!(passes.windows(2).all(|w| w[0] <= w[1]), "passes in order");
    let last = s["passes"].as_array().unwrap().len().to_string();
    assert_eq!(passes.first(), Some(&"1"));
    assert_eq!(passes.last(), Some(&last.as_str()));
    // The last pass's rows are the final contour's, written alike.
    let (_, fin) = csv(&text(&run, "contour_final.csv"));
    let after: Vec<&[String]> = rows
        .iter()
        .filter(|r| r[pass] == last)
        .map(|r| &r[..2])
        .collect();
    let fin: Vec<&[String]> = fin.iter().map(|r| &r[..]).collect();
    assert_eq!(after, fin);
    // The first pass dresses the right half only: its contour is the
    // initial one left of the apex's neighbourhood.
    let (_, initial) = csv(&text(&run, "contour_initial.csv"));
    let first: Vec<&[String]> = rows
        .iter()
        .filter(|r| r[pass] == "1")
        .map(|r| &r[..2])
        .collect();
    let left = |c: &[&[String]]| -> Vec<String> {
        c.iter()
            .filter(|r| r[0].parse::<f64>().unwrap() < -1.0)
            .map(|r| r.join(","))
            .collect()
    };
    let initial: Vec<&[String]> = initial.iter().map(|r| &r[..]).collect();
    assert!(!left(&initial).is_empty());
    assert_eq!(left(&first), left(&initial));
}

#[test]
fn every_table_heads_the_wheel_axes_as_the_program_does() {
    let run = dress(&example_path()).unwrap();
    let cls = text(&run, "program.cls");
    assert!(cls.contains("GOTO/"));
    // The programs move Z (along the wheel's axis), then X (radial).
    let mpf = text(&run, "program.mpf");
    assert!(mpf.lines().any(|l| l.contains(" G1 Z")), "{mpf}");
    for f in run.files.iter().filter(|f| f.name.ends_with(".csv")) {
        let (h, rows) = csv(&String::from_utf8(f.bytes.clone()).unwrap());
        assert_eq!(&h[..2], ["z", "x"], "{}", f.name);
        assert!(!h.iter().any(|c| c == "y"), "{}: {h:?}", f.name);
        assert!(!rows.is_empty(), "{}", f.name);
    }
}

#[test]
fn an_initial_contour_reads_with_the_new_and_the_old_header() {
    let dir = scratch("contour");
    let job = dir.join("job.toml");
    std::fs::write(
        &job,
        EXAMPLE.replace("depth = 0.05", "initial_contour = \"worn.csv\""),
    )
    .unwrap();
    // A flat-topped wheel worn unevenly, above the whole profile.
    let rows: Vec<(f64, f64)> = (0..=600)
        .map(|i| {
            let z = -3.0 + 0.01 * f64::from(i);
            (z, 1.95 + 0.02 * (3.0 * z).cos())
        })
        .collect();
    let write = |header: &str, swap: bool| {
        let mut s = format!("{header}\n");
        for &(z, x) in &rows {
            let (a, b) = if swap { (x, z) } else { (z, x) };
            s.push_str(&format!("{a},{b}\n"));
        }
        std::fs::write(dir.join("worn.csv"), s).unwrap();
        dress(&job).unwrap()
    };
    let zx = write("z,x", false);
    // The run names the files it read: the job and the contour.
    assert_eq!(zx.inputs, vec![job.clone(), dir.join("worn.csv")]);
    let s = summary(&zx);
    assert!(s["area_identity_rel_error"].as_f64().unwrap().abs() < 1e-9);
    let initial = text(&zx, "contour_initial.csv");
    assert!(initial.starts_with("z,x\n-3.000000000,"), "{initial:.60}");
    for (header, swap) in [("x,z", true), ("x,y", false)] {
        let other = write(header, swap);
        for name in ["contour_initial.csv", "mrr.csv", "program.cls"] {
            assert_eq!(text(&other, name), text(&zx, name), "{header}: {name}");
        }
    }
    // A line that is not two numbers: the file, the line and the field.
    std::fs::write(dir.join("worn.csv"), "z,x\n-3,2\n0;2\n3,2\n").unwrap();
    let e = dress(&job).unwrap_err().to_string();
    assert!(
        e.ends_with(
            "worn.csv:3: process.initial_contour: expected numbers z,x (mm) in every column"
        ),
        "{e}"
    );
    // A contour below the profile: named by its own file.
    std::fs::write(dir.join("worn.csv"), "z,x\n-3,0\n3,0\n").unwrap();
    let e = dress(&job).unwrap_err().to_string();
    assert!(
        e.contains("worn.csv: process.initial_contour: it lies") && e.contains("at z = "),
        "{e}"
    );
}

#[test]
fn job_errors_name_the_file_line_and_field() {
    let job = Path::new("some/job.toml");
    let e = dress_text(job, &EXAMPLE.replace("r1 = 1.937", "r1 = 1.85"))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("some/job.toml: wheel.r1 = 1.85 mm"), "{e}");
    let e = dress_text(
        job,
        &EXAMPLE.replace("feed_max = 300.0", "feed_max = 300.0\nfeed_rate = 3"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("some/job.toml:") && e.contains("unknown field `feed_rate`"),
        "{e}"
    );
    let slow = dress_text(job, &EXAMPLE.replace("feed_min = 50.0", "feed_min = 0.5")).unwrap();
    assert_eq!(slow.warnings.len(), 1, "{:?}", slow.warnings);
    assert!(slow.warnings[0].starts_with("process.feed_min"));
}

/// Every key of a JSON value, nested ones too (those of arrays' objects).
fn keys(v: &serde_json::Value, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, v) in m {
                out.push(k.clone());
                keys(v, out);
            }
        }
        serde_json::Value::Array(a) => a.iter().for_each(|v| keys(v, out)),
        _ => {}
    }
}

#[test]
fn every_file_column_and_summary_key_is_documented() {
    // The example, and the same with the wheel's diameter (volume rates).
    let dir = scratch("docs");
    let job = dir.join("job.toml");
    std::fs::write(
        &job,
        EXAMPLE.replace(
            "flank_tilt_deg = 10.0",
            "flank_tilt_deg = 10.0\ndiameter = 40.0",
        ),
    )
    .unwrap();
    let runs = [dress(&example_path()).unwrap(), dress(&job).unwrap()];
    let documented = |name: &str| DOCS.contains(&format!("`{name}`"));
    let mut missing = Vec::new();
    for run in &runs {
        for f in &run.files {
            if !documented(&f.name) {
                missing.push(f.name.clone());
            }
            if f.name.ends_with(".csv") {
                let (h, _) = csv(&String::from_utf8(f.bytes.clone()).unwrap());
                missing.extend(h.into_iter().filter(|c| !documented(c)));
            }
        }
        let mut k = Vec::new();
        keys(&summary(run), &mut k);
        missing.extend(k.into_iter().filter(|c| !documented(c)));
    }
    missing.sort();
    missing.dedup();
    assert!(missing.is_empty(), "not in docs/dressing.md: {missing:?}");
    // The volume rates are there only with the diameter.
    assert!(runs[1].file("mrr.csv").is_some());
    assert!(
        text(&runs[1], "mrr.csv")
            .lines()
            .next()
            .unwrap()
            .ends_with("mrr_volume_uncontrolled")
    );
}
