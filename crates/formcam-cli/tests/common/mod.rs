//! What the CLI's test files share: running the built binary in a scratch
//! folder and reading what it wrote. Each test file is its own process, so
//! scratch folders named by the process id do not meet.

#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};

pub mod browser;

/// The built `formcam` binary.
pub fn formcam() -> Command {
    Command::new(env!("CARGO_BIN_EXE_formcam"))
}

/// `formcam ARGS` run to its end.
pub fn run(args: &[&str]) -> Output {
    formcam().args(args).output().unwrap()
}

/// The repository's root.
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The bundled example jobs.
pub fn examples() -> PathBuf {
    repo().join("examples")
}

/// The shipped machine files.
pub fn machines() -> PathBuf {
    repo().join("machines")
}

/// An example job's text with its machine paths made absolute.
pub fn example(name: &str) -> String {
    std::fs::read_to_string(examples().join(name))
        .unwrap()
        .replace("../machines/", &format!("{}/", machines().display()))
}

/// A fresh, empty folder for one test.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("formcam-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A path as a command-line argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// What formcam printed on stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A JSON file.
pub fn json(path: impl AsRef<Path>) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The `summary.json` of an output folder.
pub fn summary(out: &Path) -> serde_json::Value {
    json(out.join("summary.json"))
}

/// Writes `text` as `scratch(name)/file` (and `extra` files beside it) and
/// runs `formcam ARGS... FILE -o OUT EXTRA_ARGS...`; returns the output and
/// `OUT` (not created beforehand).
pub fn run_file(
    name: &str,
    args: &[&str],
    file: &str,
    text: &str,
    extra: &[(&str, &str)],
    extra_args: &[&str],
) -> (Output, PathBuf) {
    let dir = scratch(name);
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap();
    for (f, content) in extra {
        std::fs::write(dir.join(f), content).unwrap();
    }
    let out = dir.join("out");
    let o = formcam()
        .args(args)
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .args(extra_args)
        .output()
        .unwrap();
    (o, out)
}

/// [`run_file`] for a job `job.toml` without other files or arguments.
pub fn run_job(name: &str, args: &[&str], text: &str) -> (Output, PathBuf) {
    run_file(name, args, "job.toml", text, &[], &[])
}

/// Checks that a run succeeded (the failure shows formcam's stderr).
pub fn ok(name: &str, o: &Output) {
    assert!(o.status.success(), "{name}: {}", stderr(o));
}

/// Checks that a run failed with exit status 2, one line on stderr and
/// nothing written to `out`; returns the line.
pub fn one_line_error(name: &str, o: &Output, out: &Path) -> String {
    let err = stderr(o).trim_end().to_string();
    assert_eq!(o.status.code(), Some(2), "{name}: {err}");
    assert!(!out.exists(), "{name}: a failed run wrote output");
    assert_eq!(err.lines().count(), 1, "{name}: not one line: {err}");
    err
}

/// `formcam demo --examples EXAMPLES -o OUT`.
pub fn demo(examples: &Path, out: &Path) -> Output {
    formcam()
        .arg("demo")
        .arg("--examples")
        .arg(examples)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap()
}

/// Runs `formcam wind JOB -o OUT` and checks that it succeeds.
pub fn wind_ok(job: &Path, out: &Path) -> Output {
    let o = formcam()
        .arg("wind")
        .arg(job)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    ok(&job.display().to_string(), &o);
    o
}

/// The names of the files in a folder.
pub fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into())
        .collect();
    names.sort();
    names
}

/// A serving command (`formcam view`, `formcam studio`), ended when dropped.
pub struct Running {
    /// The process.
    pub child: Child,
    /// The address it printed first.
    pub url: String,
}

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `formcam ARGS` and reads the address it prints first.
pub fn serving(args: &[&str]) -> Running {
    let mut child = formcam()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    let url = first.trim_end().to_string();
    Running { child, url }
}

/// A GET of `path` on the server at `url`: status line and body.
pub fn get(url: &str, path: &str) -> (String, Vec<u8>) {
    let addr = url.trim_start_matches("http://").trim_end_matches('/');
    let request = format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n");
    let a = formcam_testkit::send(
        addr.parse().unwrap(),
        request.as_bytes(),
        std::time::Duration::from_secs(120),
    );
    (a.status_line().to_string(), a.body)
}
