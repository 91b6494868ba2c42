//! `--structure`: which acceleration structure a command builds, parsed straight into the
//! core's [`StructureKind`] (one list of structures and their names, the core's).

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use meshq::owned::StructureKind;

/// The parser of `--structure`: one of [`StructureKind::name`]'s names, each listed in
/// `--help`. All four structures give the same answers.
pub fn structure_parser() -> impl TypedValueParser<Value = StructureKind> {
    let names = StructureKind::ALL.map(|kind| PossibleValue::new(kind.name()).help(help(kind)));
    // Only the listed names reach the map, and each parses.
    PossibleValuesParser::new(names).map(|name| name.parse::<StructureKind>().unwrap_or_default())
}

/// One line on each structure, for `--help`.
fn help(kind: StructureKind) -> &'static str {
    match kind {
        StructureKind::Bvh => "Bounding volume hierarchy (binned SAH, walked eight- or four-wide)",
        StructureKind::KdTree => "k-d tree (SAH over clipped triangles)",
        StructureKind::Octree => "Adaptive octree",
        StructureKind::Grid => "Uniform grid",
    }
}
