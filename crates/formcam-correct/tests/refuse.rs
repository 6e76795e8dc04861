#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]
//! Programs the correction does not understand are refused as it reads
//! them (before anything is computed or written), one line naming the
//! program line, its text and what to write instead; programs cut off in
//! the middle of a word are reported; the words it passes over leave the
//! program as it was but for the corrected numbers.

use std::path::{Path, PathBuf};

use formcam_correct::{Measurements, MillingProgram, Settings, correct_program};

fn programs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/programs")
}

/// Reads `name` from `tests/programs` as the correction reads a program
/// file (the dialect from its extension).
fn read(name: &str) -> (String, Result<MillingProgram, String>) {
    let path = programs().join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let ext = path.extension().unwrap().to_str().unwrap();
    let read = MillingProgram::read(&text, ext, &Settings::default()).map_err(|e| e.to_string());
    (text, read)
}

/// Every refused program: its file, the line refused and what the message
/// says there.
const REFUSED: &[(&str, usize, &str)] = &[
    // Sinumerik 840D.
    ("polar-ap-rp.mpf", 4, "polar coordinates (`AP`)"),
    ("polar-pole.mpf", 4, "polar coordinates (`G111`)"),
    ("cycle81.mpf", 4, "the canned cycle `CYCLE81`"),
    ("mcall-cycle.mpf", 4, "the canned cycle `CYCLE81`"),
    ("pocket.mpf", 4, "the canned cycle `POCKET3`"),
    ("call-l.mpf", 4, "`L123` calls a subprogram"),
    ("call.mpf", 4, "`CALL` calls a subprogram"),
    ("subprogram-name.mpf", 4, "`FINISH_SIDE` is a keyword"),
    ("bspline.mpf", 4, "the spline `BSPLINE`"),
    ("aspline.mpf", 4, "the spline `ASPLINE`"),
    ("cspline.mpf", 4, "the spline `CSPLINE`"),
    ("poly.mpf", 4, "the spline `POLY`"),
    ("trans.mpf", 4, "`TRANS` changes the coordinate system"),
    ("atrans.mpf", 4, "`ATRANS` changes the coordinate system"),
    ("arot.mpf", 4, "`AROT` changes the coordinate system"),
    ("ascale.mpf", 4, "`ASCALE` changes the coordinate system"),
    ("amirror.mpf", 4, "`AMIRROR` changes the coordinate system"),
    ("g58-offset.mpf", 4, "`G58` changes the coordinate system"),
    ("radius-comp.mpf", 4, "`G41` offsets the tool"),
    ("cip.mpf", 4, "the arc form `CIP`"),
    ("gotob.mpf", 5, "`GOTOB` jumps"),
    ("cut-assignment.mpf", 4, "in the middle of the word `Z=`"),
    // ISO/Fanuc.
    ("g68-rotation.nc", 6, "`G68` changes the coordinate system"),
    ("g51-scaling.nc", 6, "`G51` changes the coordinate system"),
    ("g65-macro.nc", 6, "`G65` calls a subprogram"),
    ("m98-call.nc", 6, "`M98` calls a subprogram"),
    ("radius-comp.nc", 6, "`G41` offsets the tool"),
    ("g16-polar.nc", 6, "polar coordinates (`G16`)"),
    ("g81-cycle.nc", 6, "the canned cycle `G81`"),
    ("macro-if.nc", 6, "`IF` jumps"),
    ("g5-spline.nc", 6, "the spline `G5`"),
    ("cut-letter.nc", 6, "in the middle of the word `Y`"),
    ("cut-comment.nc", 6, "in the middle of a comment"),
    // LinuxCNC.
    ("g5-cubic.ngc", 5, "the spline `G5`"),
    ("g5-1-quadratic.ngc", 5, "the spline `G5.1`"),
    ("g5-2-nurbs.ngc", 5, "the spline `G5.2`"),
    ("o-call.ngc", 5, "`call` calls a subprogram"),
    ("o-sub.ngc", 5, "`sub` calls a subprogram"),
    ("o-if.ngc", 5, "`if` jumps"),
    ("g38-probe.ngc", 5, "`G38.2` is a probing move"),
    ("g17-1-plane.ngc", 5, "`G17.1`: arcs in the U, V, W planes"),
    ("radius-comp.ngc", 5, "`G41.1` offsets the tool"),
    ("g7-diameter.ngc", 5, "`G7` changes the coordinate system"),
    ("cut-sign.ngc", 5, "in the middle of the word `Y-`"),
];

#[test]
fn programs_the_correction_does_not_understand_are_refused_at_their_line() {
    for &(name, line, says) in REFUSED {
        let (text, read) = read(name);
        let e = match read {
            Ok(_) => panic!("{name}: read"),
            Err(e) => e,
        };
        assert_eq!(e.lines().count(), 1, "{name}: {e}");
        let quoted = text.lines().nth(line - 1).unwrap().trim_end();
        assert!(
            e.starts_with(&format!("line {line}: `{quoted}`: ")),
            "{name}: {e}"
        );
        assert!(e.contains(says), "{name}: {e}");
        // What to do instead, after the reason.
        assert!(e.contains("; "), "{name}: {e}");
    }
}

#[test]
fn every_program_in_the_folder_is_checked() {
    let mut listed: Vec<&str> = REFUSED.iter().map(|r| r.0).collect();
    listed.extend(PASSED);
    listed.sort_unstable();
    let mut found: Vec<String> = std::fs::read_dir(programs())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    found.sort_unstable();
    assert_eq!(found, listed);
}

/// Programs whose every word is read or passed over.
const PASSED: [&str; 3] = ["passed.mpf", "passed.nc", "passed.ngc"];

/// A line with the numbers of its `X`, `Y`, `Z` words left out.
fn without_coordinates(line: &str) -> String {
    let mut out = String::new();
    let mut skipping = false;
    for c in line.chars() {
        if skipping && (c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | '=')) {
            continue;
        }
        skipping = matches!(c, 'X' | 'Y' | 'Z');
        out.push(c);
    }
    out
}

#[test]
fn words_that_do_not_move_the_path_are_passed_over_and_kept() {
    let mut cmm = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n");
    for (j, y) in [-10.0, 50.0, 100.0].iter().enumerate() {
        for (i, x) in [-10.0, 40.0, 80.0].iter().enumerate() {
            cmm.push_str(&format!("S{j},{i},{x},{y},0,{x},{y},0.1\n"));
        }
    }
    let m = Measurements::from_csv(&cmm).unwrap();
    for name in PASSED {
        let (text, read) = read(name);
        let program = read.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(program.write(&program.positions()).unwrap(), text, "{name}");
        let c = correct_program(&m, &program, &Settings::default()).unwrap();
        assert!(c.report.nodes_corrected >= 2, "{name}: {:?}", c.report);
        let (old, new): (Vec<_>, Vec<_>) =
            (text.lines().collect(), c.applied.text.lines().collect());
        assert_eq!(old.len(), new.len(), "{name}:\n{}", c.applied.text);
        let mut changed = 0;
        for (o, n) in old.iter().zip(&new) {
            if o != n {
                changed += 1;
                assert_eq!(without_coordinates(o), without_coordinates(n), "{name}");
            }
        }
        assert!(changed >= 2, "{name}:\n{}", c.applied.text);
    }
}
