//! Finding a space by name: a seed space, a member of a library family, or a file
//! (`.gen` generator file or JSON space file).

use super::dirichlet::DirichletOptions;
use super::file::load_space_file;
use super::group::load_gen_file;
use super::{SEED_SPACES, Space, SpaceError, seed_space};
use std::path::Path;

/// Whether `path` names a generator file (by its extension, `.gen`, any case).
#[must_use]
pub fn is_gen_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gen"))
}

/// A seed space by id, or a space file by path (relative to `base`): a `.gen` generator file
/// is made into its group's Dirichlet domain about the basepoint of `options`, anything else
/// is read as a JSON space file.
pub fn resolve_space(id: &str, base: &Path, options: &DirichletOptions) -> Result<Space, String> {
    if SEED_SPACES.iter().any(|s| s.id == id) {
        return seed_space(id).map_err(|e| e.to_string());
    }
    let path = base.join(id);
    if is_gen_path(&path) {
        return load_gen_file(&path, options);
    }
    if path.exists() || id.ends_with(".json") {
        return load_space_file(&path).map_err(|e| e.to_string());
    }
    Err(SpaceError::UnknownSpace(id.to_string()).to_string())
}
