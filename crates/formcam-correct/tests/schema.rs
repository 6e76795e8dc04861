//! The correction job's and the scenario's descriptions against their
//! readers, the examples and the docs: a field's default written out reads
//! as the field left out, the examples validate, and `docs/correction.md`
//! lists the fields the descriptions write.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use formcam_correct::{CORRECT_JOB, CorrectionJob, SCENARIO_JOB, ScenarioJob};
use formcam_schema::{Default, JobSchema, replace_marked, validate};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn example(name: &str) -> String {
    std::fs::read_to_string(root().join("examples").join(name)).unwrap()
}

/// Every field with a default value, written out into `base` after its
/// table's header: `read` gives the same as for `base`. Returns the fields
/// checked.
fn defaults_read_as_left_out(
    schema: &JobSchema,
    base: &str,
    read: impl Fn(&str) -> String,
) -> Vec<String> {
    let want = read(base);
    let mut checked = Vec::new();
    for table in schema.tables {
        let header = format!("[{}]\n", table.name);
        for f in table.fields {
            let Default::Value(v) = f.default else {
                continue;
            };
            if base.contains(&format!("\n{} =", f.name)) {
                continue;
            }
            let job = base.replace(&header, &format!("{header}{} = {}\n", f.name, v.toml()));
            validate(schema, &job).unwrap();
            assert_eq!(read(&job), want, "{}.{}", table.name, f.name);
            checked.push(format!("{}.{}", table.name, f.name));
        }
    }
    checked
}

#[test]
fn a_default_written_out_reads_as_the_field_left_out() {
    let job = "[correct]\nmeasurements = \"cmm.csv\"\nprogram = \"m.nc\"\n";
    let checked = defaults_read_as_left_out(&CORRECT_JOB, job, |t| {
        format!("{:?}", CorrectionJob::from_toml(t, Path::new(".")).unwrap())
    });
    assert_eq!(checked.len(), 7, "{checked:?}");
    // The example without the fields it gives at their defaults or where
    // the default is another value.
    let scenario = example("correct-panel-loop.toml")
        .lines()
        .filter(|l| {
            !["seed =", "gain =", "smoothing ="]
                .iter()
                .any(|k| l.starts_with(k))
        })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n";
    let checked = defaults_read_as_left_out(&SCENARIO_JOB, &scenario, |t| {
        format!("{:?}", ScenarioJob::from_toml(t).unwrap())
    });
    assert_eq!(checked, ["cmm.seed", "loop.gain", "loop.smoothing"]);
}

#[test]
fn the_examples_validate() {
    validate(&CORRECT_JOB, &example("correct-mould.toml")).unwrap();
    validate(&SCENARIO_JOB, &example("correct-panel-loop.toml")).unwrap();
}

#[test]
fn the_docs_list_the_described_fields() {
    let path = root().join("docs/correction.md");
    let page = std::fs::read_to_string(&path).unwrap();
    let want = replace_marked(&page, &CORRECT_JOB).unwrap();
    let want = replace_marked(&want, &SCENARIO_JOB).unwrap();
    if want != page {
        if std::env::var_os("FORMCAM_BLESS").is_some() {
            std::fs::write(&path, want).unwrap();
        } else {
            panic!(
                "docs/correction.md: the field tables differ from the correction job's and the \
                 scenario's descriptions (formcam_correct::CORRECT_JOB, SCENARIO_JOB); \
                 regenerate them with `FORMCAM_BLESS=1 cargo test -p formcam-correct --test \
                 schema`"
            );
        }
    }
}
