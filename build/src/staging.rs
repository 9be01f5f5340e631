//! All-or-nothing writes: a run's files go into a staging folder beside their destination
//! first, and move into place only when every one was written and the caller's report of them
//! went out; on any failure the destination is left as it was (files this run replaced come
//! back, folders it created go). Two files of one run that share a name are an error naming
//! both sources, found before anything is written.

use std::path::{Path, PathBuf};

use crate::output::{holds, GeneratedFile, WriteOutcome};

/// A file of the run: where it goes, and whether the run writes it.
#[derive(Debug)]
pub struct Planned {
    /// The destination path.
    pub path: PathBuf,
    /// Whether the run writes it or finds it already holding these contents.
    pub outcome: WriteOutcome,
}

/// Why a run wrote nothing.
#[derive(Debug)]
pub enum StagingError {
    /// Two sources would write one file.
    Conflict(String),
    /// A file or folder could not be written; the message names it.
    Io(String),
    /// The caller's report could not be given (it said why itself).
    Report,
}

impl std::fmt::Display for StagingError {
    fn fmt(&self, out: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StagingError::Conflict(message) | StagingError::Io(message) => out.write_str(message),
            StagingError::Report => out.write_str("the report of the files could not be written"),
        }
    }
}

/// Writes `files` (each with its source's name) into `folder`, all or none: stages the new and
/// changed ones, calls `report` with every destination and its outcome, and moves them in
/// when it returns `Ok`. Unchanged files are not touched.
pub fn write_all(
    folder: &Path,
    files: &[(String, GeneratedFile)],
    report: impl FnOnce(&[Planned]) -> Result<(), ()>,
) -> Result<Vec<Planned>, StagingError> {
    let mut sources: Vec<(&str, &str)> = Vec::new();
    for (source, file) in files {
        if let Some((_, first)) = sources.iter().find(|(name, _)| *name == file.name) {
            return Err(StagingError::Conflict(format!(
                "{} would be written twice: by {first} and by {source} (rename one of them)",
                folder.join(&file.name).display()
            )));
        }
        sources.push((&file.name, source));
    }
    let mut run = Run::new(folder)?;
    let result = run.stage(files).and_then(|planned| {
        report(&planned).map_err(|()| StagingError::Report)?;
        run.commit()?;
        Ok(planned)
    });
    if result.is_err() {
        run.roll_back();
    }
    let _ = std::fs::remove_dir_all(&run.staging);
    result
}

/// One run's state: what it created, staged and moved.
struct Run {
    folder: PathBuf,
    /// The outermost folder this run created, removed on failure.
    created: Option<PathBuf>,
    staging: PathBuf,
    /// Staged files to move: (staged path, destination).
    staged: Vec<(PathBuf, PathBuf)>,
    /// Moved files: (destination, the backup of what it held before, if anything).
    moved: Vec<(PathBuf, Option<PathBuf>)>,
}

impl Run {
    fn new(folder: &Path) -> Result<Run, StagingError> {
        let io = |what: &Path, error: std::io::Error| {
            StagingError::Io(format!("cannot create {}: {error}", what.display()))
        };
        let created = folder
            .ancestors()
            .take_while(|ancestor| !ancestor.as_os_str().is_empty() && !ancestor.exists())
            .last()
            .map(Path::to_path_buf);
        std::fs::create_dir_all(folder).map_err(|error| io(folder, error))?;
        let staging = folder.join(format!(".gbuffer-staging-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&staging);
        let run = Run {
            folder: folder.to_path_buf(),
            created,
            staging: staging.clone(),
            staged: Vec::new(),
            moved: Vec::new(),
        };
        if let Err(error) = std::fs::create_dir(&staging) {
            run.roll_back();
            return Err(io(&staging, error));
        }
        Ok(run)
    }

    /// Writes the new and changed files into the staging folder.
    fn stage(&mut self, files: &[(String, GeneratedFile)]) -> Result<Vec<Planned>, StagingError> {
        let mut planned = Vec::new();
        for (_, file) in files {
            let path = self.folder.join(&file.name);
            let outcome = match std::fs::symlink_metadata(&path) {
                Ok(metadata) if !metadata.is_file() => {
                    return Err(StagingError::Io(format!(
                        "cannot write {}: something other than a file is there",
                        path.display()
                    )));
                }
                Ok(_) if holds(&path, &file.contents) => WriteOutcome::Unchanged,
                _ => {
                    let staged = self.staging.join(&file.name);
                    std::fs::write(&staged, &file.contents).map_err(|error| {
                        StagingError::Io(format!("cannot write {}: {error}", staged.display()))
                    })?;
                    self.staged.push((staged, path.clone()));
                    WriteOutcome::Written
                }
            };
            planned.push(Planned { path, outcome });
        }
        Ok(planned)
    }

    /// Moves the staged files into place, keeping what each replaces until the run ends.
    fn commit(&mut self) -> Result<(), StagingError> {
        for (index, (staged, destination)) in self.staged.iter().enumerate() {
            let io = |error: std::io::Error| {
                StagingError::Io(format!("cannot write {}: {error}", destination.display()))
            };
            let backup = if destination.exists() {
                let backup = self.staging.join(format!("{index}.previous"));
                std::fs::rename(destination, &backup).map_err(io)?;
                Some(backup)
            } else {
                None
            };
            self.moved.push((destination.clone(), backup));
            std::fs::rename(staged, destination).map_err(io)?;
        }
        Ok(())
    }

    /// Puts back what the moved files replaced (from the staging folder, which the caller
    /// removes afterwards), and removes the folders the run created.
    fn roll_back(&self) {
        for (destination, backup) in self.moved.iter().rev() {
            match backup {
                Some(backup) => {
                    let _ = std::fs::rename(backup, destination);
                }
                None => {
                    let _ = std::fs::remove_file(destination);
                }
            }
        }
        if let Some(created) = &self.created {
            let _ = std::fs::remove_dir_all(created);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(name: &str, contents: &str) -> (String, GeneratedFile) {
        (
            "a.toml".into(),
            GeneratedFile {
                name: name.into(),
                contents: contents.into(),
            },
        )
    }

    #[test]
    fn a_failed_run_leaves_the_folder_as_it_was() {
        let root = std::env::temp_dir().join(format!("gbuffer-staging-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let folder = root.join("out");
        // A run into a new folder whose report fails leaves no folder.
        let failed = write_all(&folder, &[file("a.wgsl", "a")], |_| Err(()));
        assert!(matches!(failed, Err(StagingError::Report)));
        assert!(!root.exists());
        // A good run writes, a second reports the unchanged file.
        let planned = write_all(&folder, &[file("a.wgsl", "a")], |_| Ok(())).unwrap();
        assert_eq!(planned[0].outcome, WriteOutcome::Written);
        let planned = write_all(&folder, &[file("a.wgsl", "a")], |_| Ok(())).unwrap();
        assert_eq!(planned[0].outcome, WriteOutcome::Unchanged);
        // A destination that is a folder fails the run before the other file is written, and
        // a changed file stays as it was.
        std::fs::create_dir(folder.join("b.glsl")).unwrap();
        let failed = write_all(
            &folder,
            &[file("a.wgsl", "changed"), file("b.glsl", "b")],
            |_| Ok(()),
        );
        assert!(failed.unwrap_err().to_string().contains("b.glsl"));
        assert_eq!(std::fs::read_to_string(folder.join("a.wgsl")).unwrap(), "a");
        // Two sources of one name: an error naming both, nothing written.
        let twice = [
            file("c.wgsl", "1"),
            ("b.toml".to_string(), file("c.wgsl", "2").1),
        ];
        let error = write_all(&folder, &twice, |_| Ok(()))
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("a.toml") && error.contains("b.toml"),
            "{error}"
        );
        assert!(!folder.join("c.wgsl").exists());
        let left: Vec<_> = std::fs::read_dir(&folder)
            .unwrap()
            .map(|entry| entry.unwrap().file_name())
            .collect();
        assert_eq!(left.len(), 2, "{left:?}");
        std::fs::remove_dir_all(&root).unwrap();
    }
}
