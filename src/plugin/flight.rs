//! Replaying and recording flights on the curved-space cameras: the resources and systems
//! over the flight maths of [`crate::scene::flight`].

use crate::plugin::components::{ActiveSpace, CurvedSpaceCamera, PlayerFrame};
use crate::scene::flight::{
    DEFAULT_FLIGHT_FOV, Flight, FlightSource, MAX_FLIGHT_SECONDS, MAX_KEYS, flight_text,
    recorded_key,
};
use crate::space::motion::CoverFlight;
use crate::space::{AnySpace, Holonomy, Space};
use bevy::prelude::*;
use glam::{DMat4, DVec3};

/// A flight replayed on every curved-space camera (`walk --replay FILE`), in the family of
/// its flight type (a [`Flight`] for the constant-curvature spaces, the default; a
/// [`crate::trace::product::flight::ProductFlight`] for H²×R and S²×R): while this resource
/// exists, [`replay_flight`] sets each camera's frame to the flight's frame at the time
/// since the replay began (looping when `looped`), after the player's own motion.
#[derive(Resource, Clone, Debug)]
pub struct FlightReplay<F: CoverFlight = Flight> {
    /// The flight, made for the active space.
    pub flight: F,
    /// Start again at the end.
    pub looped: bool,
    /// The clock's time when the replay began (set by the first run).
    pub started: Option<f64>,
}

/// A product flight's replay (H²×R, S²×R).
pub type ProductFlightReplay = FlightReplay<crate::trace::product::flight::ProductFlight>;

/// A replay of a Nil flight.
pub type NilFlightReplay = FlightReplay<crate::trace::nil::flight::NilFlight>;

/// The replay of an SL̃(2,R) flight.
pub type Sl2rFlightReplay = FlightReplay<crate::trace::sl2r::flight::Sl2rFlight>;

impl<F: CoverFlight> FlightReplay<F> {
    /// A replay of `flight` from the next frame on.
    #[must_use]
    pub fn new(flight: F, looped: bool) -> Self {
        Self {
            flight,
            looped,
            started: None,
        }
    }

    /// The flight's time at clock time `now`: from the first call on, looping or held at
    /// the end.
    #[must_use]
    pub fn flight_time(&mut self, now: f64) -> f64 {
        let start = *self.started.get_or_insert(now);
        let t = (now - start).max(0.0);
        let duration = self.flight.duration();
        if duration <= 0.0 {
            0.0
        } else if self.looped {
            t % duration
        } else {
            t.min(duration)
        }
    }
}

/// Drives the cameras along a [`FlightReplay`] of the flight type `F` (registered by the
/// plugin for each family; does nothing without the resource or in a space of another
/// family). Runs after the frames are wrapped, so it wins over the player's own motion; a
/// camera's holonomy becomes the flight's way from its first key, so the panel's crossings
/// are the flight's.
pub fn replay_flight<F: CoverFlight>(
    time: Res<Time>,
    active: Res<ActiveSpace>,
    replay: Option<ResMut<FlightReplay<F>>>,
    mut cameras: Query<(&mut PlayerFrame, Option<&mut Holonomy>), With<CurvedSpaceCamera>>,
) {
    let (Some(mut replay), Some(space)) = (replay, active.space.get::<F::Space>()) else {
        return;
    };
    let t = replay.flight_time(time.elapsed_secs_f64());
    let (frame, crossed) = replay.flight.frame_in_cell(space, t);
    for (mut f, holonomy) in &mut cameras {
        f.0 = frame;
        if let Some(mut h) = holonomy {
            let mut way = Holonomy::default();
            for c in &crossed {
                way.record_crossing(c);
            }
            *h = way;
        }
    }
}

/// Records the first curved-space camera's path as a flight file (`walk --record FILE`):
/// while this resource exists, [`record_flight`] adds a key every `interval` seconds — the
/// camera's frame carried back through the faces it crossed into the universal cover, as
/// `position`, `look_at` and `up` — and writes the file at most once a second and when the
/// app exits. `walk --replay FILE` and `flight FILE` play it back; at the keys' times the
/// replay's frames are the walk's.
#[derive(Resource, Clone, Debug)]
pub struct FlightRecorder {
    /// The file written.
    pub path: std::path::PathBuf,
    /// The space or scene named in it.
    pub source: FlightSource,
    /// Seconds between keys.
    pub interval: f64,
    /// Keys so far: time, position, look_at, up (geodesic coordinates in inradii).
    pub keys: Vec<(f64, DVec3, DVec3, DVec3)>,
    /// The camera's vertical field of view.
    pub fov: f64,
    /// Why recording stopped early, if it did (the keys so far are kept).
    pub stopped: Option<String>,
    started: Option<f64>,
    space: Option<String>,
    last_write: Option<f64>,
    unwritten: bool,
}

impl FlightRecorder {
    /// A recorder writing to `path`, a key every `interval` seconds.
    #[must_use]
    pub fn new(path: std::path::PathBuf, source: FlightSource, interval: f64) -> Self {
        Self {
            path,
            source,
            interval: interval.max(1e-3),
            keys: Vec::new(),
            fov: DEFAULT_FLIGHT_FOV,
            stopped: None,
            started: None,
            space: None,
            last_write: None,
            unwritten: false,
        }
    }

    /// The flight file's text.
    #[must_use]
    pub fn text(&self) -> String {
        flight_text(&self.source, self.fov, &self.keys)
    }

    /// Writes the file (whole or not at all).
    pub fn write(&mut self) -> Result<(), String> {
        if self.keys.is_empty() {
            return Ok(());
        }
        crate::files::write_atomic(&self.path, self.text().as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", self.path.display()))?;
        self.unwritten = false;
        Ok(())
    }

    /// Adds the key of a camera at clock time `now`, if one is due.
    pub fn record(
        &mut self,
        space: &Space,
        space_id: &str,
        now: f64,
        frame: DMat4,
        holonomy: &Holonomy,
        fov: f64,
    ) {
        self.record_key(space_id, now, fov, || recorded_key(space, frame, holonomy));
    }

    /// Adds a key at clock time `now`, if one is due: `key` gives the camera's position,
    /// look-at and up points in the flight file's coordinates of the space's family
    /// ([`recorded_key`], [`crate::trace::product::flight::recorded_product_key`],
    /// [`crate::trace::nil::flight::recorded_nil_key`]), or
    /// `None` where the file cannot hold them.
    pub fn record_key(
        &mut self,
        space_id: &str,
        now: f64,
        fov: f64,
        key: impl FnOnce() -> Option<(DVec3, DVec3, DVec3)>,
    ) {
        if self.stopped.is_some() {
            return;
        }
        if self.space.get_or_insert_with(|| space_id.to_string()) != space_id {
            self.stop("the space changed; the keys so far are kept".into());
            return;
        }
        let start = *self.started.get_or_insert(now);
        let t = now - start;
        if let Some(last) = self.keys.last()
            && t - last.0 < self.interval - 1e-9
        {
            return;
        }
        if self.keys.len() >= MAX_KEYS || t > MAX_FLIGHT_SECONDS {
            self.stop(format!(
                "a flight holds at most {MAX_KEYS} keys and {MAX_FLIGHT_SECONDS} s"
            ));
            return;
        }
        match key() {
            Some((p, look, up)) => {
                self.keys.push((t, p, look, up));
                self.fov = fov;
                self.unwritten = true;
            }
            None => self.stop(format!(
                "at {t:.2} s the walk left what a flight file can hold (in S³ the hemisphere about the centre; a cell centred off the origin; π round S² or a million circles up a product's fibre; a thousand crossings from a Nil box); the keys so far are kept"
            )),
        }
    }

    fn stop(&mut self, why: String) {
        warn!("recording stopped: {why}");
        self.stopped = Some(why);
    }
}

/// Adds a key of the first curved-space camera to the [`FlightRecorder`] when one is due,
/// and writes the file at most once a second (registered by the plugin; does nothing
/// without the resource).
pub fn record_flight(
    time: Res<Time>,
    active: Res<ActiveSpace>,
    recorder: Option<ResMut<FlightRecorder>>,
    cameras: Query<(&PlayerFrame, &Holonomy, &CurvedSpaceCamera)>,
) {
    let Some(mut recorder) = recorder else {
        return;
    };
    if let Err(e) = active.space.supports(crate::space::Feature::RecordFlight) {
        if recorder.stopped.is_none() {
            recorder.stop(e.to_string());
        }
        return;
    }
    let Some((frame, holonomy, camera)) = cameras.iter().next() else {
        return;
    };
    let now = time.elapsed_secs_f64();
    recorder.record_key(&active.id, now, camera.fov_y_degrees, || {
        match &active.space {
            AnySpace::Constant(space) => recorded_key(space, frame.0, holonomy),
            AnySpace::Product(space) => {
                crate::trace::product::flight::recorded_product_key(space, frame.0, holonomy)
            }
            AnySpace::Nil(space) => {
                crate::trace::nil::flight::recorded_nil_key(space, frame.0, holonomy)
            }
            AnySpace::Sl2r(space) => {
                crate::trace::sl2r::flight::recorded_sl2r_key(space, frame.0, holonomy)
            }
        }
    });
    if recorder.unwritten && recorder.last_write.is_none_or(|w| now - w >= 1.0) {
        recorder.last_write = Some(now);
        if let Err(e) = recorder.write() {
            recorder.stop(e);
        }
    }
}

/// Writes the recorded flight when the app exits.
pub fn finish_recording(
    mut exits: MessageReader<AppExit>,
    recorder: Option<ResMut<FlightRecorder>>,
) {
    if exits.read().next().is_none() {
        return;
    }
    if let Some(mut r) = recorder
        && r.unwritten
    {
        match r.write() {
            Ok(()) => info!("wrote the recorded flight to {}", r.path.display()),
            Err(e) => error!("{e}"),
        }
    }
}
