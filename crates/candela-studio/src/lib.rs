//! Candela Studio: the interactive viewer in the browser.
//!
//! `candela view [scene]` starts [`serve`]: a local HTTP and WebSocket
//! server (axum on tokio) that serves the page embedded in the binary
//! ([`assets`]) and renders the one scene it was given. The page draws the
//! scene's triangles with WebGL2, orbits the camera, and shows the
//! path-traced image of the current camera progressively: a coarse frame
//! first, then the render itself, with frames of its film between passes
//! ([`worker`]). It is one more front end on the one settings description:
//! the page sends settings changes as JSON ([`candela_render::settings::Settings::resolve`]),
//! the camera as the settings `eye`/`look_at`/`up`/`fov`, and saves through
//! [`candela_render::film::write_film`].
//!
//! Safe by default: the server binds 127.0.0.1, every request carries a
//! random token ([`token`]), it reads only the scene it was started with,
//! and it writes only into the output folder chosen on the command line.
#![warn(missing_docs)]

pub mod assets;
pub mod bvh_view;
pub mod command_line;
mod film_requests;
pub mod frames;
pub mod mesh;
pub mod protocol;
pub mod scene_pool;
mod server;
pub mod settings_form;
pub mod token;
pub mod worker;

pub use server::{router, run, serve, Studio, StudioOptions};
