//! The root finding the families' exact methods share — a bracketed root by Newton's steps
//! safeguarded by bisection — and how much of it they did: counters on
//! this thread of the iterations of their root finders (Nil's exits, distances and balls,
//! SL̃(2,R)'s Newton polish of the closed-form exits, its distances and balls) and of the
//! safe (Lipschitz) steps towards objects. The bench reads the counters before and after a
//! picture to report them per pixel; nothing else reads them, and counting costs one
//! thread-local add.

use crate::geometry::Real;

thread_local! {
    /// Iterations of a root finder on this thread (see [`work`]).
    static ROOT_ITERATIONS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    /// Safe (Lipschitz) steps towards objects on this thread.
    static SAFE_STEPS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// The work the exact methods have done on this thread so far: the iterations of their
/// root finders and the safe steps towards objects.
#[must_use]
pub fn work() -> (u64, u64) {
    (ROOT_ITERATIONS.get(), SAFE_STEPS.get())
}

/// Counts one safe step towards an object (for [`work`]).
pub(crate) fn count_safe_step() {
    SAFE_STEPS.set(SAFE_STEPS.get() + 1);
}

/// Counts one iteration of a root finder (for [`work`]).
pub(crate) fn count_root_iteration() {
    ROOT_ITERATIONS.set(ROOT_ITERATIONS.get() + 1);
}

/// Half way between `lo` and `hi`.
pub(crate) fn half_way<R: Real>(lo: R, hi: R) -> R {
    R::from_f64(0.5) * (lo + hi)
}

/// Most steps of [`bracketed_root`]: each Newton step that fails is replaced by a bisection,
/// so 200 reach double-double's last bit from any bracket.
const MAX_ROOT_STEPS: usize = 200;

/// The root of `f` (its value and rate at a point) in the bracket `(lo, hi)`, where it
/// changes sign once, from `start`: Newton's steps where they stay inside the bracket,
/// bisection where they do not, until the bracket stops shrinking. `below(value)` says
/// whether a value lies on `lo`'s side of the root. Nil's horizontal exits, its distance's
/// winding angle and its balls' hits, and SL̃(2,R)'s balls' hits, all finish with it.
pub(crate) fn bracketed_root<R: Real>(
    f: &impl Fn(R) -> (R, R),
    (lo, hi): (R, R),
    start: R,
    below: impl Fn(R) -> bool,
) -> R {
    let zero = R::ZERO;
    let (mut lo, mut hi) = (lo, hi);
    let mut t = start;
    for _ in 0..MAX_ROOT_STEPS {
        count_root_iteration();
        let (value, rate) = f(t);
        if value == zero {
            return t;
        }
        if below(value) {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - value / rate;
        let next = if rate != zero && newton > lo && newton < hi {
            newton
        } else {
            half_way(lo, hi)
        };
        if next == t || !(lo < hi) {
            break;
        }
        t = next;
    }
    t
}
