//! Reading and writing the files users name. Reading: only regular files, and only up to
//! a stated size, checked before reading, so that a FIFO, `/dev/zero` or a huge file gives a
//! clear error instead of a hang or an exhausted memory. Writing: atomically (a file is
//! complete or untouched) and with every error reported, the last flush's too.

use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// The largest space file read (bytes): a cell of the most faces written out takes about
/// a tenth of it.
pub const MAX_SPACE_FILE_BYTES: u64 = 4 << 20;

/// The largest scene file read (bytes).
pub const MAX_SCENE_FILE_BYTES: u64 = 16 << 20;

/// The largest model (`.glb`, `.gltf`, or a buffer or image file it names) read (bytes).
pub const MAX_MODEL_BYTES: u64 = 512 << 20;

/// The text of a regular file of at most `limit` bytes; anything else is an error that
/// says what the path is instead, or how large it is against the limit.
pub(crate) fn read_text(path: &Path, limit: u64) -> Result<String, Error> {
    String::from_utf8(read_bytes(path, limit)?).map_err(|e| {
        Error::new(
            ErrorKind::InvalidData,
            format!("it is not UTF-8 text ({e})"),
        )
    })
}

/// Checks that `path` is a regular file of at most `limit` bytes without reading it.
pub(crate) fn check_regular(path: &Path, limit: u64) -> Result<u64, Error> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a FIFO, socket or device)"
        };
        return Err(Error::new(ErrorKind::InvalidInput, format!("it is {kind}")));
    }
    if meta.len() > limit {
        return Err(too_large(meta.len(), limit));
    }
    Ok(meta.len())
}

fn too_large(size: u64, limit: u64) -> Error {
    Error::new(
        ErrorKind::InvalidData,
        format!("it is {size} bytes, more than the limit of {limit} bytes"),
    )
}

/// The bytes of a regular file of at most `limit` bytes (see [`read_text`]).
pub(crate) fn read_bytes(path: &Path, limit: u64) -> Result<Vec<u8>, Error> {
    let size = check_regular(path, limit)?;
    // The file may grow between the check and the read: read one byte past the limit at most.
    let mut bytes = Vec::with_capacity(size as usize);
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64, limit));
    }
    Ok(bytes)
}

/// Writes `bytes` to `path` so that the file is either complete or untouched: into a
/// temporary file beside it, flushed to the disk, then renamed over it (a link is followed
/// and its target replaced). A path that exists and is not a regular file (a device such
/// as `/dev/full`, a FIFO) is written directly, every write and the final flush checked.
/// Every error is returned, the last flush's too.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    use std::io::Write as _;
    let target = match std::fs::metadata(path) {
        Ok(meta) if !meta.is_file() => {
            if meta.is_dir() {
                return Err(Error::new(ErrorKind::InvalidInput, "it is a directory"));
            }
            let mut file = std::fs::OpenOptions::new().write(true).open(path)?;
            file.write_all(bytes)?;
            return file.flush();
        }
        // A link to a regular file: replace the file it points to, keep the link.
        Ok(_) => std::fs::canonicalize(path)?,
        Err(_) => path.to_path_buf(),
    };
    let name = target
        .file_name()
        .ok_or_else(|| Error::new(ErrorKind::InvalidInput, "the path names no file"))?;
    let dir = target
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let temporary = dir.join(format!(
        ".{}.part-{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let written = (|| {
        let mut file = std::fs::File::create(&temporary)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        std::fs::rename(&temporary, &target)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

/// Encodes an 8-bit RGB picture as PNG and writes it with [`write_atomic`].
pub fn write_png(path: &Path, image: &image::RgbImage) -> Result<(), Error> {
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(Error::other)?;
    write_atomic(path, &png)
}
