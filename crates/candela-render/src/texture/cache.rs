//! Textures are loaded once per file, however many materials use them, and
//! a file that cannot be read is reported once.

use super::ImageTexture;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The textures of one scene build, by path.
#[derive(Debug, Default)]
pub struct TextureCache {
    loaded: HashMap<PathBuf, Option<Arc<ImageTexture>>>,
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
    pub fn get(&mut self, path: &Path) -> Option<Arc<ImageTexture>> {
        if let Some(entry) = self.loaded.get(path) {
            return entry.clone();
        }
        let entry = match ImageTexture::load(path) {
            Ok(t) => Some(Arc::new(t)),
            Err(e) => {
                self.problems.push(format!(
                    "texture {} cannot be used ({e}); using the flat colour",
                    path.display()
                ));
                None
            }
        };
        self.loaded.insert(path.to_path_buf(), entry.clone());
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
