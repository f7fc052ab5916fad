//! `candela`: render a scene from the command line.
//!
//! Exit codes: 0 success, 1 a failure while rendering or writing, 2 bad
//! input (unknown flag, unreadable or malformed scene), 130 stopped by
//! Ctrl-C (the partial image was written).

mod args;
mod bench;
mod compare;
mod dask;
mod merge_cmd;
mod progress;
mod render_cmd;
mod report;
mod resume_cmd;
mod view_cmd;

use std::process::ExitCode;

fn main() -> ExitCode {
    let (cli, matches) = args::parse();
    if matches!(
        cli.command,
        Some(args::Command::Bench(_) | args::Command::Compare(_))
    ) {
        exit_quietly_on_closed_pipe();
    }
    let result = match cli.command {
        Some(args::Command::Bench(cmd)) => bench::run(cmd).map(|()| render_cmd::Outcome::Done),
        Some(args::Command::Compare(cmd)) => compare::run(&cmd).map(|()| render_cmd::Outcome::Done),
        Some(args::Command::Merge(cmd)) => merge_cmd::run(&cmd).map(|()| render_cmd::Outcome::Done),
        Some(args::Command::View(cmd)) => {
            view_cmd::run(&cmd, &matches).map(|()| render_cmd::Outcome::Done)
        }
        Some(args::Command::Resume(cmd)) => resume_cmd::run(&cmd),
        None => match &cli.render.dask {
            Some(address) => dask::run(&cli.render, &matches, address),
            None => render_cmd::run(&cli.render, &matches),
        },
    };
    match result {
        Ok(render_cmd::Outcome::Done) => ExitCode::SUCCESS,
        Ok(render_cmd::Outcome::Interrupted) => ExitCode::from(render_cmd::INTERRUPTED),
        Err(err) => {
            eprintln!("candela: error: {}", one_line(&err));
            ExitCode::from(exit_code(&err))
        }
    }
}

/// Benchmark and comparison tables are often piped into `head`: when the
/// reader closes the pipe, end quietly as other command-line tools do
/// instead of panicking in `println!`. Only for those commands: the
/// viewer's sockets must never kill its server.
fn exit_quietly_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any thread exists; SIG_DFL
    // is a valid disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// The error and its causes on one line, skipping causes whose text the
/// message already carries (library errors often print their source too).
fn one_line(err: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

/// Bad input exits with 2, anything else with 1. A scene that loads but
/// cannot be built (a camera that cannot be placed, an unreadable
/// environment map, inconsistent geometry) is bad input too: every
/// [`candela_render::scene::SceneError`] comes from the description.
fn exit_code(err: &anyhow::Error) -> u8 {
    let bad_input = err.chain().any(|cause| {
        cause.is::<candela_scene::LoadError>()
            || cause.is::<render_cmd::UsageError>()
            || cause.is::<candela_render::scene::SceneError>()
    });
    if bad_input {
        2
    } else {
        1
    }
}
