//! Golden programs: each dialect and the example template on a small program.

#![allow(clippy::unwrap_used)]

mod common;

use formcam_nc::{Dialect, Template, write, write_template};

fn written(dialect: Dialect) -> String {
    let p = match dialect {
        Dialect::MarlinXab => common::xab(),
        _ => common::xayb(),
    };
    let mut out = String::new();
    write(&p, dialect, &mut out).unwrap();
    out
}

#[test]
fn cldata() {
    insta::assert_snapshot!(written(Dialect::Cldata));
}

#[test]
fn sinumerik_840d() {
    insta::assert_snapshot!(written(Dialect::Sinumerik840d));
}

#[test]
fn iso() {
    insta::assert_snapshot!(written(Dialect::Iso));
}

#[test]
fn linuxcnc() {
    insta::assert_snapshot!(written(Dialect::LinuxCnc));
}

#[test]
fn marlin_xab() {
    insta::assert_snapshot!(written(Dialect::MarlinXab));
}

#[test]
fn example_template() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/example.post.toml");
    let t = Template::load(&path).unwrap();
    assert_eq!(t.extension(), "h");
    let mut out = String::new();
    write_template(&common::xayb(), &t, &mut out).unwrap();
    insta::assert_snapshot!(out);
}

#[test]
fn template_axis_placeholders_and_escapes() {
    let t = Template::from_toml(
        r#"
extension = "txt"
header = "{{{name}}}"
block = "MOVE X={X} A={A} B={B} F={f} T={t} FI={fi} ({comment})"
rapid = "RAPID {axes}"
footer = "END"
decimals_mm = 2
decimals_deg = 1
modal_axes = false
axis_letters = { X = "X", A = "A", B = "B", Y = "Q" }
"#,
    )
    .unwrap();
    let mut out = String::new();
    write_template(&common::xayb(), &t, &mut out).unwrap();
    insta::assert_snapshot!(out);
}

#[test]
fn extensions() {
    let ext: Vec<&str> = Dialect::ALL.iter().map(|d| d.extension()).collect();
    assert_eq!(ext, ["cls", "mpf", "nc", "ngc", "gcode"]);
    for (d, n) in Dialect::ALL.iter().zip(Dialect::NAMES) {
        assert_eq!(Dialect::from_name(n).unwrap(), *d);
        assert_eq!(d.to_string(), n);
    }
}
