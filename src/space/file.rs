//! Space files: a user-defined space as JSON, validated like the seed spaces.
//!
//! ```json
//! {
//!   "name": "my-torus",
//!   "description": "optional text",
//!   "geometry": "euclidean",
//!   "faces": [
//!     { "normal": [1, 0, 0], "offset": 0.5, "partner": 1,
//!       "pairing": [[1,0,0,-1], [0,1,0,0], [0,0,1,0], [0,0,0,1]] },
//!     { "normal": [0, 0, 1], "offset": 0.5, "mirror": true }
//!   ]
//! }
//! ```
//!
//! A face is the chart half-space `normal · x ≤ offset`. `pairing` is the 4×4 isometry, row
//! by row, applied to a ray leaving through the face (it maps the face onto its `partner`
//! with the cell on the far side); `"mirror": true` makes the face a mirror instead.
//! A space of several cells gives each face its `"cell"` (0, 1, …; faces listed cell by
//! cell, partners numbered through all of them: [`Space::new_cells`]).
//! `curved-spaces export SPACE` writes any seed space in this form.

use super::{FaceSpec, Pairing, Space, SpaceError};
use crate::geometry::Geometry;
use glam::{DMat4, DVec3};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A face of a space file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceRecord {
    /// Outward normal in the chart.
    pub normal: [f64; 3],
    /// Chart distance of the face plane from the origin.
    pub offset: f64,
    /// The face this one is glued to.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub partner: Option<usize>,
    /// Row-major 4×4 matrix.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pairing: Option<[[f64; 4]; 4]>,
    /// Whether the face is a mirror.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub mirror: bool,
    /// The cell the face bounds, in a space of several cells (0, the default, for one):
    /// faces are listed cell by cell, the cells numbered from 0 in order.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub cell: usize,
}

// A reference, as serde's `skip_serializing_if` passes one.
#[allow(clippy::trivially_copy_pass_by_ref)]
fn is_zero(x: &usize) -> bool {
    *x == 0
}

/// The contents of a space file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceRecord {
    /// The space's name.
    pub name: String,
    /// A one-line description.
    #[serde(default)]
    pub description: String,
    /// Its geometry.
    pub geometry: Geometry,
    /// Its faces.
    pub faces: Vec<FaceRecord>,
}

/// Why a space file could not be used.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, thiserror::Error)]
pub enum SpaceFileError {
    /// Cannot read space file `path`: `source`.
    #[error("cannot read space file {path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    /// Space file `path` is not valid: `source`.
    #[error("space file {path} is not valid: {source}")]
    Json {
        path: String,
        source: serde_json::Error,
    },
    /// Space file `path`, face `face`: `reason`.
    #[error("space file {path}, face {face}: {reason}")]
    Face {
        path: String,
        face: usize,
        reason: String,
    },
    /// Space file `path`: `source`.
    #[error("space file {path}: {source}")]
    Invalid { path: String, source: SpaceError },
    /// Space file `path`: its `what` is `length` bytes, more than `limit`.
    #[error("space file {path}: its {what} is {length} bytes long, more than the limit of {limit}")]
    TooLong {
        path: String,
        what: &'static str,
        length: usize,
        limit: usize,
    },
}

/// The longest space name a space file may give (bytes).
pub const MAX_NAME_BYTES: usize = 256;

/// The longest description a space file may give (bytes).
pub const MAX_DESCRIPTION_BYTES: usize = 16 << 10;

impl SpaceRecord {
    /// The record of a space (pairings written out as matrices).
    #[must_use]
    pub fn from_space(space: &Space) -> Self {
        let faces = space
            .faces
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let mirror = f.is_mirror(i);
                FaceRecord {
                    normal: f.normal.to_array(),
                    offset: f.offset,
                    partner: (!mirror).then_some(f.partner),
                    pairing: (!mirror).then(|| f.pairing.transpose().to_cols_array_2d()),
                    mirror,
                    cell: f.cell,
                }
            })
            .collect();
        Self {
            name: space.name.clone(),
            description: space.description.clone(),
            geometry: space.geometry,
            faces,
        }
    }

    /// Builds and validates the space; `path` names the source in errors.
    pub fn build(&self, path: &str) -> Result<Space, SpaceFileError> {
        let face_error = |face: usize, reason: &str| SpaceFileError::Face {
            path: path.to_string(),
            face,
            reason: reason.to_string(),
        };
        for (what, text, limit) in [
            ("name", &self.name, MAX_NAME_BYTES),
            ("description", &self.description, MAX_DESCRIPTION_BYTES),
        ] {
            if text.len() > limit {
                return Err(SpaceFileError::TooLong {
                    path: path.to_string(),
                    what,
                    length: text.len(),
                    limit,
                });
            }
        }
        let mut cells: Vec<Vec<FaceSpec>> = vec![Vec::new()];
        for (i, f) in self.faces.iter().enumerate() {
            let current = cells.len() - 1;
            if f.cell == current + 1 && !cells[current].is_empty() {
                cells.push(Vec::new());
            } else if f.cell != current {
                return Err(face_error(
                    i,
                    &format!(
                        "`cell` {} follows cell {current}: list the faces cell by cell, the \
                         cells numbered 0, 1, 2, … in order",
                        f.cell
                    ),
                ));
            }
            let normal = DVec3::from_array(f.normal);
            let pairing = match (f.mirror, f.partner, f.pairing) {
                (true, None, None) => Some(Pairing {
                    partner: i,
                    matrix: self
                        .geometry
                        .reflection((normal / normal.length()).extend(-f.offset / normal.length())),
                }),
                (true, _, _) => {
                    return Err(face_error(
                        i,
                        "a mirror takes neither `partner` nor `pairing`",
                    ));
                }
                (false, Some(partner), Some(rows)) => Some(Pairing {
                    partner,
                    matrix: DMat4::from_cols_array_2d(&rows).transpose(),
                }),
                (false, None, None) => None,
                (false, None, Some(_)) => {
                    return Err(face_error(i, "`pairing` given without `partner`"));
                }
                (false, Some(_), None) => {
                    return Err(face_error(i, "`partner` given without `pairing`"));
                }
            };
            if let Some(cell) = cells.last_mut() {
                cell.push(FaceSpec {
                    normal,
                    offset: f.offset,
                    pairing,
                });
            }
        }
        Space::new_cells(&self.name, &self.description, self.geometry, &cells).map_err(|source| {
            SpaceFileError::Invalid {
                path: path.to_string(),
                source,
            }
        })
    }
}

/// Reads, parses and validates a space file.
pub fn load_space_file(path: &Path) -> Result<Space, SpaceFileError> {
    let name = path.display().to_string();
    let text =
        crate::files::read_text(path, crate::files::MAX_SPACE_FILE_BYTES).map_err(|source| {
            SpaceFileError::Io {
                path: name.clone(),
                source,
            }
        })?;
    let record: SpaceRecord =
        serde_json::from_str(&text).map_err(|source| SpaceFileError::Json {
            path: name.clone(),
            source,
        })?;
    record.build(&name)
}
