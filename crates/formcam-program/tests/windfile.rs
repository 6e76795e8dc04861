//! `.wind` documents read into winding jobs: the format's validation rules,
//! each error naming the member by its JSON path, unknown members warned of.

#![allow(clippy::unwrap_used)]

use formcam_program::{Check, EYE_CLEARANCE_MM, Layers, MachineSource, WindJob};
use formcam_winding::job::LayerKind;
use serde_json::{Value, json};

fn read(doc: &Value) -> Result<WindJob, formcam_program::ProgramError> {
    WindJob::from_wind(
        &serde_json::to_string_pretty(doc).unwrap(),
        EYE_CLEARANCE_MM,
        &[],
    )
}

/// A valid 1.0 document: a cylinder 100 mm across, a hoop and a helical layer
/// whose 24 circuits (pi 100 cos 41 deg / 10, rounded up) three divide, with a
/// lockDegrees of a multiple of 60 deg stepping the circuits onto distinct slots.
fn base() -> Value {
    json!({
        "schemaVersion": "1.0",
        "mandrelParameters": { "diameter": 100, "windLength": 400 },
        "towParameters": { "width": 10, "thickness": 0.3 },
        "defaultFeedRate": 1500,
        "layers": [
            { "windType": "hoop", "terminal": false },
            {
                "windType": "helical",
                "windAngle": 41,
                "patternNumber": 3,
                "skipIndex": 1,
                "lockDegrees": 180,
                "leadInMM": 10,
                "leadOutDegrees": 10
            }
        ]
    })
}

fn helical(angle: f64, pattern: u32, lock: f64) -> Value {
    json!({
        "windType": "helical",
        "windAngle": angle,
        "patternNumber": pattern,
        "skipIndex": 1,
        "lockDegrees": lock,
        "leadInMM": 10,
        "leadOutDegrees": 10
    })
}

#[test]
fn a_document_is_a_multi_layer_job_on_the_xab_winder() {
    let j = WindJob::from_wind(
        &serde_json::to_string(&base()).unwrap(),
        EYE_CLEARANCE_MM,
        &[Check::Limits],
    )
    .unwrap();
    let Layers::Multi(layers) = &j.layers else {
        panic!("not a multi-layer job");
    };
    assert_eq!(layers.len(), 2);
    assert_eq!(layers[0].kind, Some(LayerKind::Hoop));
    assert_eq!(layers[1].winding_angle_deg, Some(41.0));
    let m = j.machine.as_ref().unwrap();
    assert_eq!(m.machine.name, "X/A/B winder");
    assert_eq!(m.source, MachineSource::Shipped("winder-xab".into()));
    assert_eq!(j.allow, [Check::Slack, Check::Limits]);
    assert_eq!(j.post().extension(), "gcode");
    let w = j.wind_file.as_ref().unwrap();
    assert_eq!(w.schema_version, "1.0");
    assert_eq!(w.eye_radius_mm, 50.0 + EYE_CLEARANCE_MM);
    assert_eq!(w.eye_clearance_mm, EYE_CLEARANCE_MM);
    assert!(j.warnings.is_empty(), "{:?}", j.warnings);
    let e = WindJob::from_wind("{}", -1.0, &[]).unwrap_err().to_string();
    assert!(e.starts_with("--eye-clearance"), "{e}");
}

#[test]
fn unknown_members_are_ignored_with_a_warning() {
    let mut d = base();
    d["generator"] = json!("some CAD plug-in 4.2");
    d["mandrelParameters"]["material"] = json!("aluminium");
    d["layers"][1]["note"] = json!({ "text": "outer helical" });
    let j = read(&d).unwrap();
    for member in ["generator", "mandrelParameters.material", "layers[1].note"] {
        assert!(
            j.warnings.iter().any(|w| w.starts_with(member)),
            "{member}: {:?}",
            j.warnings
        );
    }
}

#[test]
fn invalid_documents_are_refused_for_their_reason() {
    type Edit = Box<dyn Fn(&mut Value)>;
    let cases: Vec<(&str, Edit, &[&str])> = vec![
        (
            "major-2",
            Box::new(|d| d["schemaVersion"] = json!("2.0")),
            &["schemaVersion", "not supported"],
        ),
        (
            "version-malformed",
            Box::new(|d| d["schemaVersion"] = json!("1")),
            &["schemaVersion"],
        ),
        (
            "missing-diameter",
            Box::new(|d| {
                d["mandrelParameters"]
                    .as_object_mut()
                    .unwrap()
                    .remove("diameter");
            }),
            &["mandrelParameters.diameter", "missing"],
        ),
        (
            "zero-length",
            Box::new(|d| d["mandrelParameters"]["windLength"] = json!(0)),
            &["mandrelParameters.windLength", "> 0"],
        ),
        (
            "width-as-text",
            Box::new(|d| d["towParameters"]["width"] = json!("10")),
            &["towParameters.width", "number"],
        ),
        (
            "missing-feed",
            Box::new(|d| {
                d.as_object_mut().unwrap().remove("defaultFeedRate");
            }),
            &["defaultFeedRate", "missing"],
        ),
        (
            "missing-layers",
            Box::new(|d| {
                d.as_object_mut().unwrap().remove("layers");
            }),
            &["layers", "missing"],
        ),
        (
            "wind-type",
            Box::new(|d| d["layers"][1]["windType"] = json!("polar")),
            &["layers[1].windType", "polar"],
        ),
        (
            "angle-zero",
            Box::new(|d| d["layers"][1]["windAngle"] = json!(0)),
            &["layers[1].windAngle", "(0, 90]"],
        ),
        (
            "angle-over-90",
            Box::new(|d| d["layers"][1]["windAngle"] = json!(95)),
            &["layers[1].windAngle", "(0, 90]"],
        ),
        (
            "pattern-fraction",
            Box::new(|d| d["layers"][1]["patternNumber"] = json!(2.5)),
            &["layers[1].patternNumber", "integer"],
        ),
        (
            "skip-index-zero",
            Box::new(|d| d["layers"][1]["skipIndex"] = json!(0)),
            &["layers[1].skipIndex", "integer"],
        ),
        (
            "not-coprime",
            Box::new(|d| {
                d["layers"][1]["patternNumber"] = json!(4);
                d["layers"][1]["skipIndex"] = json!(2);
            }),
            &["layers[1].skipIndex", "coprime"],
        ),
        (
            "lead-in-too-long",
            Box::new(|d| d["layers"][1]["leadInMM"] = json!(400)),
            &["layers[1].leadInMM", "windLength"],
        ),
        (
            "circuits-not-divisible",
            // 24 circuits: two divide them, five do not.
            Box::new(|d| d["layers"][1]["patternNumber"] = json!(5)),
            &["layers[1].patternNumber", "24 circuits"],
        ),
        (
            "lock-not-a-multiple",
            Box::new(|d| d["layers"][1]["lockDegrees"] = json!(100)),
            &[
                "layers[1].lockDegrees",
                "multiple of 180 / patternNumber = 60",
            ],
        ),
        (
            "lock-aliases",
            // 2 x 120 = 240 deg: two slots, plus the skip of one: three, all on one.
            Box::new(|d| d["layers"][1]["lockDegrees"] = json!(120)),
            &["layers[1].lockDegrees", "not coprime"],
        ),
        (
            "lead-out-zero",
            Box::new(|d| d["layers"][1]["leadOutDegrees"] = json!(0)),
            &["layers[1].leadOutDegrees", "> 0"],
        ),
        (
            "expanding-cone",
            Box::new(|d| d["mandrelParameters"]["endDiameter"] = json!(120)),
            &["mandrelParameters.endDiameter", "expanding cone"],
        ),
        (
            "hoop-on-cone",
            Box::new(|d| d["mandrelParameters"]["endDiameter"] = json!(90)),
            &["layers[0]", "hoop layer on a cone"],
        ),
        (
            "cone-unreachable",
            Box::new(|d| {
                d["mandrelParameters"]["endDiameter"] = json!(60);
                d["layers"] = json!([helical(45.0, 1, 180.0)]);
            }),
            &["layers[0].windAngle", "too steep", "36.8699"],
        ),
        (
            "profile",
            Box::new(|d| d["mandrelParameters"]["profile"] = json!({ "type": "vonKarman" })),
            &["mandrelParameters.profile", "vonKarman", "does not wind"],
        ),
        (
            "profile-and-cone",
            Box::new(|d| {
                d["mandrelParameters"]["profile"] = json!({ "type": "vonKarman" });
                d["mandrelParameters"]["endDiameter"] = json!(50);
            }),
            &["mandrelParameters.profile", "mutually exclusive"],
        ),
        (
            "friction",
            Box::new(|d| d["layers"][1]["frictionLambda"] = json!(0.1)),
            &["layers[1].frictionLambda", "profile mandrel"],
        ),
        (
            "friction-negative",
            Box::new(|d| d["layers"][1]["frictionLambda"] = json!(-0.1)),
            &["layers[1].frictionLambda", ">= 0"],
        ),
        (
            "terminal-not-last",
            Box::new(|d| d["layers"][0]["terminal"] = json!(true)),
            &["layers[0].terminal", "last layer"],
        ),
        (
            "terminal-not-bool",
            Box::new(|d| d["layers"][0]["terminal"] = json!("yes")),
            &["layers[0].terminal", "true or false"],
        ),
        (
            "skip-without-rotation",
            Box::new(|d| d["layers"][0] = json!({ "windType": "skip" })),
            &["layers[0].mandrelRotation", "missing"],
        ),
        (
            "misspelt-member",
            Box::new(|d| {
                d["towParameters"] = json!({ "widht": 10, "thickness": 0.3 });
            }),
            &["towParameters.width", "missing", "towParameters.widht"],
        ),
    ];
    for (name, edit, want) in cases {
        let mut d = base();
        edit(&mut d);
        let err = read(&d).unwrap_err().to_string();
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        for w in want {
            assert!(err.contains(w), "{name}: wants {w:?}: {err}");
        }
    }
}

/// The reader's errors are typed: the rule broken and its numbers, not a
/// message to take apart again.
#[test]
fn refusals_are_typed_with_the_member_and_the_numbers() {
    use formcam_program::{ProgramError, WindFileError};
    let mut d = base();
    d["layers"][1]["patternNumber"] = json!(4);
    d["layers"][1]["skipIndex"] = json!(2);
    match read(&d).unwrap_err() {
        ProgramError::WindFile(WindFileError::NotCoprime {
            member,
            skip_index,
            pattern,
            gcd,
        }) => {
            assert_eq!(member, "layers[1].skipIndex");
            assert_eq!((skip_index, pattern, gcd), (2, 4, 2));
        }
        other => panic!("not typed: {other:?}"),
    }
    let mut d = base();
    d["towParameters"] = json!({ "widht": 10, "thickness": 0.3 });
    match read(&d).unwrap_err() {
        ProgramError::WindFile(WindFileError::Missing { member, unknown }) => {
            assert_eq!(member, "towParameters.width");
            assert!(
                unknown.iter().any(|u| u == "towParameters.widht"),
                "{unknown:?}"
            );
        }
        other => panic!("not typed: {other:?}"),
    }
    // JSON that does not parse keeps serde_json's error as its source.
    let e = WindJob::from_wind("{\"layers\": [", EYE_CLEARANCE_MM, &[]).unwrap_err();
    assert!(
        matches!(e, ProgramError::WindFile(WindFileError::Json(_))),
        "{e:?}"
    );
    let source = std::error::Error::source(&e).map(ToString::to_string);
    assert!(source.is_some_and(|s| s.contains("EOF")), "{e}");
    assert!(e.to_string().starts_with("1:"), "{e}");
    // The position once, before serde_json's reason, not again after it.
    let e = WindJob::from_wind("{\n  \"layers\": [,]\n}", EYE_CLEARANCE_MM, &[]).unwrap_err();
    assert_eq!(e.to_string(), "2:14: expected value", "{e}");
}
