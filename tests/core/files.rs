//! Writing files: whole or not at all, every error reported (`files::write_atomic`).

use bevy_curved_spaces::files::{write_atomic, write_png};
use std::path::Path;

fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".part-"))
        .collect()
}

#[test]
fn writes_are_whole_replace_only_when_complete_and_report_every_error() {
    let dir = crate::common::scratch_dir("atomic-writes");
    let path = dir.join("a.txt");
    write_atomic(&path, b"first").unwrap();
    write_atomic(&path, b"second, longer").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"second, longer");
    // A link to a regular file: the file is replaced, the link kept.
    let link = dir.join("link.txt");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&path, &link).unwrap();
    write_atomic(&link, b"through the link").unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&path).unwrap(), b"through the link");
    // A full device: the error comes back (a small PNG's last flush was not checked).
    if Path::new("/dev/full").exists() {
        let full = dir.join("full.png");
        let _ = std::fs::remove_file(&full);
        std::os::unix::fs::symlink("/dev/full", &full).unwrap();
        let picture = image::RgbImage::new(16, 9);
        let e = write_png(&full, &picture).expect_err("/dev/full is full");
        assert_eq!(e.raw_os_error(), Some(28), "{e}");
    }
    // A directory, and a folder that does not exist: errors, and nothing left behind.
    assert!(write_atomic(&dir, b"x").is_err());
    assert!(write_atomic(&dir.join("missing/b.txt"), b"x").is_err());
    assert_eq!(leftovers(&dir), Vec::<String>::new());
}
