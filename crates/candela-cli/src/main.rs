//! `candela`: render a scene from the command line.
//!
//! Exit codes: 0 success, 1 a failure while rendering or writing, 2 bad
//! input (unknown flag, unreadable or malformed scene).

mod args;
mod bench;
mod progress;
mod render_cmd;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = args::Cli::parse();
    let result = match cli.command {
        Some(args::Command::Bench(cmd)) => bench::run(cmd),
        None => render_cmd::run(&cli.render),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("candela: error: {err:#}");
            ExitCode::from(exit_code(&err))
        }
    }
}

/// Bad input exits with 2, anything else with 1.
fn exit_code(err: &anyhow::Error) -> u8 {
    let bad_input = err.chain().any(|cause| {
        cause.is::<candela_scene::LoadError>() || cause.is::<render_cmd::UsageError>()
    });
    if bad_input {
        2
    } else {
        1
    }
}
