//! Job tables: fields that do not apply are errors; implausible values warn.

#![allow(clippy::unwrap_used)]

use formcam_winding::job::{DomeKind, MandrelKind, MandrelSpec, WindingSpec};

fn none(_: &str) -> Result<String, String> {
    Err("no files".into())
}

fn vessel(radius: f64, opening: f64) -> MandrelSpec {
    MandrelSpec {
        kind: Some(MandrelKind::Vessel),
        radius: Some(radius),
        cylinder_length: Some(300.0),
        dome: Some(DomeKind::Hemisphere),
        polar_opening: Some(opening),
        ..MandrelSpec::default()
    }
}

fn band(width: f64) -> WindingSpec {
    WindingSpec {
        band_width: Some(width),
        band_thickness: Some(0.5),
        ..WindingSpec::default()
    }
}

#[test]
fn a_winding_angle_on_a_vessel_is_an_error() {
    let m = vessel(100.0, 30.0).build(none).unwrap();
    assert!(band(10.0).layer_spec(&m).is_ok());
    let with_angle = WindingSpec {
        winding_angle_deg: Some(30.0),
        ..band(10.0)
    };
    let e = with_angle.layer_spec(&m).unwrap_err().to_string();
    assert!(
        e.contains("winding.winding_angle_deg") && e.contains("vessel"),
        "{e}"
    );
}

#[test]
fn implausible_radii_and_bands_warn() {
    assert!(vessel(100.0, 30.0).warnings().is_empty());
    let w = vessel(0.1, 0.03).warnings();
    assert_eq!(w.len(), 1);
    assert!(w[0].starts_with("mandrel.radius") && w[0].contains("metres?"));
    let cone = MandrelSpec {
        kind: Some(MandrelKind::Cone),
        radius_start: Some(0.06),
        radius_end: Some(0.04),
        length: Some(0.3),
        ..MandrelSpec::default()
    };
    assert_eq!(cone.warnings().len(), 2);

    // Half the circumference of a 10 mm opening: 31.4 mm.
    let m = vessel(100.0, 10.0).build(none).unwrap();
    assert!(band(31.0).warnings(&m).is_empty());
    let w = band(32.0).warnings(&m);
    assert_eq!(w.len(), 1);
    assert!(w[0].starts_with("winding.band_width"), "{w:?}");
    // Tubes have no openings.
    let tube = MandrelSpec {
        kind: Some(MandrelKind::Cylinder),
        radius: Some(50.0),
        length: Some(100.0),
        ..MandrelSpec::default()
    }
    .build(none)
    .unwrap();
    assert!(band(500.0).warnings(&tube).is_empty());
}
