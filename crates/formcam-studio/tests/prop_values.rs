//! The form's values written into a job's text and read back: what was
//! written is what is read, and writing the values read changes no byte.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use formcam_schema::{Field, Kind, Repeat};
use formcam_studio::{JobKind, apply_values_as, examples, values_of};
use proptest::prelude::*;
use serde_json::{Map, Value, json};

/// One edit of a form: a field set or cleared, a table dropped, a layer
/// added.
#[derive(Debug, Clone)]
enum Edit {
    Set {
        table: usize,
        entry: usize,
        field: usize,
        seed: Seed,
    },
    Clear {
        table: usize,
        entry: usize,
        field: usize,
    },
    Drop {
        table: usize,
    },
}

/// What a set value is made from, by the field's kind.
#[derive(Debug, Clone)]
struct Seed {
    number: f64,
    integer: i64,
    flag: bool,
    word: usize,
    text: String,
}

fn seed() -> impl Strategy<Value = Seed> {
    (
        prop_oneof![-1.0e6..1.0e6, (-1000i64..1000).prop_map(|i| i as f64 / 8.0)],
        -100_000i64..100_000,
        any::<bool>(),
        0usize..64,
        "\\PC{0,12}",
    )
        .prop_map(|(number, integer, flag, word, text)| Seed {
            number,
            integer,
            flag,
            word,
            text,
        })
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        4 => (0usize..16, 0usize..4, 0usize..32, seed()).prop_map(|(table, entry, field, seed)| {
            Edit::Set { table, entry, field, seed }
        }),
        2 => (0usize..16, 0usize..4, 0usize..32).prop_map(|(table, entry, field)| Edit::Clear {
            table,
            entry,
            field
        }),
        1 => (0usize..16).prop_map(|table| Edit::Drop { table }),
    ]
}

/// A value of the field's kind.
fn value(f: &Field, s: &Seed) -> Option<Value> {
    let word = |words: &[&str]| words.get(s.word % words.len().max(1)).map(|w| json!(w));
    Some(match f.kind {
        Kind::Number => json!(s.number),
        Kind::Integer => json!(s.integer),
        Kind::Boolean => json!(s.flag),
        Kind::Text | Kind::File => json!(s.text),
        Kind::Word(w) | Kind::Name(w) => word(w)?,
        Kind::NumberOrWord(w) if s.flag => word(w)?,
        Kind::NumberOrWord(_) => json!(s.number),
        Kind::Words(w) => json!([word(w)?]),
        Kind::Integers => json!([s.integer, s.integer + 1]),
        Kind::Tables(_) => return None,
    })
}

/// The object an edit of `table`'s entry works on, made when absent.
fn entry<'v>(
    values: &'v mut Map<String, Value>,
    name: &str,
    repeat: Repeat,
    index: usize,
) -> Option<&'v mut Map<String, Value>> {
    match repeat {
        Repeat::Single => values
            .entry(name.to_string())
            .or_insert_with(|| json!({}))
            .as_object_mut(),
        Repeat::Array => {
            let list = values
                .entry(name.to_string())
                .or_insert_with(|| json!([{}]))
                .as_array_mut()?;
            let k = index % list.len().max(1);
            list.get_mut(k)?.as_object_mut()
        }
    }
}

fn apply(kind: JobKind, values: &mut Value, e: &Edit) {
    let schema = kind.schema().expect("an editable kind has a description");
    let Some(map) = values.as_object_mut() else {
        return;
    };
    match e {
        Edit::Set {
            table,
            entry: i,
            field,
            seed,
        } => {
            let t = &schema.tables[table % schema.tables.len()];
            let f = &t.fields[field % t.fields.len()];
            if let (Some(obj), Some(v)) = (entry(map, t.name, t.repeat, *i), value(f, seed)) {
                obj.insert(f.name.to_string(), v);
            }
        }
        Edit::Clear {
            table,
            entry: i,
            field,
        } => {
            let t = &schema.tables[table % schema.tables.len()];
            let f = &t.fields[field % t.fields.len()];
            if let Some(obj) = entry(map, t.name, t.repeat, *i) {
                obj.remove(f.name);
            }
        }
        Edit::Drop { table } => {
            let t = &schema.tables[table % schema.tables.len()];
            map.remove(t.name);
        }
    }
}

/// The same values: numbers by value, whatever their JSON type.
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => x.as_f64() == y.as_f64(),
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same(p, q))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

#[test]
fn every_example_written_back_unchanged_is_the_same_text() {
    for ex in examples() {
        let values = values_of(ex.text).expect("values");
        let text = apply_values_as(Some(ex.kind), ex.text, &values).expect("applied");
        assert_eq!(text, ex.text, "{}", ex.name);
        assert_eq!(values_of(&text).expect("values"), values, "{}", ex.name);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    #[test]
    fn values_written_are_the_values_read(
        which in 0usize..64,
        edits in proptest::collection::vec(edit(), 1..8),
    ) {
        let ex = &examples()[which % examples().len()];
        let mut values = values_of(ex.text).expect("values");
        for e in &edits {
            apply(ex.kind, &mut values, e);
        }
        let text = apply_values_as(Some(ex.kind), ex.text, &values).expect("applied");
        let read = values_of(&text).expect("the text written is TOML");
        prop_assert!(same(&read, &values), "{}\n{text}\nread {read}\nwritten {values}", ex.name);
        // Nothing changed: not a byte.
        let again = apply_values_as(Some(ex.kind), &text, &read).expect("applied");
        prop_assert_eq!(again, text);
    }
}
