//! Inputs read with care: only regular files, at most `--max-input-mb`, a
//! winding job sized against `--max-memory-mb` before it is planned, and
//! machine files in URDF as well as TOML wherever a machine is taken.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::Path;
use std::process::{Output, Stdio};
use std::time::{Duration, Instant};

use common::{example, formcam, machines, ok, one_line_error, run, s, scratch, stderr, summary};

/// `formcam ARGS`, killed (and the test failed) if it takes over 60 s: a
/// reader that waits on a FIFO or reads a device without end never returns.
fn run_bounded(args: &[&str]) -> Output {
    let mut child = formcam()
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
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

#[cfg(unix)]
#[test]
fn dev_zero_as_a_job_is_refused_naming_the_path() {
    let out = scratch("dev-zero").join("out");
    let o = run_bounded(&["wind", "/dev/zero", "-o", s(&out)]);
    let err = one_line_error("dev-zero", &o, &out);
    assert_eq!(
        err,
        "formcam: error: /dev/zero: a character device, not a regular file; give a file"
    );
}

#[cfg(unix)]
#[test]
fn a_fifo_as_a_machine_file_is_refused_without_waiting() {
    let dir = scratch("fifo");
    let fifo = dir.join("machine.toml");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let o = run_bounded(&["machine", "show", s(&fifo)]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains(s(&fifo)) && err.contains("a named pipe, not a regular file"),
        "{err}"
    );
}

#[test]
fn a_folder_as_an_axes_file_is_refused() {
    let dir = scratch("folder");
    let points = dir.join("points.csv");
    let o = run(&[
        "machine",
        "fk",
        s(&machines().join("winder-4axis.toml")),
        "--axes",
        s(&dir),
        "-o",
        s(&points),
    ]);
    let err = one_line_error("folder", &o, &points);
    assert!(
        err.contains(s(&dir)) && err.contains("a folder, not a regular file"),
        "{err}"
    );
}

#[test]
fn a_bad_axes_file_names_the_file_line_column_and_cell() {
    let dir = scratch("bad-axes");
    let points = dir.join("points.csv");
    let fk = |name: &str, text: &str| {
        let axes = dir.join(name);
        std::fs::write(&axes, text).unwrap();
        let o = run(&[
            "machine",
            "fk",
            s(&machines().join("winder-4axis.toml")),
            "--axes",
            s(&axes),
            "-o",
            s(&points),
        ]);
        let err = one_line_error(name, &o, &points);
        assert!(err.contains(s(&axes)), "{err}");
        err
    };
    let err = fk(
        "cell.csv",
        "# hand-written\nA,X,Y,B\n0,0,0,0\n0,1e999,0,0\n",
    );
    assert!(
        err.ends_with(":4: column \"X\": not a finite number: \"1e999\""),
        "{err}"
    );
    let err = fk("header.csv", "# hand-written\nA,X,Y\n0,0,0\n");
    assert!(
        err.ends_with(":2: no column \"B\" (the machine's axes are A, X, Y, B)"),
        "{err}"
    );
    let err = fk("short.csv", "A,X,Y,B\n0,0,0\n");
    assert!(
        err.ends_with(
            ":2: column \"B\" (cell 4) is missing: the row has 3 cells, the header 4 (A, X, Y, B)"
        ),
        "{err}"
    );
    let err = fk("empty.csv", "\n# nothing\n");
    assert!(
        err.ends_with(": empty file (need a header row naming the machine's axes: A, X, Y, B)"),
        "{err}"
    );
}

#[test]
fn an_input_over_the_cap_is_refused_and_the_cap_can_be_raised() {
    let dir = scratch("cap");
    // A valid job padded with a comment to just over 1 MiB.
    let mut text = example("vessel-geodesic.toml");
    text.push('#');
    text.push_str(&"x".repeat(1024 * 1024));
    text.push('\n');
    let job = dir.join("job.toml");
    std::fs::write(&job, &text).unwrap();
    let out = dir.join("out");
    let o = run(&[
        "--max-input-mb",
        "1",
        "wind",
        "path",
        s(&job),
        "-o",
        s(&out),
    ]);
    let err = one_line_error("cap", &o, &out);
    assert_eq!(
        err,
        format!(
            "formcam: error: {}: larger than 1 MiB, the most read of one input; \
             raise it with --max-input-mb",
            job.display()
        )
    );
    // The option is global: after the subcommand too, and 2 MiB is enough.
    let o = run(&[
        "wind",
        "path",
        s(&job),
        "-o",
        s(&out),
        "--max-input-mb",
        "2",
    ]);
    ok("raised", &o);
    assert!(summary(&out)["circuits"].as_u64().unwrap() > 0);
}

#[test]
fn max_input_mb_must_be_positive() {
    let o = run(&["--max-input-mb", "0", "machine", "show", "winder-4axis"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--max-input-mb"), "{}", stderr(&o));
}

#[test]
fn a_job_over_the_memory_budget_is_refused_and_the_budget_can_be_raised() {
    let dir = scratch("budget");
    let job = dir.join("job.toml");
    std::fs::write(&job, example("tube-layers-4axis.toml")).unwrap();
    let out = dir.join("out");
    let o = run(&["--max-memory-mb", "1", "wind", s(&job), "-o", s(&out)]);
    let err = one_line_error("budget", &o, &out);
    assert!(
        err.contains(&format!("{}: [[layer]]: 4 layers", job.display())),
        "{err}"
    );
    assert!(err.contains("over the memory budget of 1 MiB"), "{err}");
    assert!(
        err.contains("raise the budget with --max-memory-mb"),
        "{err}"
    );
    let o = run(&["wind", s(&job), "-o", s(&out), "--max-memory-mb", "64"]);
    ok("raised", &o);
    assert_eq!(summary(&out)["layers"].as_u64(), Some(4));
}

/// `formcam machine show FILE`'s table.
fn show(file: &Path) -> String {
    let o = run(&["machine", "show", s(file)]);
    ok("show", &o);
    String::from_utf8(o.stdout).unwrap()
}

#[test]
fn machine_show_reads_urdf() {
    let urdf = show(&machines().join("placement-arm.urdf"));
    let toml = show(&machines().join("placement-arm.toml"));
    // The same links and axes in the same order (URDF has no homes).
    let first = |t: &str| {
        t.lines()
            .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
            .collect::<Vec<_>>()
    };
    assert_eq!(first(&urdf), first(&toml), "{urdf}\n{toml}");
    assert!(urdf.contains("fibre-placement arm"), "{urdf}");
    // The same document named `.xml` is URDF too.
    let xml = scratch("xml").join("arm.xml");
    std::fs::copy(machines().join("placement-arm.urdf"), &xml).unwrap();
    assert_eq!(show(&xml), urdf);
}

#[test]
fn machine_fk_of_a_urdf_machine_is_that_of_its_toml_file() {
    let dir = scratch("fk-urdf");
    let axes = dir.join("axes.csv");
    std::fs::write(
        &axes,
        "x,A,J1,J2,J3,J4,J5,J6\n0,0,90,-60,100,-130,-90,0\n1,30,45,-30,80,-100,-60,20\n",
    )
    .unwrap();
    let fk = |machine: &str, out: &str| {
        let p = dir.join(out);
        let o = run(&[
            "machine",
            "fk",
            s(&machines().join(machine)),
            "--axes",
            s(&axes),
            "-o",
            s(&p),
        ]);
        ok(machine, &o);
        std::fs::read_to_string(p).unwrap()
    };
    let u = fk("placement-arm.urdf", "urdf.csv");
    let t = fk("placement-arm.toml", "toml.csv");
    assert_eq!(u.lines().next(), t.lines().next());
    assert_eq!(u.lines().count(), 3);
    for (a, b) in u.lines().zip(t.lines()).skip(1) {
        for (x, y) in a.split(',').zip(b.split(',')) {
            let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
            assert!((x - y).abs() < 1e-9, "{a} vs {b}");
        }
    }
}

#[test]
fn a_winding_job_takes_a_urdf_machine_file() {
    let dir = scratch("job-urdf");
    let text = example("tube-placement-arm.toml").replace(
        "name = \"placement-arm\"               # a shipped machine",
        &format!("file = \"{}\"", s(&machines().join("placement-arm.urdf"))),
    );
    assert!(text.contains("placement-arm.urdf"));
    let job = dir.join("job.toml");
    std::fs::write(&job, &text).unwrap();
    let out = dir.join("out");
    let o = run(&["wind", "path", s(&job), "-o", s(&out)]);
    ok("urdf job", &o);
    // Without its roles the URDF is refused, naming the job's machine file.
    let bare = dir.join("bare.urdf");
    std::fs::write(
        &bare,
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>\
         <joint name=\"X\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/>\
         <axis xyz=\"1 0 0\"/><limit lower=\"0\" upper=\"1\" effort=\"0\" velocity=\"1\"/></joint></robot>",
    )
    .unwrap();
    std::fs::write(
        &job,
        text.replace(s(&machines().join("placement-arm.urdf")), s(&bare)),
    )
    .unwrap();
    let out = dir.join("out-bare");
    let o = run(&["wind", "path", s(&job), "-o", s(&out)]);
    let err = one_line_error("bare urdf", &o, &out);
    assert!(
        err.contains("bare.urdf") && err.contains("no <formcam> element"),
        "{err}"
    );
}
