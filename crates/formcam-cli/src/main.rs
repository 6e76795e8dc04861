//! The `formcam` command line.
fn main() {}
