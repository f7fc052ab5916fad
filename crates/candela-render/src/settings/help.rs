//! The help text, flag and choices of every setting, by its JSON name:
//! read from the clap description derived from [`Settings`] (so each is
//! written once, in the fields' doc comments and attributes). The CLI's
//! `--help`, Python's `candela.settings_help()`, the viewer's side panel
//! and its "copy command line" all read it.

use super::{Settings, ADAPTIVE_HELP, CELL_HELP};
use clap::Args;
use serde::Serialize;

/// One setting as the command line spells it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct SettingFlag {
    /// The JSON name (Python keyword, wire format).
    pub name: String,
    /// The long flag without dashes, if the command line has one (`cell`
    /// and `adaptive` are spelled `-p X Y DX DY` and `-a BATCH TOL`).
    pub long: Option<String>,
    /// The help text.
    pub help: String,
    /// The accepted values of a setting with a fixed set of them.
    pub choices: Vec<String>,
    /// The value must be written `--flag=value` (a flag whose value is
    /// optional, such as `--denoise`).
    pub require_equals: bool,
}

/// Every setting's flag, in the order of `candela --help`, then the two
/// only the CS184 spellings reach.
pub fn flags() -> Vec<SettingFlag> {
    let cmd = Settings::augment_args(clap::Command::new("candela"));
    let mut flags: Vec<SettingFlag> = cmd
        .get_arguments()
        .map(|a| SettingFlag {
            name: a.get_id().to_string(),
            long: a.get_long().map(str::to_string),
            help: a.get_help().map(|h| h.to_string()).unwrap_or_default(),
            choices: a
                .get_possible_values()
                .iter()
                .map(|v| v.get_name().to_string())
                .collect(),
            require_equals: a.is_require_equals_set(),
        })
        .collect();
    for (name, help) in [("cell", CELL_HELP), ("adaptive", ADAPTIVE_HELP)] {
        flags.push(SettingFlag {
            name: name.into(),
            long: None,
            help: help.into(),
            choices: Vec::new(),
            require_equals: false,
        });
    }
    flags
}

/// `(name, help)` of every setting: [`flags`] without the flags.
pub fn help() -> Vec<(String, String)> {
    flags().into_iter().map(|f| (f.name, f.help)).collect()
}
