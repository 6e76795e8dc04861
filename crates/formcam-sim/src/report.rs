//! The report of a check (`report.json`) and its one-line verdict.

use serde::Serialize;

use crate::Violation;

/// What `formcam check` found: the program, its time and every violation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The program file, as given.
    pub program: String,
    /// The machine (file as given, or shipped name) and its name.
    pub machine: String,
    /// The dialect read (from the program's extension).
    pub dialect: &'static str,
    /// The feed rule its per-minute feeds were timed by.
    pub feed_rule: &'static str,
    /// The number of blocks.
    pub blocks: usize,
    /// The program's time, s.
    pub duration_s: f64,
    /// Whether no check failed.
    pub clean: bool,
    /// Every broken limit, one per kind and axis, in the order they first
    /// happen.
    pub violations: Vec<Violation>,
}

impl Report {
    /// The verdict in one line: `clean: N blocks, T s`, or `K violations:
    /// <kind> at block b (line l, t s): ...`, the violation that happens
    /// first, told where it is worst ([`Violation`]'s display).
    pub fn line(&self) -> String {
        match self.violations.first() {
            None => format!("clean: {} blocks, {:.3} s", self.blocks, self.duration_s),
            Some(first) => {
                let k = self.violations.len();
                let s = if k == 1 { "" } else { "s" };
                format!("{k} violation{s}: {first}")
            }
        }
    }
}
