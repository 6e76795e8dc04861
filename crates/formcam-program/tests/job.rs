//! Reading winding jobs: the tables, their errors naming the field, the
//! machine by shipped name or file, the enums users write.

#![allow(clippy::unwrap_used)]

use std::path::PathBuf;

use formcam_machine::IkMethod;
use formcam_program::{Layers, MachineSource, ProgramError, Stage, Times, WindJob};

const MANDREL: &str = "[mandrel]\nkind = \"cylinder\"\nradius = 60.0\nlength = 800.0\n";
const WINDING: &str = "[winding]\nmu = 0.0\nwinding_angle_deg = 50.0\nband_width = 8.0\n\
                       band_thickness = 0.3\n";

fn examples() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn read(text: &str) -> Result<WindJob, ProgramError> {
    WindJob::from_toml(text, &examples())
}

fn err(text: &str) -> String {
    read(text).unwrap_err().to_string()
}

#[test]
fn tables_are_read_and_missing_ones_named() {
    let j = read(&format!("{MANDREL}{WINDING}")).unwrap();
    assert!(matches!(j.layers, Layers::Single(_)));
    assert!(!j.is_layered() && j.machine.is_none() && j.eye.is_none());
    assert_eq!(j.furthest_stage(), Stage::Path);
    assert_eq!(j.post().extension(), "mpf");
    let e = read("[mandrel\nkind = 1").unwrap_err();
    assert!(e.is_syntax());
    assert!(e.to_string().starts_with("1:"), "{e}");
    assert_eq!(err(MANDREL), "[winding]: missing table");
    assert_eq!(err(WINDING), "[mandrel]: missing table");
    assert_eq!(
        err(&format!(
            "{MANDREL}{WINDING}{}",
            WINDING.replace("[winding]", "[[layer]]")
        )),
        "[winding] and [[layer]]: give one of them"
    );
    assert_eq!(
        err(&format!("layer = []\n{MANDREL}")),
        "[[layer]]: no layers"
    );
    assert!(err(&format!("{MANDREL}{WINDING}[motoin]\n")).contains("motoin"));
}

#[test]
fn the_machine_is_a_shipped_name_or_a_file_exactly_one() {
    let job = |machine: &str| format!("{MANDREL}{WINDING}[machine]\n{machine}\n");
    let j = read(&job("name = \"winder-4axis\"\nik = \"closed-form\"")).unwrap();
    let m = j.machine.as_ref().unwrap();
    assert_eq!(m.source, MachineSource::Shipped("winder-4axis".into()));
    assert_eq!(m.machine.name, "4-axis winder");
    assert_eq!(m.ik, IkMethod::ClosedForm);
    assert_eq!(j.furthest_stage(), Stage::Axes);
    let f = read(&job("file = \"../machines/winder-4axis.toml\"")).unwrap();
    let fm = f.machine.as_ref().unwrap();
    assert_eq!(fm.machine, m.machine);
    assert_eq!(fm.ik, IkMethod::Auto);
    assert_eq!(
        fm.source.as_str(),
        "../machines/winder-4axis.toml",
        "the file as the job wrote it"
    );
    for both_or_none in [
        "name = \"winder-4axis\"\nfile = \"../machines/winder-4axis.toml\"",
        "ik = \"auto\"",
    ] {
        let e = err(&job(both_or_none));
        assert!(
            e.starts_with("[machine]: give name") && e.contains("winder-xab"),
            "{e}"
        );
    }
    let e = err(&job("name = \"winder-5axis\""));
    assert!(
        e.starts_with("machine.name = \"winder-5axis\" at 11:8: not allowed")
            && e.contains("winder-2axis"),
        "{e}"
    );
    let e = err(&job("file = \"no-such-machine.toml\""));
    assert!(
        e.starts_with("machine.file: \"no-such-machine.toml\" not found"),
        "{e}"
    );
    assert!(err(&job("name = \"winder-4axis\"\nik = \"fast\"")).contains("closed-form"));
}

#[test]
fn motion_times_and_the_post_are_kinds() {
    let j = read(&format!(
        "{MANDREL}{WINDING}[motion]\ntimes = \"pairwise\"\n[post]\ndialect = \"iso\"\n"
    ))
    .unwrap();
    assert_eq!(j.motion.times, Times::Pairwise);
    assert_eq!(j.post().extension(), "nc");
    let j = read(&format!("{MANDREL}{WINDING}[motion]\ntau_s = 0.01\n")).unwrap();
    assert_eq!(j.motion.times, Times::Global);
    let e = err(&format!(
        "{MANDREL}{WINDING}[motion]\ntimes = \"fastest\"\n"
    ));
    assert!(e.contains("fastest") && e.contains("pairwise"), "{e}");
    let e = err(&format!(
        "{MANDREL}{WINDING}[post]\ndialect = \"heidenhain\"\n"
    ));
    assert!(e.starts_with("post.dialect"), "{e}");
    let e = err(&format!(
        "{MANDREL}{WINDING}[post]\ndialect = \"iso\"\ntemplate = \"t.toml\"\n"
    ));
    assert_eq!(e, "post: give either dialect or template, not both");
    let e = err(&format!(
        "{MANDREL}{WINDING}[post]\ntemplate = \"no-such-template.toml\"\n"
    ));
    assert!(e.starts_with("post.template: cannot read"), "{e}");
}

#[test]
fn every_winding_example_reads_and_names_its_furthest_stage() {
    let mut seen = 0;
    for entry in std::fs::read_dir(examples()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        if !text.contains("[mandrel]") {
            continue;
        }
        let j = WindJob::from_toml(&text, &examples()).unwrap().named(&path);
        assert_eq!(j.title, path.display().to_string());
        let want = if text.contains("[machine]")
            && (text.contains("[post]") || text.contains("[[layer]]"))
        {
            Stage::Program
        } else if text.contains("[machine]") {
            Stage::Axes
        } else if text.contains("[eye]") {
            Stage::Eye
        } else {
            Stage::Path
        };
        assert_eq!(j.furthest_stage(), want, "{}", path.display());
        seen += 1;
    }
    assert!(seen >= 10, "{seen}");
}

/// The message after `line:column: ` of a job's syntax error.
fn syntax_message(text: &str) -> String {
    let e = WindJob::from_toml(text, std::path::Path::new(".")).unwrap_err();
    assert!(e.is_syntax(), "{e}");
    let shown = e.to_string();
    let said = shown.splitn(3, ':').nth(2).unwrap_or_default().trim();
    assert!(!said.is_empty(), "an empty message: {shown:?}");
    assert!(!shown.chars().any(char::is_control), "{shown:?}");
    said.to_string()
}

#[test]
fn a_job_cut_after_its_equals_sign_says_a_value_is_expected() {
    let whole = "[mandrel]\nkind = \"cylinder\"\nradius = 50.0\nlength = 200.0\n";
    for cut in [
        "[mandrel]\nkind = \"cylinder\"\nradius =",
        "[mandrel]\nkind = \"cylinder\"\nradius =\n",
        "[mandrel]\nkind = \"cylinder\"\nradius =   \nlength = 200.0\n",
    ] {
        assert!(
            WindJob::from_toml(whole, std::path::Path::new(".")).is_err_and(|e| !e.is_syntax())
        );
        let said = syntax_message(cut);
        assert!(said.contains("expected"), "{cut:?}: {said}");
    }
}

#[test]
fn a_job_with_a_nul_says_nul_is_not_allowed() {
    let said = syntax_message("[mandrel]\nkind = \"cylinder\"\nradius = 50.0\0\n");
    assert!(said.contains("NUL"), "{said}");
    let said = syntax_message("[mandrel]\nkind = \"cyl\0inder\"\n");
    assert!(said.contains("NUL") || said.contains("\\0"), "{said}");
}
