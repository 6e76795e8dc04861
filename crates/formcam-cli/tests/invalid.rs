//! The invalid-input corpus: every file under `tests/invalid/<format>/` is a
//! mistake a user or another tool makes in one of formcam's input formats.
//! Each is run through `formcam` by its format's rule; the run must fail
//! with exit status 2 and one short line on stderr, free of control
//! characters, naming the file, and nothing written. The line (paths made
//! relative to the corpus) is kept as an insta snapshot,
//! `snapshots/invalid__<format>__<case>.snap`. A new file is picked up
//! without editing this test; `tests/invalid/README.md` says how to add one.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};

use common::{formcam, repo, scratch, stderr};

/// The longest line an error may print for a corpus case: a message names
/// the file, the place and what is allowed, and no more.
const MAX_LINE: usize = 260;

/// Cases whose line names the companion's field that names the case rather
/// than the case itself: a user eye curve is checked against the mandrel
/// only where its file's name is no longer known.
const NAMED_BY_FIELD: &[(&str, &str)] = &[
    (
        "eye-curve-csv/inside-mandrel.csv",
        "_companion.toml: eye.curve: ",
    ),
    (
        "eye-curve-csv/too-short.csv",
        "_companion.toml: eye.curve: ",
    ),
];

/// How a format's cases are run: `formcam ARGS`, in the corpus folder, with
/// `{case}` the case (`<format>/<file>`), `{job}` the folder's
/// `_companion.toml` written for the case (its `@CASE@` the case's path),
/// `{out}` a path in a scratch folder (not created) and `{repo}` the
/// repository's root.
struct Rule {
    /// The format's folder under `tests/invalid/`.
    format: &'static str,
    /// The command line.
    args: &'static [&'static str],
}

/// One rule per format folder.
const RULES: &[Rule] = &[
    Rule {
        format: "wind-job",
        args: &["wind", "{case}", "-o", "{out}"],
    },
    Rule {
        format: "wind-layers",
        args: &["wind", "{case}", "-o", "{out}"],
    },
    Rule {
        format: "wind-file",
        args: &["wind", "{case}", "-o", "{out}"],
    },
    Rule {
        format: "meridian-csv",
        args: &["wind", "path", "{job}", "-o", "{out}"],
    },
    Rule {
        format: "eye-curve-csv",
        args: &["wind", "eye", "{job}", "-o", "{out}"],
    },
    Rule {
        format: "post-template",
        args: &["wind", "{job}", "-o", "{out}"],
    },
    Rule {
        format: "machine-toml",
        args: &["machine", "show", "{case}"],
    },
    Rule {
        format: "machine-urdf",
        args: &["machine", "show", "{case}"],
    },
    Rule {
        format: "axes-csv",
        args: &[
            "machine",
            "fk",
            "{repo}/machines/winder-2axis.toml",
            "--axes",
            "{case}",
            "-o",
            "{out}.csv",
        ],
    },
    Rule {
        format: "dress-job",
        args: &["dress", "{case}", "-o", "{out}"],
    },
    Rule {
        format: "dress-contour-csv",
        args: &["dress", "{job}", "-o", "{out}"],
    },
    Rule {
        format: "correct-job",
        args: &["correct", "{case}", "-o", "{out}"],
    },
    Rule {
        format: "scenario-job",
        args: &["correct", "simulate", "{case}", "-o", "{out}"],
    },
    Rule {
        format: "cmm-csv",
        args: &[
            "correct",
            "--measurements",
            "{case}",
            "--program",
            "{repo}/examples/correct/mould.nc",
            "-o",
            "{out}.nc",
        ],
    },
    Rule {
        format: "dmis",
        args: &[
            "correct",
            "--measurements",
            "{case}",
            "--program",
            "{repo}/examples/correct/mould.nc",
            "-o",
            "{out}.nc",
        ],
    },
    Rule {
        format: "gcode",
        args: &[
            "correct",
            "--measurements",
            "{repo}/examples/correct/cmm.csv",
            "--program",
            "{case}",
            "-o",
            "{out}.nc",
        ],
    },
    Rule {
        format: "node-table",
        args: &[
            "correct",
            "--measurements",
            "{repo}/examples/correct/cmm.csv",
            "--program",
            "{case}",
            "-o",
            "{out}.csv",
        ],
    },
];

/// The corpus's root.
fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/invalid")
        .canonicalize()
        .unwrap()
}

/// The file names in `dir` that are cases: not hidden, not companions
/// (`_...`), not the README; sorted.
fn cases_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('_') && !n.starts_with('.'))
        .collect();
    names.sort();
    names
}

/// The format folders of the corpus (every folder not starting with `_`).
fn formats() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(corpus())
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('_') && !n.starts_with('.'))
        .collect();
    names.sort();
    names
}

/// `formcam ARGS` in `dir`, killed (and the test failed) after 60 s.
fn run_in(dir: &Path, args: &[String]) -> Output {
    let mut child = formcam()
        .current_dir(dir)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("formcam {args:?} still running after 60 s");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    child.wait_with_output().unwrap()
}

/// Runs one case by its format's rule; returns stderr with the scratch
/// folder, the corpus and the repository made relative.
fn run_case(rule: &Rule, case: &str) -> (Output, String, PathBuf) {
    let corpus = corpus();
    let rel = format!("{}/{case}", rule.format);
    let dir = scratch(&format!("invalid-{}-{case}", rule.format))
        .canonicalize()
        .unwrap();
    let job = dir.join("_companion.toml");
    let companion = corpus.join(rule.format).join("_companion.toml");
    if companion.exists() {
        let text = std::fs::read_to_string(&companion).unwrap();
        let case_path = corpus.join(&rel);
        std::fs::write(&job, text.replace("@CASE@", case_path.to_str().unwrap())).unwrap();
    }
    let root = repo().canonicalize().unwrap();
    let out = dir.join("out");
    let args: Vec<String> = rule
        .args
        .iter()
        .map(|a| {
            a.replace("{case}", &rel)
                .replace("{job}", job.to_str().unwrap())
                .replace("{out}", out.to_str().unwrap())
                .replace("{repo}", root.to_str().unwrap())
        })
        .collect();
    let o = run_in(&corpus, &args);
    let err = stderr(&o)
        .replace(&format!("{}/", dir.display()), "")
        .replace(&format!("{}/", corpus.display()), "")
        .replace(&format!("{}/", root.display()), "");
    (o, err, dir)
}

/// The files in the scratch folder other than the companion: what a failed
/// run must not have written.
fn written(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "_companion.toml")
        .collect();
    names.sort();
    names
}

/// What is wrong with a case's run, or its one line.
fn check(rule: &Rule, case: &str) -> Result<String, String> {
    let rel = format!("{}/{case}", rule.format);
    let (o, err, dir) = run_case(rule, case);
    let line = err.trim_end();
    if o.status.code() != Some(2) {
        return Err(format!(
            "{rel}: exit status {:?}, expected 2 (bad input): {line}",
            o.status.code()
        ));
    }
    if line.lines().count() != 1 {
        return Err(format!("{rel}: not one line on stderr: {line}"));
    }
    if line.chars().count() > MAX_LINE {
        return Err(format!(
            "{rel}: a line of {} characters (at most {MAX_LINE}): {line}",
            line.chars().count()
        ));
    }
    if line.chars().any(char::is_control) {
        return Err(format!("{rel}: control characters on stderr: {line:?}"));
    }
    let named = NAMED_BY_FIELD
        .iter()
        .find(|(case, _)| *case == rel)
        .map_or(rel.as_str(), |(_, field)| field);
    if !line.contains(named) {
        return Err(format!("{rel}: the line does not name the file: {line}"));
    }
    let left = written(&dir);
    if !left.is_empty() {
        return Err(format!("{rel}: a failed run wrote {left:?}"));
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(line.to_string())
}

/// The snapshot's name: the format and the case, dots made underscores.
fn snapshot_name(format: &str, case: &str) -> String {
    format!("{format}__{}", case.replace('.', "_"))
}

#[test]
fn every_corpus_file_fails_with_one_line_naming_it() {
    let mut failures = Vec::new();
    for format in formats() {
        let Some(rule) = RULES.iter().find(|r| r.format == format) else {
            failures.push(format!("{format}: no rule in tests/invalid.rs"));
            continue;
        };
        for case in cases_in(&corpus().join(&format)) {
            match check(rule, &case) {
                Ok(line) => {
                    let name = snapshot_name(&format, &case);
                    let same = std::panic::catch_unwind(|| {
                        insta::assert_snapshot!(name, line);
                    });
                    if same.is_err() {
                        failures.push(format!(
                            "{format}/{case}: the line differs from its snapshot"
                        ));
                    }
                }
                Err(e) => failures.push(e),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} corpus case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_corpus_covers_every_format() {
    let formats = formats();
    for rule in RULES {
        let cases = cases_in(&corpus().join(rule.format));
        assert!(
            cases.len() >= 4,
            "{}: {} cases, at least 4 per format",
            rule.format,
            cases.len()
        );
    }
    let total: usize = formats
        .iter()
        .map(|f| cases_in(&corpus().join(f)).len())
        .sum();
    assert!(total >= 110, "{total} cases, at least 110");
}

#[test]
fn every_snapshot_has_its_case() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots");
    let names: Vec<String> = formats()
        .iter()
        .flat_map(|f| {
            cases_in(&corpus().join(f))
                .into_iter()
                .map(move |c| format!("invalid__{}.snap", snapshot_name(f, &c)))
        })
        .collect();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let file = entry.unwrap().file_name().to_string_lossy().into_owned();
        if file.starts_with("invalid__") && file.ends_with(".snap") {
            assert!(
                names.contains(&file),
                "{file}: a snapshot without its corpus case (remove it with the case)"
            );
        }
    }
}
