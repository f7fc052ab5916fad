//! `candela`: render a scene from the command line.
fn main() {}
