//! The docs list the columns the descriptions give: each `<!-- columns: ID
//! -->` section of `docs/winding.md`, `docs/dressing.md` and
//! `docs/correction.md` is the table's Markdown (`FORMCAM_BLESS=1`
//! rewrites them).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

use formcam_results::{TABLES, Table, correction, dressing, replace_marked, winding};

fn check(page: &str, tables: &[Table]) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs")
        .join(page);
    let text = std::fs::read_to_string(&path).unwrap();
    let want = replace_marked(&text, tables).unwrap();
    if want != text {
        if std::env::var_os("FORMCAM_BLESS").is_some() {
            std::fs::write(&path, want).unwrap();
        } else {
            panic!(
                "docs/{page}: the column tables differ from formcam-results' descriptions; \
                 regenerate them with `FORMCAM_BLESS=1 cargo test -p formcam-results --test docs`"
            );
        }
    }
}

#[test]
fn the_docs_list_the_described_columns() {
    let of = |prefix: &str| -> Vec<Table> {
        TABLES
            .iter()
            .filter(|t| t.id.starts_with(prefix))
            .copied()
            .collect()
    };
    check("winding.md", &of("winding."));
    check("dressing.md", &of("dressing."));
    check("correction.md", &of("correction."));
}

#[test]
fn every_table_is_listed_once_and_shared_ids_share_columns() {
    for t in TABLES {
        assert_eq!(TABLES.iter().filter(|u| *u == t).count(), 1, "{}", t.file);
        for u in TABLES.iter().filter(|u| u.id == t.id) {
            assert_eq!(
                t.columns, u.columns,
                "{} and {} share {}",
                t.file, u.file, t.id
            );
        }
        let mut names: Vec<&str> = t.columns.iter().map(|c| c.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), t.columns.len(), "{}: a column twice", t.file);
    }
    assert_eq!(winding::BLOCKS.file, "blocks.csv");
    assert_eq!(dressing::MRR.column("steady"), Some(&dressing::mrr::STEADY));
    assert_eq!(
        correction::PREDICTED
            .header_with(&[], false)
            .matches(',')
            .count(),
        7
    );
}
