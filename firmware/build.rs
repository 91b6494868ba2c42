//! Links with cortex-m-rt's script and this board's `memory.x`, and points the firmware at the
//! blob to place in flash. The blob is baked by the `meshq` command (`scripts/firmware.sh`
//! does it); it is never committed.

use std::env;
use std::path::PathBuf;

/// Cargo feature → bundled mesh (file stem in `assets/`).
/// `remesh` remeshes the small UV sphere instead of querying a mesh.
const MESHES: [(&str, &str); 3] = [
    ("BUNNY", "stanford-bunny"),
    ("SPOT", "spot"),
    ("REMESH", "uv-sphere"),
];

fn main() {
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("set by cargo"));
    std::fs::copy(manifest.join("memory.x"), out.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg=-Tlink.x");
    println!("cargo:rerun-if-changed=memory.x");

    let chosen: Vec<&str> = MESHES
        .iter()
        .filter(|(feature, _)| env::var_os(format!("CARGO_FEATURE_{feature}")).is_some())
        .map(|(_, stem)| *stem)
        .collect();
    let [stem] = chosen[..] else {
        panic!("enable exactly one of --features bunny, spot or remesh");
    };

    // `--features octree` places the mesh's octree blob in flash instead of its BVH blob,
    // `--features spatial` its BVH blob built with spatial splits, and `--features winding`
    // its BVH blob with the winding-number expansions.
    let (suffix, bake_flag) = if env::var_os("CARGO_FEATURE_OCTREE").is_some() {
        ("-octree", " --structure octree")
    } else if env::var_os("CARGO_FEATURE_WINDING").is_some() {
        ("-winding", " --winding")
    } else if env::var_os("CARGO_FEATURE_SPATIAL").is_some() {
        ("-spatial", " --spatial-splits")
    } else {
        ("", "")
    };
    println!("cargo:rerun-if-env-changed=MESHQ_BLOB_DIR");
    let dir = env::var_os("MESHQ_BLOB_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| manifest.join("../target/firmware-blobs"));
    let blob = dir.join(format!("{stem}{suffix}.meshq"));
    println!("cargo:rerun-if-changed={}", blob.display());
    assert!(
        blob.is_file(),
        "{} is missing: bake it first with `meshq bake assets/{stem}.obj -o {}{}` \
         (scripts/firmware.sh does this), or point MESHQ_BLOB_DIR at a folder holding it",
        blob.display(),
        blob.display(),
        bake_flag
    );
    println!("cargo:rustc-env=MESHQ_BLOB={}", blob.display());
    println!("cargo:rustc-env=MESHQ_MESH={stem}");
}
