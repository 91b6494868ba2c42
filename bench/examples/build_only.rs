//! Profiling aid: builds the bunny BVH repeatedly.
use meshq::bvh::BuildConfig;
use meshq_tests::{OwnedBvh, load_mesh};
fn main() {
    let l = load_mesh("stanford-bunny");
    let mesh = l.valid();
    let t = std::time::Instant::now();
    for _ in 0..20 {
        std::hint::black_box(OwnedBvh::build(&mesh, &BuildConfig::default()).ok());
    }
    println!("{:.2} ms per build", t.elapsed().as_secs_f64() * 1e3 / 20.0);
}
