//! Textures are loaded once per file, however many materials use them, and
//! a file that cannot be read is reported once.

use super::{native_color_space, ImageTexture};
use candela_scene::ColorSpace;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The textures of one scene build, by path.
#[derive(Debug, Default)]
pub struct TextureCache {
    loaded: HashMap<(PathBuf, ColorSpace), Option<Arc<ImageTexture>>>,
    problems: Vec<String>,
}

impl TextureCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// The texture at `path`, read on first use; `None` if it cannot be
    /// read, with the reason recorded in [`TextureCache::problems`] the
    /// first time only.
    /// The file is read in its format's own colour space (PNG sRGB, EXR
    /// linear).
    pub fn get(&mut self, path: &Path) -> Option<Arc<ImageTexture>> {
        self.get_in(path, native_color_space(path))
    }

    /// [`TextureCache::get`] with the stored values taken as `color_space`
    /// (a PNG of roughness values is linear data, not sRGB colour).
    pub fn get_in(&mut self, path: &Path, color_space: ColorSpace) -> Option<Arc<ImageTexture>> {
        let key = (path.to_path_buf(), color_space);
        if let Some(entry) = self.loaded.get(&key) {
            return entry.clone();
        }
        let entry = match ImageTexture::load_in(path, color_space) {
            Ok(t) => Some(Arc::new(t)),
            Err(e) => {
                let message = format!(
                    "texture {} cannot be used ({e}); using the flat colour",
                    path.display()
                );
                if !self.problems.contains(&message) {
                    self.problems.push(message);
                }
                None
            }
        };
        self.loaded.insert(key, entry.clone());
        entry
    }

    /// One message per texture file that could not be read.
    pub fn problems(&self) -> &[String] {
        &self.problems
    }

    /// Consumes the cache, returning its messages.
    pub fn into_problems(self) -> Vec<String> {
        self.problems
    }
}
