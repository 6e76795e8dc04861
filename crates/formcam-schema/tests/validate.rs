//! The validator on a description that uses every kind of field: each
//! problem reported with its field, place and what is allowed.

#![allow(clippy::unwrap_used)]

use formcam_schema::{
    Condition, Default, EmptyList, Field, JobSchema, Kind, Range, Repeat, SchemaError, Table, Unit,
    Value, validate,
};

const SEGMENT: &[Field] = &[
    Field {
        name: "z_from",
        kind: Kind::Number,
        unit: Unit::Mm,
        range: None,
        default: Default::Required,
        help: "start",
    },
    Field {
        name: "mu",
        kind: Kind::Number,
        unit: Unit::None,
        range: Some(Range::closed(-1.0, 1.0)),
        default: Default::Required,
        help: "slippage",
    },
];

const SHAPE: &[Field] = &[
    Field {
        name: "kind",
        kind: Kind::Word(&["disc", "ring"]),
        unit: Unit::None,
        range: None,
        default: Default::Required,
        help: "which shape",
    },
    Field {
        name: "radius",
        kind: Kind::Number,
        unit: Unit::Mm,
        range: Some(Range::above(0.0)),
        default: Default::RequiredWhen(Condition::Is {
            field: "kind",
            words: &["disc"],
        }),
        help: "its radius",
    },
    Field {
        name: "samples",
        kind: Kind::Integer,
        unit: Unit::None,
        range: Some(Range::closed(2.0, 100.0)),
        default: Default::Value(Value::Integer(10)),
        help: "points",
    },
    Field {
        name: "mu",
        kind: Kind::NumberOrWord(&["auto"]),
        unit: Unit::None,
        range: Some(Range::closed(-1.0, 1.0)),
        default: Default::Value(Value::Number(0.0)),
        help: "slippage",
    },
    Field {
        name: "segments",
        kind: Kind::Tables(SEGMENT),
        unit: Unit::None,
        range: None,
        default: Default::None,
        help: "pieces",
    },
    Field {
        name: "allow",
        kind: Kind::Words(&["slack", "timing"]),
        unit: Unit::None,
        range: None,
        default: Default::Value(Value::EmptyList(EmptyList)),
        help: "accepted",
    },
    Field {
        name: "file",
        kind: Kind::File,
        unit: Unit::None,
        range: None,
        default: Default::RequiredWhen(Condition::Absent { field: "radius" }),
        help: "a table",
    },
    Field {
        name: "on",
        kind: Kind::Boolean,
        unit: Unit::None,
        range: None,
        default: Default::Value(Value::Boolean(true)),
        help: "switch",
    },
];

const LAYER: &[Field] = &[Field {
    name: "angle_deg",
    kind: Kind::Number,
    unit: Unit::Deg,
    range: Some(Range::open(0.0, 90.0)),
    default: Default::Required,
    help: "angle",
}];

const SCHEMA: JobSchema = JobSchema {
    name: "demo",
    help: "a demo",
    tables: &[
        Table {
            name: "shape",
            repeat: Repeat::Single,
            required: true,
            help: "the shape",
            fields: SHAPE,
        },
        Table {
            name: "layer",
            repeat: Repeat::Array,
            required: false,
            help: "layers",
            fields: LAYER,
        },
    ],
};

const GOOD: &str = "[shape]\nkind = \"disc\"\nradius = 5\nsamples = 20\nmu = \"auto\"\n\
                    segments = [{ z_from = 0.0, mu = 0.1 }]\nallow = [\"slack\"]\non = false\n\
                    [[layer]]\nangle_deg = 45.0\n[[layer]]\nangle_deg = 30.0\n";

fn err(text: &str) -> SchemaError {
    validate(&SCHEMA, text).unwrap_err()
}

#[test]
fn a_job_of_every_kind_of_field_validates() {
    validate(&SCHEMA, GOOD).unwrap();
    validate(
        &SCHEMA,
        "shape = { kind = \"ring\", file = \"r.csv\" }\nlayer = []\n",
    )
    .unwrap();
    validate(
        &SCHEMA,
        "[shape]\nkind = \"disc\"\nradius = 1.0\n[[shape.segments]]\nz_from = 1\nmu = 0\n",
    )
    .unwrap();
}

#[test]
fn unknown_names_list_the_allowed_ones() {
    let e = err(&GOOD.replace("[[layer]]\nangle_deg = 30.0", "[layr]\n"));
    assert_eq!(
        e.to_string(),
        "[layr] at 11:2: unknown table; allowed: [shape], [[layer]]"
    );
    let e = err(&GOOD.replace("on = false", "of = false"));
    assert_eq!(
        e.to_string(),
        "shape.of at 8:1: unknown field `of`; allowed: kind, radius, samples, mu, segments, allow, file, on"
    );
    let e = err(&GOOD.replace("mu = 0.1", "mu = 0.1, z = 2"));
    assert!(
        e.to_string().starts_with("shape.segments[1].z at 6:"),
        "{e}"
    );
}

#[test]
fn types_ranges_and_words_name_the_field_the_place_and_what_is_allowed() {
    let e = err(&GOOD.replace("radius = 5", "radius = \"5\""));
    assert_eq!(
        e.to_string(),
        "shape.radius at 3:10: expected a number > 0 mm, found a string"
    );
    let e = err(&GOOD.replace("samples = 20", "samples = 2.5"));
    assert!(
        e.to_string()
            .starts_with("shape.samples at 4:11: expected an integer [2, 100]"),
        "{e}"
    );
    let e = err(&GOOD.replace("radius = 5", "radius = -5"));
    assert_eq!(
        e.to_string(),
        "shape.radius = -5 at 3:10: out of range; allowed > 0 mm"
    );
    let e = err(&GOOD.replace("radius = 5", "radius = nan"));
    assert!(matches!(e, SchemaError::OutOfRange { .. }), "{e}");
    let e = err(&GOOD.replace("angle_deg = 30.0", "angle_deg = 90.0"));
    assert_eq!(
        e.to_string(),
        "layer[2].angle_deg = 90.0 at 12:13: out of range; allowed (0, 90) deg"
    );
    let e = err(&GOOD.replace("mu = \"auto\"", "mu = \"fast\""));
    assert_eq!(
        e.to_string(),
        "shape.mu = \"fast\" at 5:6: not allowed; allowed: auto"
    );
    let e = err(&GOOD.replace("mu = \"auto\"", "mu = 1.5"));
    assert!(
        e.to_string().contains("allowed [-1, 1], or one of auto"),
        "{e}"
    );
    let e = err(&GOOD.replace("[\"slack\"]", "[\"slack\", \"slak\"]"));
    assert!(
        e.to_string().starts_with("shape.allow[2] = \"slak\""),
        "{e}"
    );
    let e = err(&GOOD.replace("kind = \"disc\"", "kind = \"square\""));
    assert!(e.to_string().contains("allowed: disc, ring"), "{e}");
    let e = err(&GOOD.replace("on = false", "on = 1"));
    assert!(matches!(e, SchemaError::WrongType { .. }), "{e}");
}

#[test]
fn missing_fields_and_tables_say_when_they_are_required() {
    let e = err(&GOOD.replace("radius = 5\n", ""));
    assert_eq!(
        e.to_string(),
        "shape.radius: missing in the table at 1:1 (required when kind = disc): \
         a number > 0 mm"
    );
    validate(
        &SCHEMA,
        &GOOD.replace(
            "kind = \"disc\"\nradius = 5\n",
            "kind = \"ring\"\nfile = \"a\"\n",
        ),
    )
    .unwrap();
    let e = err("[shape]\nkind = \"ring\"\n");
    assert!(
        e.to_string().starts_with("shape.file: missing") && e.to_string().contains("unless radius"),
        "{e}"
    );
    assert_eq!(
        err("[[layer]]\nangle_deg = 1.0\n").to_string(),
        "[shape]: missing table"
    );
    let e = err("[[layer]]\n[shape]\nkind = \"ring\"\nfile = \"f\"\n");
    assert!(
        e.to_string().starts_with("layer[1].angle_deg: missing"),
        "{e}"
    );
}

#[test]
fn the_first_problem_by_kind_then_place_is_reported() {
    let both = GOOD
        .replace("radius = 5", "radius = -5")
        .replace("on = false", "of = false");
    assert!(matches!(err(&both), SchemaError::UnknownKey { .. }));
    let e = err("[shape\nkind = 1");
    assert!(e.is_syntax() && e.to_string().starts_with("1:"), "{e}");
}

#[test]
fn the_description_serialises_to_json() {
    let json = serde_json::to_value(SCHEMA).unwrap();
    let shape = &json["tables"][0];
    assert_eq!(shape["name"], "shape");
    assert_eq!(shape["fields"][1]["range"]["min"]["value"], 0.0);
    assert_eq!(shape["fields"][1]["default"]["is"], "required-when");
    assert_eq!(shape["fields"][0]["kind"]["of"][1], "ring");
    assert_eq!(shape["fields"][2]["default"]["value"], 10);
}

#[test]
fn a_list_of_integers_checks_each_entry_against_the_range() {
    const STUDY: JobSchema = JobSchema {
        name: "study",
        help: "a study",
        tables: &[Table {
            name: "loop",
            repeat: Repeat::Single,
            required: true,
            help: "the loop",
            fields: &[Field {
                name: "counts",
                kind: Kind::Integers,
                unit: Unit::None,
                range: Some(Range::closed(2.0, 10.0)),
                default: Default::Value(Value::EmptyList(EmptyList)),
                help: "section counts",
            }],
        }],
    };
    assert_eq!(validate(&STUDY, "[loop]\ncounts = [2, 5, 10]\n"), Ok(()));
    assert_eq!(validate(&STUDY, "[loop]\n"), Ok(()));
    let e = validate(&STUDY, "[loop]\ncounts = [2, 11]\n").unwrap_err();
    assert_eq!(
        e.to_string(),
        "loop.counts[2] = 11 at 2:14: out of range; allowed [2, 10]"
    );
    let e = validate(&STUDY, "[loop]\ncounts = [2, 3.5]\n").unwrap_err();
    assert_eq!(
        e.to_string(),
        "loop.counts[2] at 2:14: expected an integer [2, 10], found a float"
    );
    let e = validate(&STUDY, "[loop]\ncounts = 3\n").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("loop.counts at 2:10: expected a list of integers"),
        "{e}"
    );
}
