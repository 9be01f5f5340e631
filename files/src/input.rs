//! Reading an input file (a layout, a scene, a shader or one it includes) the way every
//! command does: regular files only, since a FIFO or a device would block or never end, and
//! none larger than [`MAX_INPUT_BYTES`], so that no input can ask for gigabytes downstream.

use std::io::{self, Read};
use std::path::Path;

/// The largest input file read, in bytes (4 MiB: a hundred times the largest layout or shader
/// this project ships).
pub const MAX_INPUT_BYTES: u64 = 4 << 20;

/// Reads `path` as UTF-8 text; an error when it is not a regular file or is larger than
/// [`MAX_INPUT_BYTES`].
pub fn read_input(path: &Path) -> io::Result<String> {
    let refused = |reason: String| io::Error::new(io::ErrorKind::InvalidInput, reason);
    // `metadata` follows links but, unlike opening, never blocks on a FIFO.
    let metadata = std::fs::metadata(path)?;
    if !metadata.is_file() {
        return Err(refused(
            "not a regular file (a folder, FIFO or device is not read)".into(),
        ));
    }
    let too_large = |bytes: u64| {
        refused(format!(
            "{bytes} bytes, over the limit of {MAX_INPUT_BYTES} bytes ({} MiB) on input files",
            MAX_INPUT_BYTES >> 20
        ))
    };
    if metadata.len() > MAX_INPUT_BYTES {
        return Err(too_large(metadata.len()));
    }
    // The file may have grown since: read no more than the limit and one byte.
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(MAX_INPUT_BYTES + 1)
        .read_to_string(&mut text)?;
    if text.len() as u64 > MAX_INPUT_BYTES {
        return Err(too_large(text.len() as u64));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_and_fifos_are_refused_without_blocking() {
        let folder = std::env::temp_dir().join(format!("gbuffer-input-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let error = read_input(&folder).unwrap_err();
        assert!(error.to_string().contains("not a regular file"), "{error}");
        let fifo = folder.join("fifo");
        let status = std::process::Command::new("mkfifo").arg(&fifo).status();
        if status.is_ok_and(|status| status.success()) {
            let error = read_input(&fifo).unwrap_err();
            assert!(error.to_string().contains("not a regular file"), "{error}");
        }
        let large = folder.join("large.toml");
        std::fs::write(&large, vec![b'#'; MAX_INPUT_BYTES as usize + 1]).unwrap();
        let error = read_input(&large).unwrap_err();
        assert!(error.to_string().contains("over the limit"), "{error}");
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
