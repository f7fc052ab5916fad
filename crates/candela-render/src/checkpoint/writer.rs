//! Saving checkpoints during a render: every `checkpoint_every` seconds
//! between passes, and once more at the end (which a cancelled render
//! reaches too). Every front end (the CLI, the Python package) renders
//! through this, so they write the same files on the same schedule.

use super::{scene_hash, Checkpoint, CheckpointError, ContentHash, Mismatch};
use crate::film::Film;
use crate::render::PassEnd;
use crate::settings::Settings;
use candela_scene::SceneDesc;
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Why a checkpointed render cannot start.
#[derive(Debug, thiserror::Error)]
pub enum StartError {
    /// The existing checkpoint cannot be read.
    #[error(transparent)]
    File(#[from] CheckpointError),
    /// The existing checkpoint is of another render.
    #[error("{path}: {mismatch} (delete it or choose another --checkpoint path)")]
    Mismatch {
        /// The checkpoint.
        path: String,
        /// What differs.
        mismatch: Mismatch,
    },
}

/// Writes a render's checkpoints.
#[derive(Debug)]
pub struct CheckpointWriter {
    path: PathBuf,
    every: Duration,
    settings: Settings,
    scene_hash: ContentHash,
    front: Map<String, Value>,
    /// Render time of the film before this run.
    before: Duration,
    last_save: Mutex<Instant>,
    /// The first failed save during the render (reported, not fatal: the
    /// render goes on and the final save tries again).
    failure: Mutex<Option<CheckpointError>>,
}

/// A render to continue: the checkpoint's film and time.
#[derive(Clone, Debug)]
pub struct Resumed {
    /// The sums to continue.
    pub film: Film,
    /// Render time already spent on them.
    pub elapsed: Duration,
}

impl CheckpointWriter {
    /// The writer for a render of `desc` with `settings`, if they ask for
    /// checkpoints (`settings.run.checkpoint`). `front` is the front end's
    /// record (what it needs to finish the render on `candela resume`). If
    /// the file already holds a checkpoint of this scene and these
    /// settings, it is returned to continue; one of another render is an
    /// error naming the difference.
    pub fn start(
        settings: &Settings,
        desc: &SceneDesc,
        front: Map<String, Value>,
    ) -> Result<Option<(Self, Option<Resumed>)>, StartError> {
        let Some(path) = settings.run.checkpoint.clone() else {
            return Ok(None);
        };
        let hash = scene_hash(desc, settings.image.env_map.as_deref());
        let resumed = if path.exists() {
            let old = Checkpoint::load(&path)?;
            old.check_matches(hash, settings)
                .map_err(|mismatch| StartError::Mismatch {
                    path: path.display().to_string(),
                    mismatch,
                })?;
            Some(Resumed {
                film: old.film,
                elapsed: old.elapsed,
            })
        } else {
            None
        };
        let writer = Self {
            every: Duration::try_from_secs_f64(settings.run.checkpoint_every)
                .unwrap_or(Duration::ZERO),
            path,
            settings: settings.clone(),
            scene_hash: hash,
            front,
            before: resumed.as_ref().map_or(Duration::ZERO, |r| r.elapsed),
            last_save: Mutex::new(Instant::now()),
            failure: Mutex::new(None),
        };
        Ok(Some((writer, resumed)))
    }

    /// The checkpoint file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The time budget left of `budget` after the checkpoint's render time.
    pub fn budget_left(&self, budget: Option<Duration>) -> Option<Duration> {
        budget.map(|b| b.saturating_sub(self.before))
    }

    /// Render time of the film over every run, after `elapsed` of this one.
    pub fn total_time(&self, elapsed: Duration) -> Duration {
        self.before + elapsed
    }

    /// What the render loop calls after each pass: saves if the last save
    /// is `checkpoint_every` ago.
    pub fn after_pass(&self, pass: &PassEnd<'_>) {
        let due = self
            .last_save
            .lock()
            .map(|last| last.elapsed() >= self.every)
            .unwrap_or(true);
        if due {
            let saved = self.save(pass.film(), pass.elapsed);
            if let Err(e) = saved {
                if let Ok(mut first) = self.failure.lock() {
                    first.get_or_insert(e);
                }
            }
        }
    }

    /// Saves `film`, the sums after `elapsed` of this run.
    pub fn save(&self, film: Film, elapsed: Duration) -> Result<(), CheckpointError> {
        let checkpoint = Checkpoint {
            settings: self.settings.clone(),
            scene_hash: self.scene_hash,
            front: self.front.clone(),
            elapsed: self.total_time(elapsed),
            film,
        };
        checkpoint.save(&self.path)?;
        if let Ok(mut last) = self.last_save.lock() {
            *last = Instant::now();
        }
        Ok(())
    }

    /// The first save that failed during the render, if any.
    pub fn take_failure(&self) -> Option<CheckpointError> {
        self.failure.lock().ok().and_then(|mut f| f.take())
    }
}
