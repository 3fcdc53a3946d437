//! Flight files: hostile numbers, cut and scrambled texts.

use super::*;
use bevy_curved_spaces::space::motion::CoverFlight as _;

/// The shipped flight files (constant curvature, two products, SL̃(2,R)), and a
/// recorded-style one with `up`, as texts.
fn flight_texts() -> Vec<String> {
    let shipped = std::fs::read_to_string(
        manifest().join("assets/flights/seifert_weber_through_a_face.toml"),
    )
    .unwrap();
    let recorded = "space = \"poincare\"\nfov = 70\n\n[[key]]\ntime = 0.0\nposition = [0.1, 0.0, 0.2]\n\
                    look_at = [0.1, 0.0, -0.3]\nup = [0.1, 0.5, 0.2]\n\n[[key]]\ntime = 1.5\n\
                    position = [0.1, 0.2, -0.6]\nlook_at = [0.1, 0.2, -1.1]\nup = [0.1, 0.7, -0.6]\n"
        .to_string();
    let product =
        |name: &str| std::fs::read_to_string(manifest().join("assets/flights").join(name)).unwrap();
    vec![
        shipped,
        recorded,
        product("bitorus_through_a_side.toml"),
        product("turned_sphere_up_the_fibre.toml"),
        product("unit_tangent_past_the_stack.toml"),
    ]
}

/// A flight text parsed, made for its space and sampled: a flight or an error, never a
/// panic, within the time bound.
fn flight_outcome(text: &str) {
    use bevy_curved_spaces::scene::flight::{Flight, parse_flight};
    use bevy_curved_spaces::space::product::{ProductOrFlat, product_space};
    use bevy_curved_spaces::trace::product::flight::ProductFlight;
    let started = Instant::now();
    if let Ok(file) = parse_flight(text, "fuzz.toml")
        && let Some(id) = &file.space
        && let Ok(space) =
            bevy_curved_spaces::space::resolve_space(id, Path::new(""), &Default::default())
        && let Ok(flight) = Flight::new(&space, &file)
    {
        for t in [0.0, 0.5 * flight.duration(), flight.duration(), 1e9] {
            let f = flight.frame(&space, t);
            assert!(f.is_finite(), "a non-finite frame at {t} s from:\n{text}");
        }
    }
    // A product space's flight: the frames stay finite and in the cell.
    if let Ok(file) = parse_flight(text, "fuzz.toml")
        && let Some(id) = &file.space
        && let Some(Ok(ProductOrFlat::Product(space))) = product_space(id)
        && let Ok(flight) = ProductFlight::new(&space, &file)
    {
        for t in [0.0, 0.5 * flight.duration(), flight.duration(), 1e9] {
            let f = flight.frame(&space, t);
            assert!(f.is_finite(), "a non-finite frame at {t} s from:\n{text}");
            assert!(
                space.outside_by(f.w_axis) < 1e-6,
                "a frame outside the cell at {t} s from:\n{text}"
            );
        }
    }
    // An SL̃(2,R) flight: the frames stay finite and in the cell.
    if let Ok(file) = parse_flight(text, "fuzz.toml")
        && let Some(id) = &file.space
        && let Some(Ok(space)) = bevy_curved_spaces::space::sl2r::sl2r_space(id)
        && let Ok(flight) = bevy_curved_spaces::trace::sl2r::flight::Sl2rFlight::new(&file)
    {
        for t in [0.0, 0.5 * flight.duration(), flight.duration(), 1e9] {
            let f = flight.camera(&space, t).frame;
            assert!(f.is_finite(), "a non-finite frame at {t} s from:\n{text}");
            let p = f.w_axis;
            assert!(
                space.sides().iter().all(|s| {
                    s.normal[0].hi * p.x + s.normal[1].hi * p.y + s.normal[2].hi * p.z < 1e-6
                }),
                "a frame outside the cell at {t} s from:\n{text}"
            );
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    assert!(seconds < 10.0, "{seconds:.1} s for:\n{text}");
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xf117),
        ..ProptestConfig::default()
    })]

    /// A number of a flight file replaced by a hostile one.
    #[test]
    fn flight_files_with_hostile_numbers(which in 0usize..5, slot in 0usize..64, value in 0usize..HOSTILE.len()) {
        let texts = flight_texts();
        let text = &texts[which];
        let spots = numbers(text);
        let spot = spots[slot % spots.len()].clone();
        flight_outcome(&format!("{}{}{}", &text[..spot.start], HOSTILE[value], &text[spot.end..]));
    }

    /// A flight file cut short, or with random characters inserted.
    #[test]
    fn flight_files_cut_and_scrambled(which in 0usize..5, cut in 0.0f64..1.0, junk in "[ -~\\n]{0,24}") {
        let texts = flight_texts();
        let text = &texts[which];
        let mut at = (cut * text.len() as f64) as usize;
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        flight_outcome(&text[..at]);
        flight_outcome(&format!("{}{junk}{}", &text[..at], &text[at..]));
    }
}
