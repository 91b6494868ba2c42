//! The command under careless and hostile use: outputs that would destroy an input are
//! refused, failed or killed runs leave earlier files whole, tiny files that declare huge
//! counts are errors (under a memory limit), a closed pipe or a full disk is never a panic, and
//! suspicious inputs get a one-line error that names the file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_meshq")
}

fn meshq(args: &[&dyn AsRef<std::ffi::OsStr>]) -> Output {
    Command::new(bin())
        .args(args.iter().map(|a| a.as_ref()))
        .output()
        .expect("meshq runs")
}

/// Runs meshq with at most 1 GiB of address space: an allocation sized by a hostile count
/// fails (and would abort) instead of succeeding on a big machine.
fn meshq_limited(args: &[&dyn AsRef<std::ffi::OsStr>]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 1048576 && exec \"$0\" \"$@\"")
        .arg(bin())
        .args(args.iter().map(|a| a.as_ref()))
        .output()
        .expect("sh runs")
}

fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .join(name)
}

/// `count` random rays for `mesh` in `dir/rays.bin` and their closest hits in `dir/hits.bin`,
/// both written by the command.
fn rays_and_hits(mesh: &Path, dir: &Path, count: usize) -> (PathBuf, PathBuf) {
    let (rays, hits) = (dir.join("rays.bin"), dir.join("hits.bin"));
    let count = count.to_string();
    assert!(
        meshq(&[&"workload", &mesh, &"-o", &rays, &"--count", &count])
            .status
            .success()
    );
    assert!(
        meshq(&[&"raycast", &mesh, &"--rays", &rays, &"--out", &hits])
            .status
            .success()
    );
    (rays, hits)
}

/// A named pipe at `path` (`mkfifo`).
fn make_fifo(path: &Path) {
    assert!(Command::new("mkfifo").arg(path).status().unwrap().success());
}

/// A failure with status 1 and one stderr line containing `needle`, no panic.
fn refused(out: &Output, needle: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains(needle), "{stderr:?} lacks {needle:?}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn an_output_that_is_an_input_is_refused_and_nothing_is_touched() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("spot.obj");
    std::fs::copy(asset("spot.obj"), &mesh).unwrap();
    let original = std::fs::read(&mesh).unwrap();
    let blob = dir.path().join("spot.meshq");
    assert!(meshq(&[&"bake", &mesh, &"-o", &blob]).status.success());
    let rays = dir.path().join("rays.bin");
    assert!(
        meshq(&[&"workload", &mesh, &"-o", &rays, &"--count", &"100"])
            .status
            .success()
    );
    let ray_bytes = std::fs::read(&rays).unwrap();
    let blob_bytes = std::fs::read(&blob).unwrap();
    // The same file under another name (a hard link) is still the same file.
    let linked = dir.path().join("linked.obj");
    std::fs::hard_link(&mesh, &linked).unwrap();

    for args in [
        vec!["raycast", "M", "--rays", "R", "--out", "M"],
        vec!["raycast", "B", "--rays", "R", "--out", "R"],
        vec!["raycast", "B", "--rays", "R", "--out", "B"],
        vec!["closest", "B", "--points", "R", "--out", "B"],
        vec!["bake", "M", "-o", "M"],
        vec!["bake", "M", "-o", "L"],
        vec!["workload", "M", "-o", "M"],
        vec!["remesh", "M", "-o", "L"],
    ] {
        let args: Vec<std::ffi::OsString> = args
            .iter()
            .map(|a| match *a {
                "M" => mesh.clone().into_os_string(),
                "B" => blob.clone().into_os_string(),
                "R" => rays.clone().into_os_string(),
                "L" => linked.clone().into_os_string(),
                other => other.into(),
            })
            .collect();
        let args: Vec<&dyn AsRef<std::ffi::OsStr>> = args
            .iter()
            .map(|a| a as &dyn AsRef<std::ffi::OsStr>)
            .collect();
        refused(&meshq(&args), "the output is also an input");
    }
    assert_eq!(std::fs::read(&mesh).unwrap(), original);
    assert_eq!(std::fs::read(&rays).unwrap(), ray_bytes);
    assert_eq!(std::fs::read(&blob).unwrap(), blob_bytes);
}

#[test]
fn failed_and_killed_runs_leave_earlier_outputs_whole() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.obj");
    std::fs::copy(asset("spot.obj"), &good).unwrap();
    let (rays, hits) = rays_and_hits(&good, dir.path(), 1000);
    let before = std::fs::read(&hits).unwrap();
    // A run that fails (a NaN vertex) leaves the previous results as they were.
    let bad = dir.path().join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    refused(
        &meshq(&[&"raycast", &bad, &"--rays", &rays, &"--out", &hits]),
        "bad.obj",
    );
    assert_eq!(std::fs::read(&hits).unwrap(), before);

    // A bake killed part way (at several moments) leaves the old blob whole or the new one
    // complete, never a cut one.
    let blob = dir.path().join("bunny.meshq");
    let bunny = asset("stanford-bunny.obj");
    assert!(meshq(&[&"bake", &good, &"-o", &blob]).status.success());
    let old = std::fs::read(&blob).unwrap();
    for wait in [50u64, 200, 600] {
        let mut child = Command::new(bin())
            .args([
                "bake".as_ref(),
                bunny.as_os_str(),
                "-o".as_ref(),
                blob.as_os_str(),
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(wait));
        let _ = child.kill();
        let _ = child.wait();
        let now = std::fs::read(&blob).unwrap();
        let inspected = meshq(&[&"inspect", &blob]);
        assert!(
            now == old || inspected.status.success(),
            "killed after {wait} ms: {} bytes, inspect says {}",
            now.len(),
            String::from_utf8_lossy(&inspected.stderr)
        );
    }
    // What killed runs leave behind is cleaned up by the next run writing the same output;
    // a partial file another process still holds (locked while it writes) is left alone, as
    // are files of other outputs.
    let partials = |dir: &Path| -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".partial"))
            .collect();
        names.sort();
        names
    };
    let stale = dir.path().join(".meshq-bunny.meshq-AbC123.partial");
    std::fs::write(&stale, b"cut short").unwrap();
    let busy = dir.path().join(".meshq-bunny.meshq-Busy42.partial");
    let held = std::fs::File::create(&busy).unwrap();
    held.try_lock().unwrap();
    let other = dir.path().join(".meshq-other.bin-XyZ789.partial");
    std::fs::write(&other, b"not ours").unwrap();
    assert!(meshq(&[&"bake", &good, &"-o", &blob]).status.success());
    assert_eq!(
        partials(dir.path()),
        [
            ".meshq-bunny.meshq-Busy42.partial",
            ".meshq-other.bin-XyZ789.partial"
        ]
    );
    drop(held);
}

/// An output path that already names a pipe or a device (`/dev/null`, `/dev/stdout`, a named
/// pipe) is written in place: renaming a finished file over it, as other outputs are, would
/// leave a plain file where the pipe was (and, run as root with `--out /dev/null`, replace the
/// device). A named pipe stands for them all here; a reader `cat` waits on it, and gives up
/// after a minute if no writer ever comes (the pipe was replaced).
#[cfg(target_os = "linux")]
#[test]
fn an_output_that_is_a_pipe_is_written_through_not_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let dir = tempfile::tempdir().unwrap();
    let mesh = asset("spot.obj");
    let (rays, expected) = rays_and_hits(&mesh, dir.path(), 20_000);
    let pipe = dir.path().join("hits.pipe");
    make_fifo(&pipe);
    let reader = Command::new("timeout")
        .arg("60")
        .arg("cat")
        .arg(&pipe)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let run = meshq(&[&"raycast", &mesh, &"--rays", &rays, &"--out", &pipe]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let read = reader.wait_with_output().unwrap();
    assert!(read.status.success(), "no writer opened the pipe");
    // 20,000 records of 8 bytes went through the pipe (more than its 64 KB buffer), the same
    // bytes as written to a file.
    assert_eq!(read.stdout, std::fs::read(&expected).unwrap());
    assert!(std::fs::metadata(&pipe).unwrap().file_type().is_fifo());
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".partial"))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}

#[test]
fn tiny_files_that_declare_huge_counts_are_errors_under_a_memory_limit() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.meshq");
    let cases: [(&str, &[u8], &str); 8] = [
        (
            "count.ply",
            b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nend_header\n",
            "declares 4000000000 records",
        ),
        (
            "unknown.ply",
            b"ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement junk 4000000000\nproperty uchar q\nend_header\n",
            "element 'junk' declares",
        ),
        (
            "faces.ply",
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            "element 'face' declares",
        ),
        (
            "noz.ply",
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 1\n3 0 1 2\n",
            "no 'z' property",
        ),
        (
            "header.ply",
            b"ply\nformat ascii 1.0\nelement vertex\n\tend_header\n",
            "header.ply",
        ),
        ("short.stl", &stl(1, 2), "header says 1 triangles"),
        ("long.stl", &stl(3, 2), "header says 3 triangles"),
        ("huge.stl", &stl(4_000_000_000, 1), "header says 4000000000 triangles"),
    ];
    for (name, bytes, needle) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        refused(&meshq_limited(&[&"bake", &path, &"-o", &out]), needle);
    }
    // Materials are never read: `mtllib` naming a device or a pipe neither hangs nor eats
    // memory.
    let fifo = dir.path().join("pipe.mtl");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    for target in ["/dev/zero", "pipe.mtl"] {
        let obj = dir.path().join("m.obj");
        std::fs::write(
            &obj,
            format!("mtllib {target}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        )
        .unwrap();
        let run = meshq_limited(&[&"bake", &obj, &"-o", &out]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
    }
    // A mesh path that is a pipe is refused, not waited on.
    let fifo_mesh = dir.path().join("pipe.obj");
    make_fifo(&fifo_mesh);
    refused(
        &meshq(&[&"bake", &fifo_mesh, &"-o", &out]),
        "not a regular file",
    );
}

/// A binary STL whose header says `declared` triangles, holding `stored`.
fn stl(declared: u32, stored: usize) -> Vec<u8> {
    let mut bytes = vec![0u8; 80];
    bytes.extend_from_slice(&declared.to_le_bytes());
    for _ in 0..stored {
        for v in [
            0.0f32, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0,
        ] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        bytes.extend_from_slice(&[0, 0]);
    }
    bytes
}

#[test]
fn a_closed_pipe_or_a_full_disk_is_never_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let blob = dir.path().join("spot.meshq");
    assert!(
        meshq(&[&"bake", &asset("spot.obj"), &"-o", &blob])
            .status
            .success()
    );
    // A full disk on stdout: one line, status 1.
    if Path::new("/dev/full").exists() {
        for args in [
            vec![&"inspect" as &dyn AsRef<std::ffi::OsStr>, &blob],
            vec![&"inspect", &blob, &"--json"],
            vec![
                &"bake",
                &asset("spot.obj"),
                &"-o",
                &dir.path().join("b.meshq"),
            ],
            // Help and version text are written and checked like any output.
            vec![&"--help"],
            vec![&"--version"],
            vec![&"inspect", &"--help"],
        ] {
            let out = Command::new(bin())
                .args(args.iter().map(|a| a.as_ref()))
                .stdout(std::fs::File::create("/dev/full").unwrap())
                .output()
                .unwrap();
            refused(&out, "No space left on device");
        }
    }
    // A reader that closed its end first: quiet, with the status of a command stopped by
    // SIGPIPE. The read end is closed before the command starts (closing it after the spawn
    // raced with the command: a fast one wrote into the pipe's buffer and exited 0).
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(bin())
        .args(["inspect".as_ref(), blob.as_os_str()])
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(141), "{:?}", out);
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(bin())
        .arg("--help")
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(141), "--help: {:?}", out);
    // An output path that is the closed pipe (`--out /dev/stdout`) is the same case.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(bin())
        .args(["workload".as_ref(), asset("spot.obj").as_os_str()])
        .args(["-o", "/dev/stdout", "--count", "100000"])
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(141), "-o /dev/stdout: {:?}", out);
    // A usage error is still clap's text on stderr, status 2.
    let out = meshq(&[&"--no-such-flag"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unexpected argument"));
}

#[test]
fn suspicious_inputs_get_errors_or_documented_answers() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = asset("spot.obj");
    // A workload needs a mesh with bounds.
    let empty = dir.path().join("empty.obj");
    std::fs::write(&empty, "# nothing\n").unwrap();
    refused(
        &meshq(&[&"workload", &empty, &"-o", &dir.path().join("w.bin")]),
        "no triangles",
    );
    // Rays from a pipe are counted as they are read.
    let rays = dir.path().join("rays.bin");
    assert!(
        meshq(&[&"workload", &mesh, &"-o", &rays, &"--count", &"500"])
            .status
            .success()
    );
    let hits = dir.path().join("hits.bin");
    let out = Command::new(bin())
        .args([
            "raycast".as_ref(),
            mesh.as_os_str(),
            "--rays".as_ref(),
            "/dev/stdin".as_ref(),
            "--out".as_ref(),
            hits.as_os_str(),
            "--json".as_ref(),
        ])
        .stdin(std::fs::File::open(&rays).unwrap())
        .output()
        .unwrap();
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["rays"], 500);
    assert_eq!(std::fs::metadata(&hits).unwrap().len(), 500 * 8);
}

/// `--hits 4096` keeps memory flat: rays are read in chunks of at most a million records, so
/// 5,000 rays with 4,096 records each run under 256 MiB of address space (sized by rays × N
/// up front, the records alone would take 320 MiB).
#[test]
fn many_hits_per_ray_run_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = asset("spot.obj");
    let rays = dir.path().join("rays.bin");
    let count = "5000";
    assert!(
        meshq(&[&"workload", &mesh, &"-o", &rays, &"--count", &count])
            .status
            .success()
    );
    let out = Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 262144 && exec \"$0\" \"$@\"")
        .arg(bin())
        .args(["raycast"])
        .arg(&mesh)
        .arg("--rays")
        .arg(&rays)
        .args(["--hits", "4096", "--out", "/dev/null", "--json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["rays"], 5000, "{summary}");
}

/// An OBJ of `n` zero-area triangles at one point (`point`) or `n` copies of one triangle.
fn piled_obj(path: &Path, n: usize, at_one_point: bool) {
    let mut text = String::new();
    if at_one_point {
        for t in 0..n {
            text.push_str("v 0.25 0.5 0.75\nv 0.25 0.5 0.75\nv 0.25 0.5 0.75\n");
            text.push_str(&format!("f {} {} {}\n", 3 * t + 1, 3 * t + 2, 3 * t + 3));
        }
    } else {
        text.push_str("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        text.push_str(&"f 1 2 3\n".repeat(n));
    }
    std::fs::write(path, text).unwrap();
}

/// `check` on triangles that no box separates ends in one error naming the check and the flag
/// that raises its budget, in bounded work, instead of testing every pair; within the budget
/// it reports the pairs and the zero-area triangles.
#[test]
fn checks_on_piled_up_triangles_stop_at_their_budget() {
    let dir = tempfile::tempdir().unwrap();
    let points = dir.path().join("point.obj");
    piled_obj(&points, 50_000, true);
    let out = meshq(&[&"check", &points]);
    refused(&out, "self-intersection check");
    refused(&out, "--max-pair-tests");
    let against = meshq(&[&"check", &points, &"--against", &points]);
    refused(&against, "--max-pair-tests");

    let copies = dir.path().join("same.obj");
    piled_obj(&copies, 1_000, false);
    let out = meshq(&[&"check", &copies, &"--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // Every pair of copies lies on each other.
    assert_eq!(
        report["self_intersecting_pairs"],
        1_000 * 999 / 2,
        "{report}"
    );
    assert!(report["self_pairs_tested"].as_u64().unwrap() <= (1 << 20) + 512 * 1_000);
    let small = meshq(&[&"check", &copies, &"--max-pair-tests", &"1000"]);
    refused(&small, "budget of 1000 pairs is spent");

    let few = dir.path().join("few.obj");
    piled_obj(&few, 10, true);
    let out = meshq(&[&"check", &few, &"--json"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["degenerate_triangles"], 10, "{report}");
    assert_eq!(report["self_intersecting_pairs"], 0, "{report}");
}

/// `remesh` of triangles that all span one box writes its result and reports the distance
/// from the samples its test budget paid for, saying so, instead of a closest-point search per
/// sample over every triangle (the square of the count: 10.3 s at 10,000 triangles before);
/// `--max-distance-tests` raises the budget until every sample is measured.
#[test]
fn remeshing_triangles_no_box_separates_reports_a_bounded_distance() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("overlap.obj");
    let n = 10_000;
    let mut text = String::new();
    for i in 0..n {
        let t = i as f32 / n as f32;
        text.push_str(&format!(
            "v -1 {} -1\nv 1 {} -1\nv {} 0 1\n",
            -1.0 + 2.0 * t,
            1.0 - 2.0 * t,
            2.0 * t - 1.0
        ));
    }
    for i in 0..n {
        text.push_str(&format!("f {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3));
    }
    std::fs::write(&input, text).unwrap();
    let output = dir.path().join("out.ply");
    let out = meshq(&[&"remesh", &input, &"-o", &output, &"--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(output.exists());
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let samples = report["distance_samples"].as_u64().unwrap();
    let measured = report["distance_samples_measured"].as_u64().unwrap();
    let tested = report["distance_tests"].as_u64().unwrap();
    let triangles = n + report["after"]["triangles"].as_u64().unwrap();
    assert_eq!(samples, 4 * triangles, "{report}");
    assert!(measured > 0 && measured < samples, "{report}");
    assert!(tested <= (1 << 20) + 256 * triangles, "{report}");
    let text = meshq(&[&"remesh", &input, &"-o", &output]);
    let said = String::from_utf8_lossy(&text.stdout);
    assert!(said.contains("--max-distance-tests"), "{said}");

    // A small input of the same kind, with room for every sample: all measured.
    let few = dir.path().join("few.obj");
    std::fs::write(
        &few,
        "v -1 -1 -1\nv 1 1 -1\nv -1 0 1\nv -1 1 -1\nv 1 -1 -1\nv 1 0 1\nf 1 2 3\nf 4 5 6\n",
    )
    .unwrap();
    let out = meshq(&[
        &"remesh",
        &few,
        &"-o",
        &output,
        &"--json",
        &"--max-distance-tests",
        &"100000000",
    ]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        report["distance_samples_measured"], report["distance_samples"],
        "{report}"
    );
}

/// `inspect` validates a blob as the loaders do: a BVH blob (resealed, so its checksum
/// passes) whose stored triangle names a vertex that does not exist is refused by `inspect`
/// with the same error as by `raycast`, not described as a sound blob.
#[test]
fn inspect_refuses_what_the_loaders_refuse() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = asset("spot.obj");
    let blob = dir.path().join("spot.meshq");
    assert!(meshq(&[&"bake", &mesh, &"-o", &blob]).status.success());
    assert!(meshq(&[&"inspect", &blob]).status.success());
    let mut bytes = std::fs::read(&blob).unwrap();
    let loaded = meshq_tests::load_obj(&mesh);
    // The first stored triangle whose 12 bytes occur once in the blob: its first index
    // becomes 999,999.
    let at = loaded
        .triangles
        .iter()
        .find_map(|t| {
            let needle: Vec<u8> = t.iter().flat_map(|i| i.to_le_bytes()).collect();
            let mut hits = bytes.windows(12).enumerate().filter(|(_, w)| *w == needle);
            match (hits.next(), hits.next()) {
                (Some((at, _)), None) => Some(at),
                _ => None,
            }
        })
        .expect("a stored triangle");
    bytes[at..at + 4].copy_from_slice(&999_999u32.to_le_bytes());
    meshq::advanced::reseal(&mut bytes).unwrap();
    let damaged = dir.path().join("damaged.meshq");
    std::fs::write(&damaged, &bytes).unwrap();
    let inspect = meshq(&[&"inspect", &damaged]);
    refused(&inspect, "invalid blob");
    let rays = dir.path().join("rays.bin");
    assert!(
        meshq(&[&"workload", &mesh, &"-o", &rays, &"--count", &"10"])
            .status
            .success()
    );
    let raycast = meshq(&[
        &"raycast",
        &damaged,
        &"--rays",
        &rays,
        &"--out",
        &"/dev/null",
    ]);
    refused(&raycast, "cannot use blob");
    // The same cause, word for word, after each command's own context.
    let cause = |out: &Output| {
        let text = String::from_utf8_lossy(&out.stderr).trim_end().to_string();
        text.rsplit(": ").next().unwrap_or_default().to_string()
    };
    assert_eq!(cause(&inspect), cause(&raycast));
}

/// A point so far away that squared distances overflow `f32` (2e19 from a unit triangle) gets
/// its nearest triangle and a finite distance, not "nothing found".
#[test]
fn closest_points_from_very_far_away_are_answered() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("tri.obj");
    std::fs::write(&mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let points = dir.path().join("far.bin");
    let coords: [f32; 6] = [2e19, 0.0, 0.0, 0.0, -3e30, 0.0];
    let bytes: Vec<u8> = coords.iter().flat_map(|c| c.to_le_bytes()).collect();
    std::fs::write(&points, bytes).unwrap();
    let out = dir.path().join("closest.bin");
    let run = meshq(&[&"closest", &mesh, &"--points", &points, &"--out", &out]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let records = std::fs::read(&out).unwrap();
    let word = |i: usize| <[u8; 4]>::try_from(&records[4 * i..4 * i + 4]).unwrap();
    for (k, want) in [(0usize, 2e19f64 - 1.0), (1, 3e30)] {
        let distance = f64::from(f32::from_le_bytes(word(2 * k)));
        let triangle = u32::from_le_bytes(word(2 * k + 1));
        assert_eq!(triangle, 0, "point {k}");
        assert!(
            (distance - want).abs() <= want * 1e-6,
            "point {k}: {distance}"
        );
    }
}
