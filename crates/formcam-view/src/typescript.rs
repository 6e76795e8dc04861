//! The TypeScript types of the JSON the view sends: every `/api/` answer's
//! type and the report's inlined tables, declared by ts-rs from the Rust
//! types that are serialised (their fields, names, optional fields and
//! docs as serde writes them). The page imports them from
//! `viewer/src/generated/`, which holds these files as [`typescript`]
//! writes them (`tests/ts_types.rs` compares them; `FORMCAM_BLESS=1`
//! writes them again).

use ts_rs::{Config, TS};

use crate::band::Band;
use crate::correction::{
    CorrectionBody, DeviationMap, NodeCounts, NodeMarks, RoundMap, SectionStats, SurfaceMesh,
};
use crate::dressing::{DresserPass, DresserSample, DressingBody, MrrPlot};
use crate::folder::ResultKind;
use crate::overlay::{EyeTrajectory, Shown};
use crate::pathview::{PathBand, PathBody};
use crate::plots::{AxisPlots, MeridianPlot, PullPlot, WindingPlots};
use crate::report::{AxisTable, Knots, LaidTable, SampleTables};
use crate::scene::{LinkScene, MachineScene, MandrelScene, Solid, SolidShape};
use crate::server::{BlocksBody, KindBody, OverlaysBody, TimelineBody};
use crate::timeline::{AxisHead, Sample, TimelineHead};
use crate::violations::{AxisRange, Violations};

/// A generated TypeScript file of the page.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TsFile {
    /// Its name in `viewer/src/generated/`: `Sample.ts`, ..., `index.ts`.
    pub name: String,
    /// Its text.
    pub text: String,
}

/// The file of the index, which exports every type.
pub const TS_INDEX: &str = "index.ts";

/// Every type the view sends as JSON, a file each named after its Rust
/// type (`Sample.ts` declaring `Sample`, importing the types it uses),
/// by name, then [`TS_INDEX`] exporting them all.
///
/// # Errors
///
/// The name of a type ts-rs cannot declare (none of those listed).
pub fn typescript() -> Result<Vec<TsFile>, String> {
    let cfg = Config::new();
    let mut files = vec![
        // `/api/kind`, `/api/overlays`.
        file::<KindBody>(&cfg)?,
        file::<ResultKind>(&cfg)?,
        file::<OverlaysBody>(&cfg)?,
        // `/api/timeline`, `/api/sample`, `/api/blocks`.
        file::<TimelineBody>(&cfg)?,
        file::<TimelineHead>(&cfg)?,
        file::<AxisHead>(&cfg)?,
        file::<Shown>(&cfg)?,
        file::<Sample>(&cfg)?,
        file::<BlocksBody<'static>>(&cfg)?,
        // `/api/machine`, `/api/mandrel`.
        file::<MachineScene>(&cfg)?,
        file::<LinkScene>(&cfg)?,
        file::<Solid>(&cfg)?,
        file::<SolidShape>(&cfg)?,
        file::<MandrelScene>(&cfg)?,
        // `/api/violations`, `/api/eye`, `/api/band`.
        file::<Violations>(&cfg)?,
        file::<AxisRange>(&cfg)?,
        file::<EyeTrajectory>(&cfg)?,
        file::<Band>(&cfg)?,
        // `/api/plots`.
        file::<WindingPlots>(&cfg)?,
        file::<MeridianPlot>(&cfg)?,
        file::<PullPlot>(&cfg)?,
        file::<AxisPlots>(&cfg)?,
        // `/api/path`.
        file::<PathBody>(&cfg)?,
        file::<PathBand>(&cfg)?,
        // `/api/dressing`, `/api/dressing/sample`.
        file::<DressingBody>(&cfg)?,
        file::<DresserPass>(&cfg)?,
        file::<MrrPlot>(&cfg)?,
        file::<DresserSample>(&cfg)?,
        // `/api/correction`.
        file::<CorrectionBody>(&cfg)?,
        file::<DeviationMap>(&cfg)?,
        file::<RoundMap>(&cfg)?,
        file::<SectionStats>(&cfg)?,
        file::<SurfaceMesh>(&cfg)?,
        file::<NodeMarks>(&cfg)?,
        file::<NodeCounts>(&cfg)?,
        file::<formcam_correct::Placement>(&cfg)?,
        // The report's `report:samples`.
        file::<SampleTables>(&cfg)?,
        file::<AxisTable>(&cfg)?,
        file::<Knots>(&cfg)?,
        file::<LaidTable>(&cfg)?,
    ];
    files.sort_by(|a, b| a.name.cmp(&b.name));
    let mut index = String::from(
        "// Generated from formcam-view's types (crates/formcam-view/src/typescript.rs):\n\
         // `FORMCAM_BLESS=1 cargo test -p formcam-view --test ts_types` writes it again.\n\n",
    );
    for f in &files {
        let stem = f.name.trim_end_matches(".ts");
        index.push_str(&format!("export type {{ {stem} }} from './{stem}';\n"));
    }
    files.push(TsFile {
        name: TS_INDEX.to_string(),
        text: index,
    });
    Ok(files)
}

/// `T`'s file: ts-rs's declaration of it, with its imports, its lines'
/// trailing blanks taken off.
fn file<T: TS + 'static>(cfg: &Config) -> Result<TsFile, String> {
    let name = T::output_path()
        .and_then(|p| p.to_str().map(str::to_string))
        .ok_or_else(|| std::any::type_name::<T>().to_string())?;
    let text = T::export_to_string(cfg).map_err(|e| format!("{}: {e}", T::ident(cfg)))?;
    let mut trimmed = String::with_capacity(text.len());
    for line in text.lines() {
        trimmed.push_str(line.trim_end());
        trimmed.push('\n');
    }
    Ok(TsFile {
        name,
        text: trimmed,
    })
}
