//! Creases under remeshing: a fold sampled far more finely than the target length is
//! coarsened along its line, stays sharp and straight, and keeps its ends.

use meshq::mesh::MeshRef;
use meshq::owned::Remeshed;
use meshq::remesh::{EdgeTarget, RemeshConfig};

/// Length of the fold, along x.
const LENGTH: f32 = 4.0;
/// Samples along the fold: 1/64 of the length apart, a quarter of the target length.
const ALONG: u32 = 65;
/// Rows across each face, from the fold out to 1.
const ACROSS: u32 = 4;
/// The target edge length.
const TARGET: f32 = 0.25;

/// Two unit-wide faces meeting at a right angle along the x axis: one in the plane z = 0
/// (y from 0 to 1), one in the plane y = 0 (z from 0 to 1). Both are gridded with
/// [`ALONG`] columns, so the fold's edges are a quarter of [`TARGET`] long.
fn folded_strip() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    // Rows k = -ACROSS..=ACROSS: k < 0 on the upright face (z = -k/ACROSS), k ≥ 0 on the
    // floor (y = k/ACROSS); row 0 is the fold.
    let rows = -(ACROSS as i32)..=(ACROSS as i32);
    for k in rows.clone() {
        for i in 0..ALONG {
            let x = LENGTH * i as f32 / (ALONG - 1) as f32;
            let across = k.unsigned_abs() as f32 / ACROSS as f32;
            positions.push(if k < 0 {
                [x, 0.0, across]
            } else {
                [x, across, 0.0]
            });
        }
    }
    let index = |row: u32, i: u32| row * ALONG + i;
    let mut triangles = Vec::new();
    for row in 0..2 * ACROSS {
        for i in 0..ALONG - 1 {
            let (a, b) = (index(row, i), index(row, i + 1));
            let (c, d) = (index(row + 1, i), index(row + 1, i + 1));
            triangles.push([a, c, b]);
            triangles.push([b, c, d]);
        }
    }
    (positions, triangles)
}

/// Whether `p` lies on the upright face (y = 0) or the floor (z = 0), as a pair of flags,
/// within `eps`.
fn faces_of(p: [f32; 3], eps: f32) -> (bool, bool) {
    (p[1].abs() <= eps, p[2].abs() <= eps)
}

#[test]
fn a_finely_sampled_fold_is_coarsened_and_stays_sharp_straight_and_whole() {
    let (positions, triangles) = folded_strip();
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let config = RemeshConfig {
        target: EdgeTarget::Length(TARGET),
        feature_angle: Some(45.0),
        ..RemeshConfig::default()
    };
    let out = Remeshed::of(&mesh, &config).unwrap();
    // Coordinates are at most a few units: a relative epsilon of the strip's size.
    let eps = 1e-5 * LENGTH;
    let on_fold: Vec<u32> = (0u32..)
        .zip(&out.positions)
        .filter(|&(_, &p)| faces_of(p, eps) == (true, true))
        .map(|(v, _)| v)
        .collect();
    // Every triangle lies in one face: none cuts the corner, so the fold stayed sharp.
    for t in &out.triangles {
        let corners = t.map(|v| faces_of(out.positions[v as usize], eps));
        let upright = corners.iter().all(|c| c.0);
        let floor = corners.iter().all(|c| c.1);
        assert!(upright || floor, "triangle {t:?} spans the fold");
    }
    // The fold keeps both ends, and its vertices cover it with no gap longer than the
    // split limit: it is still one line from x = 0 to x = LENGTH.
    let mut xs: Vec<f32> = on_fold
        .iter()
        .map(|&v| out.positions[v as usize][0])
        .collect();
    xs.sort_by(f32::total_cmp);
    assert_eq!(xs.first().copied(), Some(0.0), "start of the fold");
    assert_eq!(xs.last().copied(), Some(LENGTH), "end of the fold");
    for pair in xs.windows(2) {
        assert!(
            pair[1] - pair[0] <= TARGET * 4.0 / 3.0 + eps,
            "gap {pair:?}"
        );
    }
    eprintln!(
        "{} fold vertices of {ALONG}, {} collapses",
        on_fold.len(),
        out.report.collapses
    );
    // Coarsened: far fewer than the 65 input samples (about LENGTH / TARGET + 1 = 17 at
    // the target length; a quarter-length spacing would keep every one).
    assert!(
        on_fold.len() <= (ALONG as usize) / 2,
        "{} fold vertices kept",
        on_fold.len()
    );
    assert!(out.report.collapses > 0);
}
