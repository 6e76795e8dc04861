//! Machine files: forward kinematics of a known chain and one-line errors.

#![allow(clippy::unwrap_used)]

use formcam_machine::{Machine, MachineError};

const HEAD: &str = r#"
[machine]
name = "test"
kind = "winder"
mandrel = "base"
payout = "tip"
"#;

fn with_links(links: &str) -> Result<Machine, MachineError> {
    Machine::from_toml(&format!(
        "{HEAD}\n{links}\n[[point]]\nname = \"tip\"\nlink = \"base\"\n"
    ))
}

fn error(links: &str) -> String {
    let e = with_links(links).unwrap_err().to_string();
    assert!(!e.contains('\n'), "one line: {e}");
    e
}

#[test]
fn a_planar_dh_arm_matches_its_closed_form() {
    // Two revolute links of 300 and 200 mm in the xy plane.
    let m = Machine::from_toml(
        r#"
[machine]
name = "planar"
kind = "winder"
mandrel = "base"
payout = "tip"

[[link]]
name = "base"

[[link]]
name = "l1"
parent = "base"
joint = "revolute"
driven = true
axis = "A"
dh = { a = 300.0 }

[[link]]
name = "l2"
parent = "l1"
joint = "revolute"
driven = true
axis = "B"
dh = { a = 200.0, d = 10.0 }

[[point]]
name = "tip"
link = "l2"
"#,
    )
    .unwrap();
    for (a, b) in [(0.3, -1.1), (2.0, 0.7), (-2.5, 3.0)] {
        let p = m.key_points(&[a, b])[0];
        let x = 300.0 * f64::cos(a) + 200.0 * f64::cos(a + b);
        let y = 300.0 * f64::sin(a) + 200.0 * f64::sin(a + b);
        assert!((p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9 && (p.z - 10.0).abs() < 1e-9);
    }
    assert!(m.table().contains("revolute"));
}

#[test]
fn a_prismatic_joint_with_an_origin_slides_along_its_direction() {
    let m = with_links(
        r#"
[[link]]
name = "base"
[[link]]
name = "slide"
parent = "base"
joint = "prismatic"
driven = true
axis = "X"
origin = { xyz = [1.0, 2.0, 3.0], rpy_deg = [0.0, 0.0, 90.0] }
direction = [1.0, 0.0, 0.0]
min_mm = -10.0
max_mm = 10.0
"#,
    )
    .unwrap();
    let poses = m.poses(&[5.0]);
    let p = poses[1].translation.vector;
    // The origin turns x onto y: the slide moves along world y.
    assert!((p.x - 1.0).abs() < 1e-12 && (p.y - 7.0).abs() < 1e-12 && (p.z - 3.0).abs() < 1e-12);
}

#[test]
fn bad_files_give_one_line_errors_naming_the_place_and_field() {
    let base = "[[link]]\nname = \"base\"\n";
    let cases = [
        (
            format!(
                "{base}[[link]]\nname = \"a\"\nparent = \"b\"\n[[link]]\nname = \"b\"\nparent = \"a\"\n"
            ),
            "cycle",
        ),
        (
            format!("{base}[[link]]\nname = \"a\"\nparent = \"nowhere\"\n"),
            "link \"a\": parent: no link is named \"nowhere\"",
        ),
        (
            format!(
                "{base}[[link]]\nname = \"a\"\nparent = \"base\"\njoint = \"prismatic\"\ndriven = true\naxis = \"X\"\n\
                 [[link]]\nname = \"b\"\nparent = \"a\"\njoint = \"revolute\"\ndriven = true\naxis = \"X\"\n"
            ),
            "link \"b\": axis: \"X\" drives two joints",
        ),
        (
            format!(
                "{base}[[link]]\nname = \"a\"\nparent = \"base\"\njoint = \"prismatic\"\ndriven = true\naxis = \"X\"\nmin_mm = 5.0\nmax_mm = 2.0\n"
            ),
            "link \"a\": min_mm: 5 > max_mm = 2",
        ),
        (
            format!("{base}[[link]]\nname = \"a\"\nparent = \"base\"\njoint = \"spherical\"\n"),
            "unknown variant `spherical`",
        ),
        (
            format!(
                "{base}[[link]]\nname = \"a\"\nparent = \"base\"\njoint = \"revolute\"\ndriven = true\naxis = \"A\"\nmin_mm = 0.0\n"
            ),
            "link \"a\": min_mm: a revolute joint takes degrees",
        ),
        (
            format!("{base}[[link]]\nname = \"a\"\njoint = \"revolute\"\n"),
            "link \"a\": parent: missing",
        ),
        (
            format!(
                "{base}[[link]]\nname = \"a\"\nparent = \"base\"\njoint = \"revolute\"\ndriven = true\n"
            ),
            "link \"a\": axis: missing",
        ),
        (
            format!("{base}[[link]]\nname = \"base\"\n"),
            "link \"base\": name: used by two links",
        ),
        (
            format!("{base}[[link.visual]]\nshape = \"cone\"\n"),
            "link \"base\": visual.shape: unknown shape \"cone\"",
        ),
    ];
    for (links, want) in cases {
        let e = error(&links);
        assert!(e.contains(want), "want \"{want}\" in \"{e}\"");
    }
    // The [machine] table's references.
    let e = Machine::from_toml(&HEAD.replace("\"tip\"", "\"nothing\"")).unwrap_err();
    assert!(e.to_string().contains("link"), "{e}");
    let text = format!(
        "{}\n{base}[[point]]\nname = \"tip\"\nlink = \"base\"\n",
        HEAD.replace("payout = \"tip\"", "payout = \"eye\"")
    );
    let e = Machine::from_toml(&text).unwrap_err().to_string();
    assert!(
        e.contains("[machine]: payout: no point is named \"eye\""),
        "{e}"
    );
    // Syntax errors carry the line.
    let e = Machine::from_toml("[machine]\nname = 3\n").unwrap_err();
    assert!(matches!(e, MachineError::Syntax { line: 2, .. }), "{e:?}");
}

#[test]
fn the_spindle_turns_modulo_by_default_and_modulo_is_checked() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../machines");
    for name in ["winder-2axis", "winder-4axis", "winder-6axis", "winder-xab"] {
        let text = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        let m = Machine::from_toml(&text).unwrap();
        let s = m.roles.spindle.unwrap();
        for (i, a) in m.axes.iter().enumerate() {
            assert_eq!(a.modulo, i == s, "{name}: axis {}", a.name);
        }
    }
    let spindle = |extra: &str| {
        format!(
            "[[link]]\nname = \"base\"\n[[link]]\nname = \"s\"\nparent = \"base\"\n\
             joint = \"revolute\"\ndriven = true\naxis = \"A\"\n{extra}\n"
        )
    };
    let with_spindle = |extra: &str| {
        Machine::from_toml(&format!(
            "{}spindle = \"A\"\n{}\n[[point]]\nname = \"tip\"\nlink = \"base\"\n",
            HEAD,
            spindle(extra)
        ))
    };
    assert!(with_spindle("").unwrap().axes[0].modulo);
    assert!(!with_spindle("modulo = false").unwrap().axes[0].modulo);
    // A spindle with limits is not modulo by default, and cannot be.
    assert!(
        !with_spindle("min_deg = -720.0\nmax_deg = 720.0")
            .unwrap()
            .axes[0]
            .modulo
    );
    let e = with_spindle("max_deg = 720.0\nmodulo = true")
        .unwrap_err()
        .to_string();
    assert!(e.contains("link \"s\"") && e.contains("modulo"), "{e}");
    // Other axes are modulo only when the file says so.
    assert!(!with_links(&spindle("")).unwrap().axes[0].modulo);
    assert!(with_links(&spindle("modulo = true")).unwrap().axes[0].modulo);
    let e = error(
        "[[link]]\nname = \"base\"\n[[link]]\nname = \"x\"\nparent = \"base\"\n\
         joint = \"prismatic\"\ndriven = true\naxis = \"X\"\nmodulo = true\n",
    );
    assert!(e.contains("link \"x\"") && e.contains("modulo"), "{e}");
    let e = error(
        "[[link]]\nname = \"base\"\n[[link]]\nname = \"r\"\nparent = \"base\"\n\
         joint = \"revolute\"\nmodulo = true\n",
    );
    assert!(e.contains("link \"r\"") && e.contains("modulo"), "{e}");
}

/// The message after `line:column: ` of a machine file's TOML error.
fn syntax_message(text: &str) -> String {
    let e = Machine::from_toml(text).unwrap_err();
    assert!(matches!(e, MachineError::Syntax { .. }), "{e}");
    let shown = e.to_string();
    let said = shown.splitn(3, ':').nth(2).unwrap_or_default().trim();
    assert!(!said.is_empty(), "an empty message: {shown:?}");
    assert!(!shown.chars().any(char::is_control), "{shown:?}");
    said.to_string()
}

#[test]
fn a_machine_cut_after_its_equals_sign_says_a_value_is_expected() {
    let text = include_str!("../../../machines/winder-2axis.toml");
    let at = text.find("kind = ").unwrap() + "kind =".len();
    let said = syntax_message(&text[..at]);
    assert!(said.contains("expected"), "{said}");
    let rest = &text[at..];
    let blanked = format!("{}{}", &text[..at], &rest[rest.find('\n').unwrap()..]);
    let said = syntax_message(&blanked);
    assert!(said.contains("expected"), "{said}");
}

#[test]
fn a_machine_with_a_nul_says_nul_is_not_allowed() {
    let text = include_str!("../../../machines/winder-2axis.toml");
    let said = syntax_message(&text.replacen("kind = \"winder\"", "kind = \"winder\"\0", 1));
    assert!(said.contains("NUL"), "{said}");
}
