//! The workspace's layers hold: every crate is in ARCHITECTURE.md's layer
//! table, and `cargo metadata` shows no dependency on a crate of the same
//! or a higher layer (normal and build dependencies), and no test or bench
//! using a crate that depends on the crate under test.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

use serde_json::Value;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// ARCHITECTURE.md's `## Layers` table: crate name -> layer.
fn layer_table() -> BTreeMap<String, u32> {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let section = text
        .split("\n## Layers\n")
        .nth(1)
        .expect("ARCHITECTURE.md has a `## Layers` section");
    let mut out = BTreeMap::new();
    for line in section.lines().skip_while(|l| !l.starts_with('|')) {
        if !line.starts_with('|') {
            break;
        }
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let Ok(layer) = cells[1].parse::<u32>() else {
            continue;
        };
        for name in cells[2].split(',') {
            let name = name.trim().trim_matches('`').to_string();
            assert!(
                out.insert(name.clone(), layer).is_none(),
                "{name} is in two layers"
            );
        }
    }
    out
}

/// The workspace's crates and their dependencies on one another:
/// (crate, dependency, kind) with kind `normal`, `build` or `dev`.
fn workspace_arrows() -> (BTreeSet<String>, Vec<(String, String, String)>) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .current_dir(root())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let meta: Value = serde_json::from_slice(&out.stdout).unwrap();
    let packages = meta["packages"].as_array().unwrap();
    let names: BTreeSet<String> = packages
        .iter()
        .map(|p| p["name"].as_str().unwrap().to_string())
        .collect();
    let mut arrows = Vec::new();
    for p in packages {
        let from = p["name"].as_str().unwrap();
        for d in p["dependencies"].as_array().unwrap() {
            let to = d["name"].as_str().unwrap();
            if names.contains(to) {
                let kind = d["kind"].as_str().unwrap_or("normal");
                arrows.push((from.to_string(), to.to_string(), kind.to_string()));
            }
        }
    }
    (names, arrows)
}

/// Whether `from` depends on `to` through normal and build dependencies.
fn reaches(arrows: &[(String, String, String)], from: &str, to: &str) -> bool {
    let mut todo = vec![from.to_string()];
    let mut seen = BTreeSet::new();
    while let Some(c) = todo.pop() {
        if c == to {
            return true;
        }
        if !seen.insert(c.clone()) {
            continue;
        }
        todo.extend(
            arrows
                .iter()
                .filter(|(f, _, k)| *f == c && k != "dev")
                .map(|(_, t, _)| t.clone()),
        );
    }
    false
}

#[test]
fn every_crate_has_a_layer_and_depends_only_on_lower_layers() {
    let layers = layer_table();
    let (names, arrows) = workspace_arrows();
    let listed: BTreeSet<String> = layers.keys().cloned().collect();
    assert_eq!(
        names, listed,
        "ARCHITECTURE.md's layer table lists exactly the workspace's crates"
    );
    let mut wrong = Vec::new();
    for (from, to, kind) in &arrows {
        let ok = if kind == "dev" {
            !reaches(&arrows, to, from)
        } else {
            layers[to] < layers[from]
        };
        if !ok {
            wrong.push(format!(
                "{from} (layer {}) -> {to} (layer {}) [{kind}]",
                layers[from], layers[to]
            ));
        }
    }
    assert!(
        wrong.is_empty(),
        "dependencies against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_table_reader_finds_every_layer() {
    let layers = layer_table();
    assert_eq!(layers.get("formcam-files"), Some(&0));
    assert_eq!(
        layers.get("formcam-cli").copied(),
        layers.values().max().copied()
    );
    assert!(layers.len() >= 17);
}
