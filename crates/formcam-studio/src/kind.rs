//! The four kinds of job the studio edits, each with its one description
//! (`formcam-schema`), told apart by a job's top-level tables as
//! `formcam-run` tells them.

use std::fmt;

use formcam_correct::{CORRECT_JOB, CorrectionJob, SCENARIO_JOB, ScenarioJob};
use formcam_dress::DRESS_JOB;
use formcam_program::WINDING_JOB;
use formcam_run::JobKind;
use formcam_schema::JobSchema;
use serde::{Deserialize, Serialize};

/// A kind of job the studio edits and runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StudioKind {
    /// A winding job (`[mandrel]`, `[winding]` or `[[layer]]`, ...).
    Winding,
    /// A wheel dressing job (`[wheel]`).
    Dressing,
    /// A mould correction job (`[correct]`).
    Correction,
    /// A closed-loop correction scenario (`[surface]` and `[warp]`).
    Scenario,
}

impl StudioKind {
    /// Every kind, in the order the studio lists them.
    pub const ALL: [StudioKind; 4] = [
        StudioKind::Winding,
        StudioKind::Dressing,
        StudioKind::Correction,
        StudioKind::Scenario,
    ];

    /// The kind's name as JSON and the page write it (`winding`, ...).
    pub fn name(self) -> &'static str {
        match self {
            StudioKind::Winding => "winding",
            StudioKind::Dressing => "dressing",
            StudioKind::Correction => "correction",
            StudioKind::Scenario => "scenario",
        }
    }

    /// The kind named `name` (as [`StudioKind::name`] writes it).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The description of this kind's job file: the one the process crate
    /// validates against and the form is drawn from.
    pub fn schema(self) -> &'static JobSchema {
        match self {
            StudioKind::Winding => &WINDING_JOB,
            StudioKind::Dressing => &DRESS_JOB,
            StudioKind::Correction => &CORRECT_JOB,
            StudioKind::Scenario => &SCENARIO_JOB,
        }
    }

    /// The kind of the job whose text is `text`, by its top-level tables
    /// as `formcam-run`'s `JobKind::of` tells them (`[surface]` and
    /// `[warp]` a scenario, `[correct]`, `[wheel]`, else a winding job when
    /// it has a winding table); `None` for a text that is no TOML, has
    /// none of these tables, or is a machine file (its `[machine]` table is
    /// also a winding job's, its `[[link]]`s are no job's).
    pub fn of(text: &str) -> Option<Self> {
        let table = text.parse::<toml::Table>().ok()?;
        Self::of_tables(&table)
    }

    /// [`StudioKind::of`] for a job's top-level table already parsed.
    pub fn of_tables(table: &toml::Table) -> Option<Self> {
        if table.contains_key("link") {
            None
        } else if ScenarioJob::is_scenario(table) {
            Some(StudioKind::Scenario)
        } else if CorrectionJob::is_job(table) {
            Some(StudioKind::Correction)
        } else if formcam_run::is_dress_job(table) {
            Some(StudioKind::Dressing)
        } else if WINDING_JOB
            .tables
            .iter()
            .any(|t| table.contains_key(t.name))
        {
            Some(StudioKind::Winding)
        } else {
            None
        }
    }

    /// The run `formcam-run` gives a job of this kind.
    pub fn job_kind(self) -> JobKind {
        match self {
            StudioKind::Winding => JobKind::Winding,
            StudioKind::Dressing => JobKind::Dressing,
            StudioKind::Correction => JobKind::Correction,
            StudioKind::Scenario => JobKind::Scenario,
        }
    }
}

impl fmt::Display for StudioKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_by_their_tables_as_the_run_tells_them() {
        let cases = [
            (
                "[surface]\nkind = \"panel\"\n[warp]\n",
                Some(StudioKind::Scenario),
            ),
            ("[correct]\ngain = 1.0\n", Some(StudioKind::Correction)),
            ("[wheel]\nr1 = 1.0\n", Some(StudioKind::Dressing)),
            ("[mandrel]\nkind = \"vessel\"\n", Some(StudioKind::Winding)),
            ("[[layer]]\nkind = \"hoop\"\n", Some(StudioKind::Winding)),
            ("[other]\nx = 1\n", None),
            ("not = [toml", None),
        ];
        for (text, kind) in cases {
            assert_eq!(StudioKind::of(text), kind, "{text}");
            if let Some(k) = kind {
                let p = std::path::Path::new("job.toml");
                assert_eq!(JobKind::of(p, text), k.job_kind(), "{text}");
            }
        }
    }

    #[test]
    fn names_are_the_json_words_and_schemas_their_own() {
        for k in StudioKind::ALL {
            let json = serde_json::to_string(&k).expect("serialises");
            assert_eq!(json, format!("\"{}\"", k.name()));
            assert_eq!(StudioKind::from_name(k.name()), Some(k));
            let back: StudioKind = serde_json::from_str(&json).expect("reads back");
            assert_eq!(back, k);
            assert!(!k.schema().tables.is_empty());
        }
        assert_eq!(StudioKind::Dressing.schema().name, DRESS_JOB.name);
        assert_eq!(StudioKind::from_name("Winding"), None);
    }
}
