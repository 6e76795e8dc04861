//! Job tables: mandrels grown by the layers laid on them.

#![allow(clippy::unwrap_used)]

use formcam_geom::Meridian;
use formcam_winding::job::{DomeKind, LayerKind, MandrelKind, MandrelSpec, WindingSpec};

#[test]
fn grown_mandrels_are_wider_by_the_thickness() {
    let none = |_: &str| -> Result<String, String> { Err("no files".into()) };
    let cyl = MandrelSpec {
        kind: Some(MandrelKind::Cylinder),
        radius: Some(50.0),
        length: Some(100.0),
        ..MandrelSpec::default()
    };
    let g = cyl.grown(1.5).unwrap().build(none).unwrap();
    assert!((g.r(10.0) - 51.5).abs() < 1e-12);
    let vessel = MandrelSpec {
        kind: Some(MandrelKind::Vessel),
        radius: Some(100.0),
        cylinder_length: Some(300.0),
        dome: Some(DomeKind::Hemisphere),
        polar_opening: Some(30.0),
        ..MandrelSpec::default()
    };
    let v0 = vessel.build(none).unwrap();
    let v1 = vessel.grown(2.0).unwrap().build(none).unwrap();
    let mid0 = 0.5 * (v0.z_range().0 + v0.z_range().1);
    let mid1 = 0.5 * (v1.z_range().0 + v1.z_range().1);
    assert!((v1.r(mid1) - v0.r(mid0) - 2.0).abs() < 1e-12);
    // The openings stay.
    assert!((v1.r(v1.z_range().0) - 30.0).abs() < 1e-9);
    // A profile's r grows at every z (the spline interpolates its nodes).
    let table = "z,r\n0,40\n50,45\n100,52\n150,60\n200,60\n";
    let read = |_: &str| -> Result<String, String> { Ok(table.into()) };
    let profile = MandrelSpec {
        kind: Some(MandrelKind::Profile),
        file: Some("p.csv".into()),
        ..MandrelSpec::default()
    };
    let p0 = profile.build(read).unwrap();
    let p1 = profile
        .grown(0.8)
        .unwrap()
        .grown(0.7)
        .unwrap()
        .build(read)
        .unwrap();
    for z in [0.0, 50.0, 100.0, 150.0, 200.0] {
        assert!((p1.r(z) - p0.r(z) - 1.5).abs() < 1e-9, "z = {z}");
    }
}

/// A layer's `kind` is read as a `LayerKind` under its name; another word is
/// refused as the table is read, naming the allowed ones; a skip layer is not
/// something `layer_spec` plans.
#[test]
fn layer_kinds_are_read_by_name() {
    for kind in [LayerKind::Helical, LayerKind::Hoop, LayerKind::Skip] {
        let w: WindingSpec = toml::from_str(&format!("kind = \"{kind}\"")).unwrap();
        assert_eq!(w.kind, Some(kind));
    }
    let none: WindingSpec = toml::from_str("band_width = 6.0").unwrap();
    assert_eq!(none.kind.unwrap_or_default(), LayerKind::Helical);
    let e = toml::from_str::<WindingSpec>("kind = \"spiral\"")
        .unwrap_err()
        .to_string();
    for allowed in ["kind", "spiral", "helical", "hoop", "skip"] {
        assert!(e.contains(allowed), "{e}");
    }
    let none = |_: &str| -> Result<String, String> { Err("no files".into()) };
    let cyl = MandrelSpec {
        kind: Some(MandrelKind::Cylinder),
        radius: Some(50.0),
        length: Some(100.0),
        ..MandrelSpec::default()
    }
    .build(none)
    .unwrap();
    let skip = WindingSpec {
        kind: Some(LayerKind::Skip),
        band_width: Some(6.0),
        band_thickness: Some(0.25),
        winding_angle_deg: Some(45.0),
        ..WindingSpec::default()
    };
    assert_eq!(
        skip.layer_spec(&cyl).unwrap_err().to_string(),
        "winding.kind: \"skip\" is not a layer kind here (helical or hoop)"
    );
}
