#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]
//! The correction job and scenario files, and a whole program corrected.

use std::path::Path;

use formcam_correct::{
    CORRECT, CorrectError, CorrectionJob, Corrector, Given, Grid, Interpolation, JobField,
    Measurements, MillingProgram, Options, Rule, SCENARIO_JOB, ScenarioError, ScenarioField,
    ScenarioJob, Settings, Tool, correct_program,
};
use formcam_schema::Default as Preset;

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn job(extra: &str) -> Result<CorrectionJob, CorrectError> {
    CorrectionJob::from_toml(
        &format!("[correct]\nmeasurements = \"cmm.csv\"\nprogram = \"m.nc\"\n{extra}"),
        Path::new("."),
    )
}

#[test]
fn the_bundled_job_reads_with_its_settings() {
    let path = examples().join("correct-mould.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let j = CorrectionJob::from_toml(&text, &examples()).unwrap();
    assert_eq!(j.measurements, examples().join("correct/cmm.csv"));
    assert_eq!(j.program, examples().join("correct/mould.nc"));
    let o = j.settings.options;
    assert_eq!(o.tool, Tool::Ball { radius: 6.0 });
    assert_eq!(o.interpolation, Interpolation::Bicubic);
    assert_eq!((o.gain, o.margin_mm), (1.0, 5.0));
    assert_eq!(j.settings.noise_mm, 0.003);
    assert_eq!(j.settings.max_deviation_mm, 5.0);
}

#[test]
fn job_errors_name_the_field_and_the_range() {
    for (extra, want) in [
        ("gain = 0.0", "correct.gain = 0: allowed (0, 2]"),
        ("gain = 2.5", "correct.gain = 2.5: allowed (0, 2]"),
        (
            "tool = \"ball:-2\"",
            "correct.tool = \"ball:-2\": the ball radius must be > 0 mm",
        ),
        (
            "tool = \"flat\"",
            "correct.tool = \"flat\": allowed `point` or `ball:R`",
        ),
        (
            "interpolation = \"spline\"",
            "correct.interpolation = \"spline\": allowed bilinear, bicubic",
        ),
        (
            "margin_mm = -1.0",
            "correct.margin_mm = -1: must be >= 0 mm",
        ),
        (
            "noise_mm = -0.1",
            "correct.noise_mm = -0.1: must be >= 0 mm",
        ),
        (
            "arc_tolerance_mm = 0.0",
            "correct.arc_tolerance_mm = 0: must be > 0 mm",
        ),
        (
            "max_segment_mm = -3.0",
            "correct.max_segment_mm = -3: must be > 0 mm",
        ),
        (
            "max_deviation_mm = 0.0",
            "correct.max_deviation_mm = 0: must be > 0 mm",
        ),
        (
            "dialect = \"heidenhain\"",
            "correct.dialect = \"heidenhain\"",
        ),
        (
            "dialect = \"cldata\"",
            "correct.dialect = \"cldata\": allowed iso, fanuc, sinumerik-840d",
        ),
        (
            "points_per_section = 1",
            "correct.points_per_section = 1: allowed [2, 100000]",
        ),
        (
            "points_per_section = 100001",
            "correct.points_per_section = 100001: allowed [2, 100000]",
        ),
        ("gain = nan", "correct.gain = NaN: allowed (0, 2]"),
        (
            "speed = 3.0",
            "correct.speed at 4:1: unknown field `speed`; allowed: measurements, program",
        ),
        (
            "gain = \"high\"",
            "correct.gain at 4:8: expected a number (0, 2]",
        ),
    ] {
        let e = job(extra).unwrap_err().to_string();
        assert!(e.starts_with(want), "{extra}: {e}");
    }
    let e = CorrectionJob::from_toml("[mandrel]\nkind = \"cylinder\"\n", Path::new("."));
    assert!(e.unwrap_err().to_string().contains("no [correct] table"));
    // The field is an enum the caller can name in its own words.
    assert!(matches!(
        job("gain = 0.0"),
        Err(CorrectError::Field {
            field: JobField::Gain,
            ..
        })
    ));
}

/// A value just outside an end of a range: below a lower end, above an
/// upper one (the end itself where it is open).
fn outside(b: formcam_schema::Bound, below: bool) -> f64 {
    let step = if below { -1.0 } else { 1.0 };
    if b.closed { b.value + step } else { b.value }
}

#[test]
fn every_range_of_the_job_refuses_its_outside_naming_the_field_and_the_range() {
    let mut checked = 0;
    for f in CORRECT.fields {
        let Some(range) = f.range else { continue };
        let field = JobField::from_key(f.name).unwrap();
        let ends = [(range.min, true), (range.max, false)];
        for (end, below) in ends {
            let Some(b) = end else { continue };
            let v = outside(b, below);
            let written = if matches!(f.kind, formcam_schema::Kind::Integer) {
                format!("{v}")
            } else {
                format!("{v:?}")
            };
            let e = job(&format!("{} = {written}", f.name)).unwrap_err();
            let rule = Rule::Range {
                range,
                unit: f.unit,
            };
            assert_eq!(
                e,
                CorrectError::Field {
                    field,
                    value: Given::Number(v),
                    rule: rule.clone(),
                },
                "{}",
                f.name
            );
            // The words: the field, the value as a number, the range and unit.
            let want = format!("correct.{} = {v}: {rule}", f.name);
            assert_eq!(e.to_string(), want);
            assert!(want.contains(&range.to_string()), "{want}");
            checked += 1;
        }
        assert!(matches!(f.default, Preset::Value(_) | Preset::Described(_)));
    }
    // gain (both ends), margin, noise, arc tolerance, points per section
    // (both ends), longest segment, largest deviation.
    assert_eq!(checked, 9);
}

#[test]
fn settings_checked_in_code_say_what_the_job_file_says() {
    // The same value refused from a job file and from settings made in code
    // (the command line's way in) carries the same field, value and rule.
    type Set = fn(&mut Settings);
    let cases: [(&str, Set); 5] = [
        ("gain = 0.0", |s| s.options.gain = 0.0),
        ("margin_mm = -1.0", |s| s.options.margin_mm = -1.0),
        ("noise_mm = -0.1", |s| s.noise_mm = -0.1),
        ("points_per_section = 1", |s| s.points_per_section = Some(1)),
        ("max_deviation_mm = 0.0", |s| s.max_deviation_mm = 0.0),
    ];
    for (extra, set) in cases {
        let mut s = Settings::default();
        set(&mut s);
        assert_eq!(s.check(), Err(job(extra).unwrap_err()), "{extra}");
    }
}

#[test]
fn tools_and_interpolations_parse_from_their_names() {
    assert_eq!("point".parse::<Tool>(), Ok(Tool::Point));
    assert_eq!("ball:6".parse::<Tool>(), Ok(Tool::Ball { radius: 6.0 }));
    assert!("ball:x".parse::<Tool>().is_err());
    assert!("ball:0".parse::<Tool>().is_err());
    assert_eq!(
        "bicubic".parse::<Interpolation>(),
        Ok(Interpolation::Bicubic)
    );
    assert!("Bicubic".parse::<Interpolation>().is_err());
}

#[test]
fn the_scenario_file_reads_and_names_bad_fields() {
    let text = std::fs::read_to_string(examples().join("correct-panel-loop.toml")).unwrap();
    let s = ScenarioJob::from_toml(&text).unwrap();
    assert_eq!(s.section_study, [3, 5, 9, 17, 33]);
    assert_eq!(s.scenario.tool, Tool::Ball { radius: 6.0 });
    assert_eq!(s.scenario.options.interpolation, Interpolation::Bicubic);
    assert_eq!((s.scenario.sections, s.scenario.points), (17, 13));
    for (from, to, want) in [
        ("step = 1.0", "step = 0.0", "program.step = 0: must be > 0"),
        (
            "tool = \"ball:6\"",
            "tool = \"ball:0\"",
            "program.tool = \"ball:0\": the ball radius must be > 0 mm",
        ),
        (
            "kind = \"panel\"",
            "kind = \"dome\"",
            "surface.kind = \"dome\": allowed panel, nose-cone",
        ),
        (
            "interpolation = \"bicubic\"",
            "interpolation = \"cubic\"",
            "loop.interpolation = \"cubic\": allowed bilinear, bicubic",
        ),
    ] {
        let e = ScenarioJob::from_toml(&text.replacen(from, to, 1)).unwrap_err();
        assert!(e.to_string().contains(want), "{to}: {e}");
    }
}

#[test]
fn scenario_fields_out_of_range_name_the_field_in_the_words_of_the_check() {
    let text = std::fs::read_to_string(examples().join("correct-panel-loop.toml")).unwrap();
    for (from, to, field, value) in [
        ("step = 1.0", "step = 0.0", ScenarioField::Step, 0.0),
        (
            "sections = 17",
            "sections = 1",
            ScenarioField::Sections,
            1.0,
        ),
        (
            "iterations = 3",
            "iterations = 21",
            ScenarioField::Iterations,
            21.0,
        ),
        ("gain = 1.0", "gain = 3.0", ScenarioField::Gain, 3.0),
        ("[3, 5, 9", "[3, 1, 9", ScenarioField::SectionStudy, 1.0),
        (
            "amplitude = 0.4",
            "amplitude = -0.4",
            ScenarioField::Amplitude,
            -0.4,
        ),
    ] {
        let e = ScenarioJob::from_toml(&text.replacen(from, to, 1)).unwrap_err();
        let f = field.described().unwrap();
        let rule = Rule::Range {
            range: f.range.unwrap(),
            unit: f.unit,
        };
        assert_eq!(
            e,
            CorrectError::Scenario(ScenarioError::Field {
                field,
                value: Given::Number(value),
                rule: rule.clone(),
            }),
            "{to}"
        );
        // The scenario checked in code refuses it in the same words.
        let (table, key) = field.path();
        assert!(
            SCENARIO_JOB
                .table(table)
                .and_then(|t| t.field(key))
                .is_some()
        );
        assert_eq!(e.to_string(), format!("{table}.{key} = {value}: {rule}"));
    }
    let s = ScenarioJob::from_toml(&text).unwrap();
    let mut loose = s.scenario.clone();
    loose.step = 0.0;
    assert_eq!(
        loose.validate().unwrap_err().to_string(),
        "program.step = 0: must be > 0 mm"
    );
    // A radius the surface's kind needs, left out, and an unknown field.
    let e = ScenarioJob::from_toml(&text.replacen("radius_y = 900.0", "", 1)).unwrap_err();
    let e = e.to_string();
    assert!(
        e.starts_with("surface.radius_y: missing") && e.contains("(required when kind = panel)"),
        "{e}"
    );
    let e = ScenarioJob::from_toml(&text.replacen("seed = 1", "sed = 1", 1)).unwrap_err();
    assert!(e.to_string().starts_with("cmm.sed at "), "{e}");
}

/// A flat plate z = 0 measured in 3 sections x 4 points, everything `dz`
/// high.
fn plate(dz: f64) -> Measurements {
    let mut cmm = String::from("section,point,x_nom,y_nom,z_nom,x_act,y_act,z_act\n");
    for (j, y) in [0.0, 50.0, 100.0].iter().enumerate() {
        for (i, x) in [0.0, 40.0, 80.0, 120.0].iter().enumerate() {
            cmm.push_str(&format!("S{j},{i},{x},{y},0,{x},{y},{dz}\n"));
        }
    }
    Measurements::from_csv(&cmm).unwrap()
}

const PROGRAM: &str = "%\nO100 (PLATE)\nN10 G21 G90 G17\nN20 T1 M6 (TOOL)\nN30 G0 X10. Y10. Z20.\n\
                       N40 G1 Z0. F800.\nN50 X100.\nN60 G3 X100. Y30. I0. J10.\nN70 G1 X10. ; back\n\
                       N80 G0 X200. Z20.\nN90 G1 Z0.\nM30\n%\n";

#[test]
fn apply_moves_the_feed_nodes_and_leaves_rapids_and_nodes_outside() {
    let m = plate(0.1);
    let grid = Grid::from_measurements(&m, None).unwrap();
    let program = MillingProgram::read(PROGRAM, "nc", &Settings::default()).unwrap();
    let a = Corrector::new(&grid, Options::default())
        .unwrap()
        .apply(&program, None)
        .unwrap();
    let rapid = program.movable().iter().filter(|m| !**m).count();
    assert_eq!(rapid, 2);
    assert_eq!(a.nodes.len() + rapid, a.positions.len());
    assert_eq!(a.corrections.len(), a.nodes.len());
    // Inside: 0.1 mm down along z, exactly; the node at x = 200 is outside.
    for (before, (after, c)) in a.nodes.iter().zip(
        a.positions
            .iter()
            .filter(|p| p[2] < 19.0)
            .zip(&a.corrections),
    ) {
        let dz = if before[0] > 150.0 { 0.0 } else { -0.1 };
        assert!(
            (after[2] - before[2] - dz).abs() < 1e-12,
            "{before:?} {c:?}"
        );
    }
    assert_eq!(a.outside_lines, [11]);
    assert_eq!(a.totals.outside, 1);
    assert!(
        a.text.contains("\nN40 G1 Z-.1 F800.\n") || a.text.contains("\nN40 G1 Z-0.1 F800.\n"),
        "{}",
        a.text
    );
    assert!(a.text.contains("\nN80 G0 X200. Z20.\n"), "{}", a.text);
    assert!(a.text.contains("linearised as G1 chords within 0.001 mm"));
}

#[test]
fn the_pipeline_reports_and_names_the_line_beyond_the_limit() {
    let program = MillingProgram::read(PROGRAM, "nc", &Settings::default()).unwrap();
    let c = correct_program(&plate(0.1), &program, &Settings::default()).unwrap();
    let r = &c.report;
    assert_eq!((r.nodes_outside, r.outside_lines.as_str()), (1, "11"));
    assert_eq!(r.nodes_rapid_unchanged, 2);
    assert!((r.max_displacement_mm - 0.1).abs() < 1e-12);
    assert_eq!((r.sections, r.points_per_section), (3, 4));
    assert_eq!(r.smoothing, None);
    let json = serde_json::to_value(r).unwrap();
    assert_eq!(json["tool"], serde_json::json!({"kind": "point"}));
    assert_eq!(json["interpolation"], "bilinear");
    assert_eq!(json["program_syntax"], "iso");
    // 3 mm high with gain 2: 6 mm beyond the default 5 mm, at line 6 (N40).
    let gain2 = Settings {
        options: Options {
            gain: 2.0,
            ..Options::default()
        },
        ..Settings::default()
    };
    let e = correct_program(&plate(3.0), &program, &gain2).unwrap_err();
    assert!(
        matches!(e, CorrectError::NodeDisplacement { line: 6, displacement_mm, .. }
            if (displacement_mm - 6.0).abs() < 1e-9),
        "{e}"
    );
    // A deviation beyond the limit stops before anything is corrected.
    let e = correct_program(&plate(7.0), &program, &gain2).unwrap_err();
    assert!(matches!(e, CorrectError::Deviation { .. }), "{e}");
}
