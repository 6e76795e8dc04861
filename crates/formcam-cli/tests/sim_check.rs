//! `formcam check PROGRAM --machine MACHINE [-o report.json]`: the verdict
//! line, the exit status (0 clean, 3 a check failed, 2 bad input), the
//! report written only where asked and never over an input, and every
//! winding program the demo writes checked against its machine: within
//! every position, velocity, velocity-jump and acceleration limit (the
//! planner keeps the machines' `a_max` by default).

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::path::{Path, PathBuf};

use common::{demo, examples, formcam, machines, s, scratch, stderr};

/// `formcam check ARGS`.
fn check(args: &[&str]) -> std::process::Output {
    formcam().arg("check").args(args).output().unwrap()
}

fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A 4-axis winder program (A, X, Y, B) in Sinumerik 840D.
const GOOD: &str = "; PROGRAM OK\nG0 X0 Y250 B0\nG93 G1 A=ACP(10) X1 F60\nG1 A=ACP(20) X3 F60\nG1 A=ACP(30) X4 F60\n";

/// The same with block 3 (line 4) too fast on X and block 4 (line 5) past X's 3000 mm.
const BAD: &str = "; PROGRAM BAD\nG0 X0 Y250 B0\nG93 G1 A=ACP(10) X1 F60\nG1 A=ACP(20) X600 F240\nG1 A=ACP(30) X3001 F0.6\nG1 A=ACP(40) X2990 F0.6\n";

#[test]
fn the_exit_status_says_clean_failed_or_unreadable() {
    let dir = scratch("status");
    let machine = machines().join("winder-4axis.toml");
    let good = dir.join("good.mpf");
    std::fs::write(&good, GOOD).unwrap();
    let o = check(&[s(&good), "--machine", s(&machine)]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), "clean: 4 blocks, 3.000 s\n");

    // A shipped machine by name; the report only where asked.
    let bad = dir.join("bad.mpf");
    std::fs::write(&bad, BAD).unwrap();
    let report = dir.join("report.json");
    let o = check(&[s(&bad), "--machine", "winder-4axis", "-o", s(&report)]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let line = stdout(&o);
    assert_eq!(line.lines().count(), 1, "{line}");
    assert!(
        line.contains("violations: velocity at block 3 (line 4, 1.000 s): axis X"),
        "{line}"
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(r["clean"], false);
    assert_eq!(r["blocks"], 5);
    let v = r["violations"].as_array().unwrap();
    let find = |kind: &str| {
        v.iter()
            .find(|x| x["kind"] == kind && x["axis"] == "X")
            .unwrap_or_else(|| panic!("no {kind}: {v:?}"))
    };
    assert_eq!(
        (
            find("velocity")["block"].as_u64(),
            find("velocity")["line"].as_u64()
        ),
        (Some(3), Some(4))
    );
    assert_eq!(
        (
            find("position")["block"].as_u64(),
            find("position")["line"].as_u64()
        ),
        (Some(4), Some(5))
    );
    assert_eq!(find("position")["value"], 3001.0);
    assert_eq!(find("position")["limit"], 3000.0);

    // Bad input: status 2, one line naming the file, the line and what is allowed.
    let broken = dir.join("broken.mpf");
    std::fs::write(&broken, "G0 X0\nG1 Q=1 F10\n").unwrap();
    let o = check(&[s(&broken), "--machine", "winder-4axis"]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.starts_with(&format!("formcam: error: {}: line 2: ", broken.display())),
        "{err}"
    );
    let odd = dir.join("program.txt");
    std::fs::write(&odd, GOOD).unwrap();
    let o = check(&[s(&odd), "--machine", "winder-4axis"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains(".ngc (LinuxCNC)"), "{}", stderr(&o));
    let o = check(&[s(&good), "--machine", s(&dir.join("none.toml"))]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("none.toml"), "{}", stderr(&o));
    // Never over an input.
    let o = check(&[s(&good), "--machine", s(&machine), "-o", s(&good)]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&good).unwrap(), GOOD);
}

/// The machine a demo job names: `[machine] name` or `file`; `.wind` jobs
/// run on the built-in X/A/B winder.
fn machine_of(job: &Path) -> Option<PathBuf> {
    if job.extension().is_some_and(|e| e == "wind") {
        return Some("winder-xab".into());
    }
    let doc: toml::Value = toml::from_str(&std::fs::read_to_string(job).ok()?).ok()?;
    let m = doc.get("machine")?;
    match (m.get("name"), m.get("file")) {
        (Some(n), _) => Some(n.as_str()?.into()),
        (_, Some(f)) => Some(examples().join(f.as_str()?)),
        _ => None,
    }
}

#[test]
fn every_program_the_demo_writes_keeps_its_machines_limits() {
    let dir = scratch("demo");
    let out = dir.join("out");
    let o = demo(&examples(), &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut checked = Vec::new();
    for entry in std::fs::read_dir(&out).unwrap() {
        let folder = entry.unwrap().path();
        let name = folder.file_name().unwrap().to_string_lossy().into_owned();
        let Some(job) = ["toml", "wind"]
            .iter()
            .map(|e| examples().join(format!("{name}.{e}")))
            .find(|p| p.exists())
        else {
            continue;
        };
        let Some(machine) = machine_of(&job) else {
            continue;
        };
        for program in std::fs::read_dir(&folder).unwrap() {
            let program = program.unwrap().path();
            if program.file_stem().is_none_or(|s| s != "program") {
                continue;
            }
            let report = dir.join(format!("{name}.json"));
            let o = check(&[s(&program), "--machine", s(&machine), "-o", s(&report)]);
            let r: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
            let kinds: Vec<&str> = r["violations"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v["kind"].as_str().unwrap())
                .collect();
            assert!(kinds.is_empty(), "{name}: {}", stdout(&o));
            assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
            checked.push(name.clone());
        }
    }
    checked.sort();
    // The winding programs: Marlin, CLDATA, LinuxCNC and 840D.
    assert!(checked.len() >= 6, "{checked:?}");
}

/// A tube job of radius `r`, for its mandrel.
fn tube_job(r: f64) -> String {
    format!(
        "[mandrel]\nkind = \"cylinder\"\nradius = {r:.1}\nlength = 600.0\n\n[winding]\nmu = 0.0\n\
         winding_angle_deg = 55.0\nband_width = 8.0\nband_thickness = 0.3\ndwell_min_deg = 180.0\n"
    )
}

#[test]
fn the_mandrel_of_a_job_is_checked_against_the_machine() {
    let dir = scratch("mandrel");
    let machine = machines().join("winder-4axis.toml");
    let good = dir.join("good.mpf");
    std::fs::write(&good, GOOD).unwrap();
    // The eye's roller (radius 12) at Y = 250 clears a tube of radius 100;
    // a tube of radius 240 reaches into it.
    let thin = dir.join("thin.toml");
    std::fs::write(&thin, tube_job(100.0)).unwrap();
    let o = check(&[s(&good), "--machine", s(&machine), "--mandrel", s(&thin)]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let thick = dir.join("thick.toml");
    std::fs::write(&thick, tube_job(240.0)).unwrap();
    let o = check(&[s(&good), "--machine", s(&machine), "--mandrel", s(&thick)]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let line = stdout(&o);
    assert!(
        line.starts_with("1 violation: collision at block ")
            && line.contains("eye and mandrel overlap by"),
        "{line}"
    );
    // A job that cannot be read names its file.
    let missing = dir.join("missing.toml");
    let o = check(&[s(&good), "--machine", s(&machine), "--mandrel", s(&missing)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("missing.toml"), "{}", stderr(&o));
}
