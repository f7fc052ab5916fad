//! `candela`: render a scene from the command line.
//!
//! Minimal wiring of `candela bench ...` for now; the full command line
//! (CS184-compatible render flags) replaces this file.

mod bench;

use clap::{Parser, Subcommand};

/// Command line of the `candela` binary.
#[derive(Debug, Parser)]
#[command(name = "candela", about = "A physically based path tracer")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Benchmarks of the ray-intersection core.
    #[command(subcommand)]
    Bench(bench::BenchCommand),
}

fn main() -> std::process::ExitCode {
    let result = match Cli::parse().command {
        Command::Bench(cmd) => bench::run(cmd),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
