//! The page, embedded in the binary: no network, no npm, no CDN. Plain
//! JavaScript and WebGL2, one small file per concern (see `web/`).

/// An embedded file: its URL path, content type and bytes.
pub struct Asset {
    /// Path under the server root.
    pub path: &'static str,
    /// The `Content-Type` header.
    pub content_type: &'static str,
    /// The file.
    pub body: &'static str,
}

/// The page; `{{TOKEN}}` is replaced by the session's token, so that the
/// scripts and styles it loads carry it too.
pub const INDEX_HTML: &str = include_str!("../web/index.html");

/// Every other embedded file.
pub const ASSETS: &[Asset] = &[
    js("math.js", include_str!("../web/math.js")),
    js("net.js", include_str!("../web/net.js")),
    js("view3d.js", include_str!("../web/view3d.js")),
    js("orbit.js", include_str!("../web/orbit.js")),
    js("panel.js", include_str!("../web/panel.js")),
    js("bvh.js", include_str!("../web/bvh.js")),
    js("inspect.js", include_str!("../web/inspect.js")),
    js("app.js", include_str!("../web/app.js")),
    Asset {
        path: "style.css",
        content_type: "text/css; charset=utf-8",
        body: include_str!("../web/style.css"),
    },
];

const fn js(path: &'static str, body: &'static str) -> Asset {
    Asset {
        path,
        content_type: "text/javascript; charset=utf-8",
        body,
    }
}

/// The asset at `path`, if embedded.
pub fn find(path: &str) -> Option<&'static Asset> {
    ASSETS.iter().find(|a| a.path == path)
}
