//! Reading the files users name: only regular files, and only up to a stated size, checked
//! before reading, so that a FIFO, `/dev/zero` or a huge file gives a clear error instead
//! of a hang or an exhausted memory.

use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// The largest space file read (bytes): a cell of the most faces written out takes about
/// a tenth of it.
pub const MAX_SPACE_FILE_BYTES: u64 = 4 << 20;

/// The largest scene file read (bytes).
pub const MAX_SCENE_FILE_BYTES: u64 = 16 << 20;

/// The text of a regular file of at most `limit` bytes; anything else is an error that
/// says what the path is instead, or how large it is against the limit.
pub(crate) fn read_text(path: &Path, limit: u64) -> Result<String, Error> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a FIFO, socket or device)"
        };
        return Err(Error::new(ErrorKind::InvalidInput, format!("it is {kind}")));
    }
    let too_large = |size: u64| {
        Error::new(
            ErrorKind::InvalidData,
            format!("it is {size} bytes, more than the limit of {limit} bytes"),
        )
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    // The file may grow between the check and the read: read one byte past the limit at most.
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        Error::new(
            ErrorKind::InvalidData,
            format!("it is not UTF-8 text ({e})"),
        )
    })
}
