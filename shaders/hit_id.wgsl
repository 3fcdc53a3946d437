// What a ray met, for the benchmark's comparison with the CPU reference.
// The Rust twin: `trace (TracedRay::id)`.
#define_import_path curved_spaces::hit_id

#import curved_spaces::layout::{ball_count, tube_count}

#ifdef HIT_ID
// What the ray met (trace::TracedRay::id): object index + 1 (balls, then tubes; 0 for
// none), crossings, a hash of the faces crossed, and how it ended (1 hit, 2 fog, 3 budget).
var<private> hit_id: vec4<u32>;
const FNV_OFFSET: u32 = 2166136261u;

// The object's place in the GPU's lists (gpu::gpu_object_indices): balls, tubes, globes,
// discs, mesh instances, then the avatar's images.
fn object_number(kind: u32, index: u32) -> u32 {
    var base = 0u;
    var counts = array<u32, 5>(0u, 0u, 0u, 0u, 0u);
#ifdef BALLS
    counts[0] = ball_count();
#endif
#ifdef TUBES
    counts[1] = tube_count();
#endif
#ifdef GLOBES
    counts[2] = #{GLOBE_COUNT}u;
#endif
#ifdef DISCS
    counts[3] = #{DISC_COUNT}u;
#endif
#ifdef INSTANCES
    counts[4] = #{INSTANCE_COUNT}u;
#endif
    for (var k = 1u; k < kind; k += 1u) {
        base += counts[k - 1u];
    }
    return base + index;
}
const FNV_PRIME: u32 = 16777619u;
#endif
