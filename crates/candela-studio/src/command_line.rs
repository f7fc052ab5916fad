//! "Copy command line": the `candela` command that renders the image the
//! viewer shows. Only the settings the page changed become flags (the
//! scene's own hints apply again when the CLI loads the same file), each
//! spelled as [`candela_render::settings::flags`] says; the camera is the
//! `--eye`/`--look-at`/`--up`/`--fov` settings.

use candela_render::settings::{flags, Settings};
use serde_json::{Map, Value};
use std::path::Path;

/// The command line rendering `settings` (of which the keys of `changes`
/// were given explicitly) of `scene` (`None`: the demo) into `output`.
pub fn command_line(
    scene: Option<&Path>,
    settings: &Settings,
    changes: &Map<String, Value>,
    output: &str,
) -> String {
    let mut words = vec!["candela".to_string()];
    let values = settings.to_json();
    for flag in flags() {
        if !changes.contains_key(&flag.name) {
            continue;
        }
        let Some(value) = values.get(&flag.name).filter(|v| !v.is_null()) else {
            continue;
        };
        match (flag.name.as_str(), &flag.long) {
            ("cell", _) => {
                words.push("-p".into());
                for k in ["x", "y", "width", "height"] {
                    words.push(plain(&value[k]));
                }
            }
            ("adaptive", _) => {
                words.push("-a".into());
                words.push(plain(&value["batch"]));
                words.push(plain(&value["tolerance"]));
            }
            (_, Some(long)) => {
                // `--eye=-1,2,3`: a value starting with `-` must not look
                // like a flag.
                let value = plain(value);
                if value.starts_with('-') || flag.require_equals {
                    words.push(format!("--{long}={value}"));
                } else {
                    words.push(format!("--{long}"));
                    words.push(value);
                }
            }
            (_, None) => {}
        }
    }
    if let Some(path) = scene {
        words.push(path.display().to_string());
    }
    words.push("-f".into());
    words.push(output.into());
    words
        .iter()
        .map(|w| shell_quote(w))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A JSON value as one command-line word: arrays as `x,y,z`.
fn plain(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        Value::Array(items) => items.iter().map(plain).collect::<Vec<_>>().join(","),
        other => other.to_string(),
    }
}

/// `word`, single-quoted for a POSIX shell if it needs it.
fn shell_quote(word: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "-_./,:=+@%".contains(c);
    if !word.is_empty() && word.chars().all(safe) {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn changed_settings_become_flags() {
        let changes = json!({
            "spp": 4, "roulette": false, "eye": [1.5, -2, 3], "look_at": [-1, 0, 0],
            "cell": [1, 2, 3, 4], "lighting": "hemisphere", "denoise": true
        });
        let changes = changes.as_object().unwrap().clone();
        let settings = Settings::default().overlay(&changes).unwrap();
        let line = command_line(
            Some(Path::new("my scene.dae")),
            &settings,
            &changes,
            "out.png",
        );
        assert_eq!(
            line,
            "candela --spp 4 --lighting hemisphere --roulette false --eye 1.5,-2.0,3.0 \
             --look-at=-1.0,0.0,0.0 --denoise=true -p 1 2 3 4 'my scene.dae' -f out.png"
        );
    }
}
