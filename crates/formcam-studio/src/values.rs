//! A job's text as the values of its form and back: [`values_of`] reads the
//! TOML as JSON (tables as objects, repeated tables `[[layer]]` as arrays of
//! objects, dates as text), [`apply_values`] writes edited values into the
//! text they came from with `toml_edit`, so that what the user did not
//! change stays byte for byte: comments before and after a key, blank
//! lines and the order of keys and tables. A changed value is replaced in
//! place (keeping the comment after it), a number written as the field's
//! description wants it (an integer for an integer field, a float for a
//! number unless the text had an integer there), new keys appended in the
//! description's order, keys absent from the values removed, whole tables
//! added or removed and `[[layer]]` entries added or removed at the end by
//! the list's length.

pub(crate) use formcam_files::line_col;
use formcam_schema::{Field, JobSchema, Kind, Repeat, Table};
use serde_json::{Map, Number, Value as Json};
use toml_edit::{
    ArrayOfTables, DocumentMut, InlineTable, Item, Table as TomlTable, TableLike, Value as Toml,
};

use crate::error::ValuesProblem;
use crate::{JobKind, StudioError};

/// The values of the job whose text is `text`, as its form shows them:
/// tables as JSON objects, repeated tables as arrays of objects, integers
/// and floats as JSON numbers (a float that is not finite as the text
/// `"nan"`, `"inf"` or `"-inf"`), dates as text.
pub fn values_of(text: &str) -> Result<Json, StudioError> {
    let doc = parse(text)?;
    Ok(json_of_table(doc.as_table()))
}

/// `base` (the job's text as saved) with `values` (the form's values)
/// written into it, keeping everything of `base` the values do not change.
/// The job's kind (and so the description that orders new keys and types
/// numbers) is told from the values' tables, else from `base`'s; see
/// [`apply_values_as`].
pub fn apply_values(base: &str, values: &Json) -> Result<String, StudioError> {
    let kind = values
        .as_object()
        .and_then(|m| {
            let tables: toml::Table = m
                .keys()
                .map(|k| (k.clone(), toml::Value::Table(toml::Table::new())))
                .collect();
            JobKind::of_tables(&tables)
        })
        .or_else(|| JobKind::of_text(base));
    apply_values_as(kind, base, values)
}

/// [`apply_values`] for a job of the kind given (`None`: no description;
/// new keys in the values' order, numbers as the JSON gives them). A JSON
/// `null` is a value left out.
pub fn apply_values_as(
    kind: Option<JobKind>,
    base: &str,
    values: &Json,
) -> Result<String, StudioError> {
    let mut doc = parse(base)?;
    let Json::Object(map) = values else {
        return Err(values_error("", ValuesProblem::NotAnObject));
    };
    apply_root(doc.as_table_mut(), map, kind.and_then(JobKind::schema))?;
    Ok(doc.to_string())
}

/// `text` as an editable document, or where it is not TOML.
fn parse(text: &str) -> Result<DocumentMut, StudioError> {
    text.parse::<DocumentMut>().map_err(|e| {
        let at = e.span().map_or(0, |s| s.start);
        let (line, column) = line_col(text, at);
        StudioError::NotToml {
            line,
            column,
            message: formcam_files::syntax_message(e.message(), text, at),
        }
    })
}

fn values_error(field: &str, problem: ValuesProblem) -> StudioError {
    StudioError::Values {
        field: field.to_string(),
        problem,
    }
}

// ---------------------------------------------------------------- reading

fn json_of_table(t: &dyn TableLike) -> Json {
    Json::Object(
        t.iter()
            .filter_map(|(k, item)| json_of_item(item).map(|v| (k.to_string(), v)))
            .collect(),
    )
}

fn json_of_item(item: &Item) -> Option<Json> {
    match item {
        Item::None => None,
        Item::Value(v) => Some(json_of_value(v)),
        Item::Table(t) => Some(json_of_table(t)),
        Item::ArrayOfTables(a) => Some(Json::Array(a.iter().map(|t| json_of_table(t)).collect())),
    }
}

fn json_of_value(v: &Toml) -> Json {
    match v {
        Toml::String(s) => Json::String(s.value().clone()),
        Toml::Integer(i) => Json::from(*i.value()),
        Toml::Float(f) => json_of_float(*f.value()),
        Toml::Boolean(b) => Json::Bool(*b.value()),
        Toml::Datetime(d) => Json::String(d.value().to_string()),
        Toml::Array(a) => Json::Array(a.iter().map(json_of_value).collect()),
        Toml::InlineTable(t) => json_of_table(t),
    }
}

/// A float as JSON: a number, or the text TOML writes for one that is not
/// finite.
fn json_of_float(f: f64) -> Json {
    match Number::from_f64(f) {
        Some(n) => Json::Number(n),
        None if f.is_nan() => Json::String("nan".into()),
        None if f > 0.0 => Json::String("inf".into()),
        None => Json::String("-inf".into()),
    }
}

/// Whether two values mean the same: numbers by value (`20` and `20.0`),
/// objects by their keys whatever the order.
fn same(a: &Json, b: &Json) -> bool {
    match (a, b) {
        (Json::Number(x), Json::Number(y)) => match (x.as_i64(), y.as_i64()) {
            (Some(i), Some(j)) => i == j,
            _ => x.as_f64() == y.as_f64(),
        },
        (Json::Array(x), Json::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same(p, q))
        }
        (Json::Object(x), Json::Object(y)) => {
            let given = |m: &Map<String, Json>| m.values().filter(|v| !v.is_null()).count();
            given(x) == given(y)
                && x.iter()
                    .filter(|(_, v)| !v.is_null())
                    .all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

// ---------------------------------------------------------------- writing

/// The document's top level: its tables, by the description's tables.
fn apply_root(
    root: &mut TomlTable,
    values: &Map<String, Json>,
    schema: Option<&JobSchema>,
) -> Result<(), StudioError> {
    remove_absent(root, values);
    for key in ordered_keys(
        values,
        schema.map(|s| s.tables.iter().map(|t| t.name).collect()),
    ) {
        let Some(json) = values.get(&key).filter(|v| !v.is_null()) else {
            continue;
        };
        let table = schema.and_then(|s| s.table(&key));
        match table {
            Some(t) => apply_described_table(root, &key, t, json)?,
            None => apply_entry(root, &key, json),
        }
    }
    Ok(())
}

/// A table of the description (`[mandrel]` or `[[layer]]`), given or new.
fn apply_described_table(
    root: &mut TomlTable,
    key: &str,
    table: &Table,
    json: &Json,
) -> Result<(), StudioError> {
    match (table.repeat, json) {
        (Repeat::Single, Json::Object(obj)) => {
            match root.get_mut(key) {
                Some(item) if item.is_table_like() => {
                    if let Some(t) = item.as_table_like_mut() {
                        apply_fields(t, obj, Some(table.fields));
                    }
                }
                _ => {
                    let mut t = TomlTable::new();
                    apply_fields(&mut t, obj, Some(table.fields));
                    root.insert(key, Item::Table(t));
                }
            }
            Ok(())
        }
        (Repeat::Single, _) => Err(values_error(key, ValuesProblem::NotATable)),
        (Repeat::Array, Json::Array(list)) => {
            let mut objects = Vec::with_capacity(list.len());
            for (i, v) in list.iter().enumerate() {
                match v {
                    Json::Object(o) => objects.push(o),
                    _ => {
                        return Err(values_error(
                            &format!("{key}[{i}]"),
                            ValuesProblem::NotATable,
                        ));
                    }
                }
            }
            apply_repeated(root, key, &objects, Some(table.fields));
            Ok(())
        }
        (Repeat::Array, _) => Err(values_error(key, ValuesProblem::NotTables)),
    }
}

/// A repeated table: the entries kept edited in place, new ones appended,
/// those past the list's length removed; an empty list removes it.
fn apply_repeated(
    root: &mut TomlTable,
    key: &str,
    objects: &[&Map<String, Json>],
    fields: Option<&'static [Field]>,
) {
    if objects.is_empty() {
        root.remove(key);
        return;
    }
    if !matches!(root.get(key), Some(Item::ArrayOfTables(_))) {
        let given = Json::Array(objects.iter().map(|o| Json::Object((*o).clone())).collect());
        if root
            .get(key)
            .and_then(json_of_item)
            .is_some_and(|old| same(&old, &given))
        {
            return;
        }
        root.insert(key, Item::ArrayOfTables(ArrayOfTables::new()));
    }
    let Some(Item::ArrayOfTables(aot)) = root.get_mut(key) else {
        return;
    };
    while aot.len() > objects.len() {
        aot.remove(aot.len() - 1);
    }
    for (i, obj) in objects.iter().enumerate() {
        match aot.get_mut(i) {
            Some(t) => apply_fields(t, obj, fields),
            None => {
                let mut t = TomlTable::new();
                apply_fields(&mut t, obj, fields);
                aot.push(t);
            }
        }
    }
}

/// The keys of one table (or inline table): absent ones removed, given ones
/// replaced where changed, new ones appended in the description's order.
fn apply_fields(t: &mut dyn TableLike, values: &Map<String, Json>, fields: Option<&[Field]>) {
    remove_absent(t, values);
    let order = fields.map(|f| f.iter().map(|f| f.name).collect());
    for key in ordered_keys(values, order) {
        let Some(json) = values.get(&key).filter(|v| !v.is_null()) else {
            continue;
        };
        let field = fields.and_then(|fs| fs.iter().find(|f| f.name == key));
        apply_value_entry(t, &key, json, field.map(|f| f.kind));
    }
}

/// A key of the top level that the description does not name: written as
/// JSON gives it (an object as a table, a list of objects as repeated
/// tables, anything else as a value).
fn apply_entry(root: &mut TomlTable, key: &str, json: &Json) {
    match json {
        Json::Object(obj) => match root.get_mut(key) {
            Some(item) if item.is_table_like() => {
                if let Some(t) = item.as_table_like_mut() {
                    apply_fields(t, obj, None);
                }
            }
            _ => {
                let mut t = TomlTable::new();
                apply_fields(&mut t, obj, None);
                root.insert(key, Item::Table(t));
            }
        },
        Json::Array(list) if !list.is_empty() && list.iter().all(Json::is_object) => {
            let objects: Vec<&Map<String, Json>> =
                list.iter().filter_map(Json::as_object).collect();
            apply_repeated(root, key, &objects, None);
        }
        _ => apply_value_entry(root, key, json, None),
    }
}

/// One key's value: left alone when it means the same, else replaced in
/// place with the old value's comment, or appended.
fn apply_value_entry(t: &mut dyn TableLike, key: &str, json: &Json, kind: Option<Kind>) {
    match t.get_mut(key) {
        Some(item) => {
            if json_of_item(item).is_some_and(|old| same(&old, json)) {
                return;
            }
            match item {
                Item::Value(old) => {
                    let mut new = toml_value(json, kind, Some(&*old));
                    *new.decor_mut() = old.decor().clone();
                    *old = new;
                }
                other => *other = Item::Value(toml_value(json, kind, None)),
            }
        }
        None => {
            t.insert(key, Item::Value(toml_value(json, kind, None)));
        }
    }
}

/// The keys of `t` that `values` does not give (or gives as `null`),
/// removed.
fn remove_absent(t: &mut dyn TableLike, values: &Map<String, Json>) {
    let absent: Vec<String> = t
        .iter()
        .map(|(k, _)| k.to_string())
        .filter(|k| values.get(k).is_none_or(Json::is_null))
        .collect();
    for k in absent {
        t.remove(&k);
    }
}

/// The keys of `values`: first those the description lists, in its order,
/// then the others in the values' order.
fn ordered_keys(values: &Map<String, Json>, described: Option<Vec<&str>>) -> Vec<String> {
    let described = described.unwrap_or_default();
    let mut keys: Vec<String> = described
        .iter()
        .filter(|k| values.contains_key(**k))
        .map(|k| k.to_string())
        .collect();
    keys.extend(
        values
            .keys()
            .filter(|k| !described.contains(&k.as_str()))
            .cloned(),
    );
    keys
}

/// A JSON value as a TOML value of the field's kind (`kind`), the old value
/// `old` telling an integer from a float where the kind allows both.
fn toml_value(json: &Json, kind: Option<Kind>, old: Option<&Toml>) -> Toml {
    match json {
        Json::Null => Toml::from(""),
        Json::Bool(b) => Toml::from(*b),
        Json::Number(n) => number(n.as_i64(), n.as_f64().unwrap_or(f64::NAN), kind, old),
        Json::String(s) => string(s, kind, old),
        Json::Array(list) => {
            let inner = match kind {
                Some(Kind::Integers) => Some(Kind::Integer),
                Some(Kind::Tables(sub)) => Some(Kind::Tables(sub)),
                _ => None,
            };
            let mut a = toml_edit::Array::new();
            for v in list {
                a.push(toml_value(v, inner, None));
            }
            Toml::Array(a)
        }
        Json::Object(obj) => {
            let sub = match kind {
                Some(Kind::Tables(sub)) => Some(sub),
                _ => None,
            };
            let mut t = InlineTable::new();
            for key in ordered_keys(obj, sub.map(|s| s.iter().map(|f| f.name).collect())) {
                let Some(v) = obj.get(&key).filter(|v| !v.is_null()) else {
                    continue;
                };
                let field = sub.and_then(|s| s.iter().find(|f| f.name == key));
                t.insert(key.as_str(), toml_value(v, field.map(|f| f.kind), None));
            }
            Toml::InlineTable(t)
        }
    }
}

/// A number as its field wants it: an integer field takes a whole number as
/// an integer; a number field takes a float, or an integer where the text
/// had one and the value is whole.
fn number(int: Option<i64>, f: f64, kind: Option<Kind>, old: Option<&Toml>) -> Toml {
    let whole = int.or_else(|| (f.fract() == 0.0 && f.abs() < 9.0e15).then_some(f as i64));
    match (kind, whole) {
        (Some(Kind::Integer), Some(i)) => Toml::from(i),
        (Some(Kind::Number | Kind::NumberOrWord(_)), Some(i))
            if matches!(old, Some(Toml::Integer(_))) =>
        {
            Toml::from(i)
        }
        (Some(Kind::Number | Kind::NumberOrWord(_) | Kind::Integer), _) => Toml::from(f),
        _ => match int {
            Some(i) => Toml::from(i),
            None => Toml::from(f),
        },
    }
}

/// Text as its field wants it: a number field takes text that reads as a
/// number (a form's input, `nan`, `inf`) as that number; a date stays a
/// date where the text had one.
fn string(s: &str, kind: Option<Kind>, old: Option<&Toml>) -> Toml {
    let numeric = matches!(
        kind,
        Some(Kind::Number | Kind::Integer | Kind::NumberOrWord(_))
    );
    if numeric {
        let t = s.trim();
        if let Ok(i) = t.parse::<i64>() {
            return number(Some(i), i as f64, kind, old);
        }
        let special = match t {
            "nan" | "+nan" | "-nan" => Some(f64::NAN),
            "inf" | "+inf" => Some(f64::INFINITY),
            "-inf" => Some(f64::NEG_INFINITY),
            _ => None,
        };
        if let Some(f) = special.or_else(|| t.parse::<f64>().ok().filter(|f| f.is_finite())) {
            return number(None, f, kind, old);
        }
    }
    if let Some(Toml::Datetime(_)) = old
        && let Ok(d) = s.parse::<toml_edit::Datetime>()
    {
        return Toml::from(d);
    }
    Toml::from(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    const JOB: &str = "# a job\n[mandrel]\nkind = \"cylinder\"  # the shape\n\n# radius in mm\nradius = 50.0\nlength = 300\n\n[winding]\nwinding_angle_deg = 45.0 # deg\nband_width = 10.0\n";

    #[test]
    fn values_are_tables_of_fields() {
        let v = values_of(JOB).expect("toml");
        assert_eq!(v["mandrel"]["kind"], json!("cylinder"));
        assert_eq!(v["mandrel"]["radius"], json!(50.0));
        assert!(v["mandrel"]["length"].is_i64());
        assert_eq!(v["winding"]["band_width"], json!(10.0));
        let layered =
            values_of("[[layer]]\nkind = \"hoop\"\n[[layer]]\nkind = \"skip\"\n").expect("toml");
        assert_eq!(layered["layer"][1]["kind"], json!("skip"));
        let dated = values_of("[a]\nwhen = 1979-05-27T07:32:00Z\nx = nan\n").expect("toml");
        assert_eq!(dated["a"]["when"], json!("1979-05-27T07:32:00Z"));
        assert_eq!(dated["a"]["x"], json!("nan"));
        assert!(matches!(
            values_of("[a\n"),
            Err(StudioError::NotToml { line: 1, .. })
        ));
    }

    #[test]
    fn nothing_changed_is_the_same_text() {
        let v = values_of(JOB).expect("toml");
        assert_eq!(apply_values(JOB, &v).expect("applies"), JOB);
        // A form sends 50 for 50.0: the same value.
        let mut sent = v.clone();
        sent["mandrel"]["radius"] = json!(50);
        assert_eq!(apply_values(JOB, &sent).expect("applies"), JOB);
    }

    #[test]
    fn a_changed_value_keeps_its_comments_and_type() {
        let mut v = values_of(JOB).expect("toml");
        v["mandrel"]["radius"] = json!(60);
        v["mandrel"]["length"] = json!(250);
        v["winding"]["winding_angle_deg"] = json!("30");
        let out = apply_values(JOB, &v).expect("applies");
        assert!(out.contains("# radius in mm\nradius = 60.0\n"), "{out}");
        assert!(out.contains("length = 250\n"), "{out}");
        assert!(out.contains("winding_angle_deg = 30.0 # deg\n"), "{out}");
        assert!(out.starts_with("# a job\n[mandrel]\nkind = \"cylinder\"  # the shape\n"));
        assert_eq!(
            values_of(&out).expect("toml")["mandrel"]["radius"],
            json!(60.0)
        );
    }

    #[test]
    fn keys_and_tables_added_and_removed() {
        let mut v = values_of(JOB).expect("toml");
        v["winding"]["samples"] = json!(2001);
        v["winding"]["mu"] = json!(0.1);
        v["mandrel"]
            .as_object_mut()
            .expect("object")
            .remove("length");
        v["eye"] = json!({"mode": "axis-parallel", "radius": 160});
        let out = apply_values_as(Some(JobKind::Winding), JOB, &v).expect("applies");
        assert!(!out.contains("length"), "{out}");
        // mu before samples: the description's order.
        let (mu, samples) = (out.find("mu = 0.1"), out.find("samples = 2001"));
        assert!(mu.is_some() && samples.is_some() && mu < samples, "{out}");
        assert!(
            out.contains("[eye]\nmode = \"axis-parallel\"\nradius = 160.0\n"),
            "{out}"
        );
        assert!(out.find("[eye]") > out.find("[winding]"), "{out}");
        let mut back = values_of(&out).expect("toml");
        back.as_object_mut().expect("object").remove("eye");
        let out2 = apply_values(&out, &back).expect("applies");
        assert!(!out2.contains("[eye]"), "{out2}");
    }

    #[test]
    fn layers_added_and_removed_by_the_list() {
        let base = "[mandrel]\nkind = \"cylinder\"\n\n# first\n[[layer]]\nkind = \"hoop\"\nband_width = 10.0\n\n[[layer]]\nkind = \"helical\" # second\nband_width = 10.0\n\n[machine]\nname = \"winder-4axis\"\n";
        let mut v = values_of(base).expect("toml");
        let layers = v["layer"].as_array_mut().expect("layers");
        layers.push(json!({"kind": "skip", "mandrel_rotation_deg": 90}));
        let out = apply_values(base, &v).expect("applies");
        let back = values_of(&out).expect("toml");
        assert_eq!(back["layer"].as_array().map(Vec::len), Some(3));
        assert_eq!(back["layer"][2]["mandrel_rotation_deg"], json!(90.0));
        assert!(out.contains("kind = \"helical\" # second"), "{out}");
        assert!(out.find("kind = \"skip\"") < out.find("[machine]"), "{out}");
        let mut fewer = back.clone();
        fewer["layer"].as_array_mut().expect("layers").truncate(1);
        let out = apply_values(&out, &fewer).expect("applies");
        assert_eq!(
            values_of(&out).expect("toml")["layer"]
                .as_array()
                .map(Vec::len),
            Some(1)
        );
        assert!(out.contains("# first\n[[layer]]"), "{out}");
    }

    #[test]
    fn a_new_job_is_written_in_the_descriptions_order() {
        let v = json!({
            "process": {"step": 0.01, "depth": 0.05},
            "wheel": {"width": 6, "ball_radius": 1.85},
            "dresser": {"width": 2.9},
        });
        let out = apply_values("", &v).expect("applies");
        assert_eq!(
            out,
            "[wheel]\nball_radius = 1.85\nwidth = 6.0\n\n[dresser]\nwidth = 2.9\n\n\
             [process]\ndepth = 0.05\nstep = 0.01\n"
        );
        assert_eq!(JobKind::of_text(&out), Some(JobKind::Dressing));
    }

    #[test]
    fn values_that_are_no_tables_are_refused_naming_them() {
        let e = apply_values(JOB, &json!({"mandrel": 3})).expect_err("refused");
        assert_eq!(
            e.to_string(),
            "mandrel: a table must be an object of fields"
        );
        let e = apply_values_as(Some(JobKind::Winding), JOB, &json!({"layer": [{}, 2]}))
            .expect_err("refused");
        assert_eq!(
            e.to_string(),
            "layer[1]: a table must be an object of fields"
        );
        assert!(apply_values(JOB, &json!([1])).is_err());
    }
}
