//! One description of each job type formcam reads: its tables and fields,
//! their types, units, ranges, defaults and help. The TOML readers validate
//! a job against it, `docs/` lists it, and the browser's job editor is drawn
//! from it, so the three never disagree.
