//! `candela view [scene]`: Candela Studio, the interactive viewer in the
//! browser (crate `candela-studio`). Binds 127.0.0.1 on a free port unless
//! told otherwise, prints the URL with its token and opens the browser.

use crate::args::{explicit_settings, Cs184Flags};
use crate::render_cmd::{load_scene, UsageError};
use anyhow::{Context, Result};
use candela_render::settings::Settings;
use candela_studio::{Studio, StudioOptions};
use clap::{ArgMatches, Args};
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// Flags of `candela view`.
#[derive(Args, Debug, Clone)]
pub struct ViewArgs {
    /// Scene file (any format `candela` renders). Omit it to view the built-in demo scene.
    pub scene: Option<PathBuf>,

    /// Port to listen on [default: a free one].
    #[arg(long)]
    pub port: Option<u16>,

    /// Listen on this address (IP or IP:PORT) instead of 127.0.0.1: anyone
    /// who can reach it and has the token can drive the renderer.
    #[arg(long, value_name = "ADDR")]
    pub listen: Option<String>,

    /// Do not open the browser; just print the URL.
    #[arg(long)]
    pub no_browser: bool,

    /// Folder the page's "save" writes images into.
    #[arg(long, value_name = "DIR", default_value = ".")]
    pub out_dir: PathBuf,

    /// Treat every load warning as an error.
    #[arg(long)]
    pub strict: bool,

    /// The starting render settings (the side panel changes them).
    #[command(flatten)]
    pub settings: Settings,

    /// CS184 spellings of settings.
    #[command(flatten, next_help_heading = "CS184 flags")]
    pub cs184: Cs184Flags,

    /// Sets a scene parameter (Mitsuba's `$name`): `-D spp=16`.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = crate::args::parse_define)]
    pub defines: Vec<(String, String)>,
}

/// Runs the viewer until the process is stopped. `matches` are the
/// command line's, to tell explicit settings from defaults.
pub fn run(args: &ViewArgs, matches: &ArgMatches) -> Result<()> {
    let view_matches = matches.subcommand_matches("view").unwrap_or(matches);
    let explicit = explicit_settings(&args.settings, &args.cs184, view_matches);
    let mut given = args.settings.clone();
    args.cs184.apply(&mut given);
    given.validate().map_err(UsageError::from)?;
    let addr = listen_address(args)?;
    if !addr.ip().is_loopback() {
        eprintln!(
            "candela: warning: listening on {addr}, not only on this machine: anyone who can \
             reach it and has the token can use the renderer and read the scene"
        );
    }
    if !args.out_dir.is_dir() {
        return Err(UsageError(format!(
            "--out-dir {}: not a folder",
            args.out_dir.display()
        ))
        .into());
    }
    let loaded = load_scene(args.scene.as_deref(), args.strict, &args.defines, false)?;
    let options = StudioOptions {
        scene_path: args.scene.clone(),
        out_dir: args.out_dir.clone(),
        token: None,
        settings: explicit,
    };
    let studio = Studio::new(loaded, options).map_err(UsageError)?;
    let page = studio.clone();
    let no_browser = args.no_browser;
    candela_studio::run(studio, addr, move |bound| {
        let url = page.url(bound);
        println!("Candela Studio: {url}");
        if !no_browser {
            // Best effort: without a desktop the user opens the URL.
            let _ = Command::new("xdg-open")
                .arg(&url)
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn();
        }
    })
    .with_context(|| format!("cannot serve on {addr}"))
}

/// `--listen` (an IP, or IP:PORT) and `--port`, or 127.0.0.1 on a free port.
fn listen_address(args: &ViewArgs) -> Result<SocketAddr, UsageError> {
    let port = args.port.unwrap_or(0);
    let Some(text) = &args.listen else {
        return Ok(SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), port));
    };
    if let Ok(addr) = text.parse::<SocketAddr>() {
        return Ok(addr);
    }
    text.parse::<IpAddr>()
        .map(|ip| SocketAddr::new(ip, port))
        .map_err(|_| {
            UsageError(format!(
                "--listen {text}: expected an IP address or IP:PORT"
            ))
        })
}
