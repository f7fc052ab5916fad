//! The settings panel's description: every setting of
//! [`Settings`], with its help, its choices, its default and its value for
//! this scene (the scene's hints applied), from which the page generates
//! its form. Nothing here restates a default or a rule: the values come
//! from [`Settings::default`] and [`Settings::resolve`], the text from
//! [`candela_render::settings::flags`].

use candela_render::settings::{flags, Settings};
use serde::Serialize;
use serde_json::Value;

/// One field of the form.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Field {
    /// The JSON name the page sends back.
    pub name: String,
    /// The help text (shown as the field's title).
    pub help: String,
    /// The values of a setting with a fixed set of them.
    pub choices: Vec<String>,
    /// The default, before the scene's hints.
    pub default: Value,
    /// The value for this scene (defaults under the scene's hints).
    pub value: Value,
}

/// Every setting as a form field, in the order of `candela --help`.
pub fn describe(scene_settings: &Settings) -> Vec<Field> {
    let defaults = Settings::default().to_json();
    let values = scene_settings.to_json();
    flags()
        .into_iter()
        .filter(|f| defaults.contains_key(&f.name))
        .map(|f| Field {
            default: defaults[&f.name].clone(),
            value: values.get(&f.name).cloned().unwrap_or(Value::Null),
            choices: if defaults[&f.name].is_boolean() {
                Vec::new()
            } else {
                f.choices
            },
            help: f.help,
            name: f.name,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setting_is_a_field_once() {
        let fields = describe(&Settings::default());
        let mut names: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
        let mut keys: Vec<String> = Settings::default().to_json().keys().cloned().collect();
        names.sort_unstable();
        keys.sort_unstable();
        assert_eq!(names, keys);
        let lighting = fields.iter().find(|f| f.name == "lighting").unwrap();
        assert!(
            lighting.choices.contains(&"mis".to_string()),
            "{lighting:?}"
        );
        assert!(
            fields.iter().all(|f| !f.help.is_empty()),
            "every field has help"
        );
    }
}
