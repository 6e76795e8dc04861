//! The two 10^5-block cases the benches and the `check_1e5` example time:
//! the demo's 840D vessel program repeated with its mandrel (collisions),
//! and a many-layer helical job (snag).

use std::path::Path;

use formcam_machine::Machine;
use formcam_nc::Program;
use formcam_program::{Stage, WindJob, plan_until, write_program};
use formcam_sim::{Collisions, FeedRule, FreeFibre, Timeline, program_axes, read_program};

/// The collision case: the machine, the repeated program, its timeline and
/// the collision check with the job's mandrel.
pub struct VesselCase {
    /// The job's machine.
    pub machine: Machine,
    /// The program, 10^5 blocks.
    pub program: Program,
    /// Its line numbers.
    pub lines: Vec<usize>,
    /// Its timeline by the 840D rule.
    pub timeline: Timeline,
    /// The collisions with the job's mandrel and laminate.
    pub collisions: Collisions,
}

/// The demo's 840D vessel program (its eye passes over the domes inside
/// the mandrel's box, so the exact distance runs there), repeated to `n`
/// blocks with the spindle carried on; its mandrel from the job.
pub fn vessel(n: usize) -> VesselCase {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let job_path = examples.join("vessel-program-840d.toml");
    let job = WindJob::from_toml(&std::fs::read_to_string(&job_path).unwrap(), &examples).unwrap();
    let m = job.machine.as_ref().unwrap().machine.clone();
    let planned = plan_until(&job, Stage::Program).unwrap();
    let mut text = Vec::new();
    write_program(&planned, &mut text).unwrap();
    let text = String::from_utf8(text).unwrap();
    let (one, _, _) = read_program(Path::new("program.mpf"), &text, &m).unwrap();
    let spindle = m.axis("A").unwrap();
    let turn = one.blocks.last().unwrap().target[spindle];
    let mut p = Program::new("VESSEL", program_axes(&m));
    let mut copy = 0.0;
    while p.blocks.len() < n {
        for b in one.blocks.iter().take(n - p.blocks.len()) {
            let mut b = b.clone();
            b.target[spindle] += copy * turn;
            p.blocks.push(b);
        }
        copy += 1.0;
    }
    let lines: Vec<usize> = (1..=n).collect();
    let laminate = formcam_program::laminate_of_job(&job).unwrap();
    let stages = laminate.stage_of_blocks(
        formcam_nc::Dialect::Sinumerik840d,
        p.blocks.iter().map(|b| b.comment.as_deref()),
    );
    let collisions = Collisions::with_mandrel(&m, None, &laminate, stages).unwrap();
    let timeline = Timeline::new(&p, &lines, FeedRule::Sinumerik840d, &m).unwrap();
    VesselCase {
        machine: m,
        program: p,
        lines,
        timeline,
        collisions,
    }
}

/// The job: `layers` geodesic helical layers on the example vessel, tight
/// block tolerances.
fn helical_job(layers: usize) -> WindJob {
    let mut text = String::from(
        "[mandrel]\nkind = \"vessel\"\nradius = 100.0\ncylinder_length = 300.0\n\
         dome = \"hemisphere\"\npolar_opening = 30.0\n\n",
    );
    for _ in 0..layers {
        text.push_str("[[layer]]\nband_width = 10.0\nband_thickness = 0.5\n\n");
    }
    text.push_str(
        "[eye]\nmode = \"axis-parallel\"\nradius = 160.0\nclearance = 20.0\nl_max = 600.0\n\n\
         [machine]\nname = \"winder-4axis\"\n\n\
         [motion]\ntolerance_mm = 0.002\ntolerance_deg = 0.002\n\n\
         [checks]\nallow = [\"slack\", \"clearance\", \"l_max\", \"reverse-rotation\"]\n\n\
         [post]\ndialect = \"sinumerik-840d\"\n",
    );
    WindJob::from_toml(&text, Path::new(".")).unwrap()
}

/// The snag case: enough helical layers for `n` blocks, planned once,
/// written, read back; its timeline, free fibre and layer count.
pub fn helical(n: usize) -> (Timeline, FreeFibre, usize) {
    let one = plan_until(&helical_job(1), Stage::Program).unwrap();
    let per_layer = one.program.as_ref().unwrap().program.blocks.len();
    let layers = n.div_ceil(per_layer).max(1);
    let wound = plan_until(&helical_job(layers), Stage::Program).unwrap();
    let mut bytes = Vec::new();
    write_program(&wound, &mut bytes).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    let m = wound.machine.clone().unwrap();
    let (p, lines, d) = read_program(Path::new("program.mpf"), &text, &m).unwrap();
    let tl = Timeline::new(&p, &lines, FeedRule::of(d), &m).unwrap();
    let fibre = formcam_program::free_fibre(&wound).unwrap();
    (tl, fibre, layers)
}
