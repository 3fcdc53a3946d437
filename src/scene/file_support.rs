//! What the families' scene files share ([`super::file`] for the constant-curvature spaces,
//! `trace::product::file`, `trace::nil::file` and `trace::sl2r::file` for the others):
//! reading the text and telling the families' files apart by their `space` key, errors that
//! name the file and the line, "did you mean" for an unknown key, and the keys they take
//! alike (colours, `ambient`, `walls` and `wall_opacity`, a point light and start view).

use glam::DVec3;
use std::path::Path;
use toml::Spanned;

/// A scene file could not be used: the file, the line (where one is to blame) and what is
/// wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}{}: {message}", line.map(|l| format!(":{l}")).unwrap_or_default())]
pub struct SceneFileError {
    /// The file.
    pub file: String,
    /// The line at fault, where known.
    pub line: Option<usize>,
    /// What is wrong.
    pub message: String,
}

/// The `space` key of a scene file's text, where it can be read: how the loaders tell the
/// families' files apart.
pub(crate) fn space_key(text: &str) -> Option<String> {
    #[derive(serde::Deserialize)]
    struct SpaceOnly {
        space: String,
    }
    toml::from_str::<SpaceOnly>(text)
        .ok()
        .map(|peek| peek.space)
}

/// Reads the scene file at `path` and parses it with `parse` if `names` says its text is
/// of the family; `Ok(None)` for any other file (another family's, or one whose `space`
/// cannot be read: the constant-curvature loader says what is wrong with it).
pub(crate) fn load_family_scene<T>(
    path: &Path,
    names: impl Fn(&str) -> bool,
    parse: impl Fn(&str, &str) -> Result<T, SceneFileError>,
) -> Result<Option<T>, SceneFileError> {
    let (name, text) = read_scene_text(path)?;
    if names(&text) {
        parse(&text, &name).map(Some)
    } else {
        Ok(None)
    }
}

/// The fog keys the families' files share, checked: `fog` (a positive distance, `unit`
/// named in the message), `ambient` (0 to 1) and `fog_colour` (finite, at most 1); `None`
/// for a key the file leaves out.
pub(crate) struct FogKeys {
    /// The fog distance.
    pub fog: Option<f64>,
    /// The ambient share.
    pub ambient: Option<f64>,
    /// The fog's colour.
    pub fog_colour: Option<DVec3>,
}

/// Reads the shared fog keys ([`FogKeys`]); an error comes with the key's span.
pub(crate) fn fog_keys(
    fog: Option<&Spanned<f64>>,
    ambient: Option<&Spanned<f64>>,
    fog_colour: Option<&Spanned<[f64; 3]>>,
    unit: &str,
) -> Result<FogKeys, SpanError> {
    let fog = match fog {
        Some(f) if !(*f.get_ref() > 0.0 && f.get_ref().is_finite()) => {
            return Err((
                f.span(),
                format!(
                    "the fog distance must be a positive number{unit}, got {}",
                    f.get_ref()
                ),
            ));
        }
        f => f.map(|f| *f.get_ref()),
    };
    let ambient = ambient.map(ambient_of).transpose()?;
    let fog_colour = match fog_colour {
        Some(c) => Some(
            colour(*c.get_ref())
                .map_err(|m| (c.span(), format!("fog_colour: {m}")))?
                .min(DVec3::ONE),
        ),
        None => None,
    };
    Ok(FogKeys {
        fog,
        ambient,
        fog_colour,
    })
}

/// A scene file's name and text (at most [`crate::files::MAX_SCENE_FILE_BYTES`]), or an
/// error naming it.
pub(crate) fn read_scene_text(path: &Path) -> Result<(String, String), SceneFileError> {
    let name = path.display().to_string();
    match crate::files::read_text(path, crate::files::MAX_SCENE_FILE_BYTES) {
        Ok(text) => Ok((name, text)),
        Err(e) => Err(SceneFileError {
            file: name,
            line: None,
            message: format!("cannot read the scene file: {e}"),
        }),
    }
}

/// The errors of one file's text: the file, the line of a span, the message.
pub(crate) fn failing<'a>(
    text: &'a str,
    file: &'a str,
) -> impl Fn(Option<std::ops::Range<usize>>, String) -> SceneFileError + 'a {
    move |span, message| SceneFileError {
        file: file.to_string(),
        line: span.map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1),
        message,
    }
}

/// A file's TOML as `T`; an unknown key's error names the nearest of `keys`.
pub(crate) fn parse_toml<T: serde::de::DeserializeOwned>(
    text: &str,
    file: &str,
    keys: &[&str],
) -> Result<T, SceneFileError> {
    toml::from_str(text).map_err(|e| {
        // The TOML error's first line repeats the position; keep its message.
        failing(text, file)(e.span(), suggest_key(e.message(), keys))
    })
}

/// A span and what is wrong there.
pub(crate) type SpanError = (std::ops::Range<usize>, String);

/// `ambient`, between 0 and 1.
pub(crate) fn ambient_of(a: &Spanned<f64>) -> Result<f64, SpanError> {
    if (0.0..=1.0).contains(a.get_ref()) {
        Ok(*a.get_ref())
    } else {
        Err((
            a.span(),
            format!("ambient must be between 0 and 1, got {}", a.get_ref()),
        ))
    }
}

/// The walls of `walls = OPENING` and `wall_opacity = A` (which needs the walls).
pub(crate) fn walls_of(
    walls: Option<&Spanned<f64>>,
    opacity: Option<&Spanned<f64>>,
) -> Result<Option<crate::scene::WallStyle>, SpanError> {
    match (walls, opacity) {
        (Some(opening), opacity) => crate::scene::WallStyle::with_opacity(
            *opening.get_ref(),
            opacity.map_or(crate::scene::walls::DEFAULT_WALL_OPACITY, |o| *o.get_ref()),
        )
        .map(Some)
        .map_err(|e| {
            let span = match (&e, opacity) {
                (crate::scene::WallError::Opacity(_), Some(o)) => o.span(),
                _ => opening.span(),
            };
            (span, e.to_string())
        }),
        (None, Some(o)) => Err((
            o.span(),
            "wall_opacity needs walls = OPENING (0 solid to 1 none) beside it".into(),
        )),
        (None, None) => Ok(None),
    }
}

/// An unknown-field message of `toml` with the nearest of `keys`, if one is within two
/// edits.
pub(crate) fn suggest_key(message: &str, keys: &[&str]) -> String {
    let unknown = message
        .strip_prefix("unknown field `")
        .and_then(|rest| rest.split('`').next());
    let Some(word) = unknown else {
        return message.to_string();
    };
    let distance = |a: &str, b: &str| {
        let b: Vec<char> = b.chars().collect();
        let mut row: Vec<usize> = (0..=b.len()).collect();
        for (i, ca) in a.chars().enumerate() {
            let mut prev = row[0];
            row[0] = i + 1;
            for (j, cb) in b.iter().enumerate() {
                let next = (prev + usize::from(ca != *cb))
                    .min(row[j] + 1)
                    .min(row[j + 1] + 1);
                prev = row[j + 1];
                row[j + 1] = next;
            }
        }
        row[b.len()]
    };
    match keys
        .iter()
        .map(|k| (distance(word, k), *k))
        .min()
        .filter(|(d, _)| *d <= 2)
    {
        Some((_, key)) => format!("{message} (did you mean `{key}`?)"),
        None => message.to_string(),
    }
}

/// A colour (or emission) from a file: finite, negative channels taken as 0.
pub(crate) fn colour(c: [f64; 3]) -> Result<DVec3, String> {
    let v = DVec3::from_array(c);
    if !v.is_finite() {
        return Err(format!("colours must be finite numbers, got {c:?}"));
    }
    Ok(v.max(DVec3::ZERO))
}

/// A scene file's `[lighting]` table (either kind of space): how the lamps light the
/// scene ([`crate::scene::lighting::Lighting`]).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LightingSpec {
    /// `"images"` (every image in the cover) or `"nearest"` (the nearest copy).
    paths: Option<Spanned<String>>,
    /// How far the images are summed exactly, in inradii.
    reach: Option<Spanned<f64>>,
    /// The images beyond the reach by their mean.
    tail: Option<bool>,
    /// How many of the nearest images are shadowed.
    shadows: Option<Spanned<i64>>,
    /// The lamps' radius in inradii, for soft shadows (0: points).
    lamp_radius: Option<Spanned<f64>>,
    /// Shadow rays per shadowed image of a lamp with a radius (soft shadows).
    soft_samples: Option<Spanned<i64>>,
}

/// The lighting of a `[lighting]` table: its keys over the defaults, each checked.
pub(crate) fn lighting_of(
    spec: &Spanned<LightingSpec>,
) -> Result<crate::scene::lighting::Lighting, SpanError> {
    use crate::scene::lighting::{LightPaths, Lighting};
    let mut lighting = Lighting::default();
    let l = spec.get_ref();
    if let Some(p) = &l.paths {
        lighting.paths = LightPaths::from_name(p.get_ref()).ok_or_else(|| {
            (
                p.span(),
                format!(
                    "light paths must be \"images\" or \"nearest\", got {:?}",
                    p.get_ref()
                ),
            )
        })?;
    }
    if let Some(r) = &l.reach {
        lighting.reach_inradii = *r.get_ref();
    }
    if let Some(t) = l.tail {
        lighting.tail = t;
    }
    if let Some(k) = &l.shadows {
        lighting.shadows = u32::try_from(*k.get_ref())
            .ok()
            .filter(|k| *k <= Lighting::MAX_SHADOWS)
            .ok_or_else(|| {
                (
                    k.span(),
                    format!(
                        "shadows must be 0 to {} shadowed images, got {}",
                        Lighting::MAX_SHADOWS,
                        k.get_ref()
                    ),
                )
            })?;
    }
    if let Some(n) = &l.soft_samples {
        lighting.soft_samples = u32::try_from(*n.get_ref())
            .ok()
            .filter(|n| (1..=Lighting::MAX_SOFT_SAMPLES).contains(n))
            .ok_or_else(|| {
                (
                    n.span(),
                    format!(
                        "soft_samples must be 1 to {} shadow rays per image, got {}",
                        Lighting::MAX_SOFT_SAMPLES,
                        n.get_ref()
                    ),
                )
            })?;
    }
    if let Some(a) = &l.lamp_radius {
        lighting.lamp_radius_inradii = *a.get_ref();
        lighting.check().map_err(|m| (a.span(), m))?;
    }
    let span = l.reach.as_ref().map_or_else(|| spec.span(), Spanned::span);
    lighting.check().map_err(|m| (span, m))?;
    Ok(lighting)
}

/// A `[start]` table of the files whose positions are points of one chart (the product and
/// Nil spaces): the eye, what it looks at, the vertical field of view.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PointStartSpec {
    pub(crate) position: [f64; 3],
    pub(crate) look_at: Option<[f64; 3]>,
    pub(crate) fov: Option<f64>,
}

/// A `[[light]]` of those files: a point lamp.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PointLightSpec {
    pub(crate) position: [f64; 3],
}

/// A point written in a file, and where.
pub(crate) type SpannedPoint = ([f64; 3], std::ops::Range<usize>);

/// The one light those files may have: `None` for none, else its position (with its
/// span), or the error at the second one (`family` names the scene: "a product scene").
pub(crate) fn one_light(
    lights: &[Spanned<PointLightSpec>],
    family: &str,
) -> Result<Option<SpannedPoint>, SpanError> {
    match lights {
        [] => Ok(None),
        [light] => Ok(Some((light.get_ref().position, light.span()))),
        [_, second, ..] => Err((
            second.span(),
            format!("{family} has one light, this file has {}", lights.len()),
        )),
    }
}
