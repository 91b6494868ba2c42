//! What a PLY header may declare: no more records than the bytes after the header can hold,
//! and the properties meshq reads. Checked before the payload is parsed, so a tiny file that
//! declares billions of elements is an error instead of an allocation of gigabytes.

use anyhow::{Result, bail};
use ply_rs_bw::ply::{Encoding, Header, PropertyType, ScalarType};

/// Bytes of one binary scalar.
fn scalar_bytes(t: &ScalarType) -> u64 {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// The fewest bytes one property can take: in binary its scalar (a list: its length alone, for
/// an empty list); in ASCII one digit and a separator.
fn smallest_property(encoding: &Encoding, t: &PropertyType) -> u64 {
    match (encoding, t) {
        (Encoding::Ascii, _) => 2,
        (_, PropertyType::Scalar(s)) => scalar_bytes(s),
        (_, PropertyType::List(count, _)) => scalar_bytes(count),
    }
}

/// Where the payload starts in `bytes`: just after the `end_header` line.
pub fn payload_start(bytes: &[u8]) -> Result<usize> {
    const END: &[u8] = b"end_header";
    let Some(at) = bytes.windows(END.len()).position(|w| w == END) else {
        bail!("no end_header line in the PLY header");
    };
    match bytes
        .get(at + END.len()..)
        .and_then(|rest| rest.iter().position(|&b| b == b'\n'))
    {
        Some(newline) => Ok(at + END.len() + newline + 1),
        None => Ok(bytes.len()),
    }
}

/// Checks `header` against the `payload` bytes that follow it: every element's records must
/// fit (each at least one byte, so an element without properties cannot declare more records
/// than there are bytes), vertices must have `x`, `y` and `z`, faces a vertex index list.
pub fn check_header(header: &Header, payload: u64) -> Result<()> {
    let mut needed: u128 = 0;
    for element in header.elements.values() {
        let record: u64 = element
            .properties
            .values()
            .map(|p| smallest_property(&header.encoding, &p.data_type))
            .sum();
        needed += element.count as u128 * u128::from(record.max(1));
        if needed > u128::from(payload) {
            bail!(
                "element '{}' declares {} records, more than the {payload} bytes after the header can hold",
                element.name,
                element.count
            );
        }
        let has = |name: &str| element.properties.contains_key(name);
        match element.name.as_str() {
            "vertex" => {
                if let Some(axis) = ["x", "y", "z"].into_iter().find(|a| !has(a)) {
                    bail!("the vertex element has no '{axis}' property");
                }
            }
            "face" if element.count > 0 => {
                let list = ["vertex_indices", "vertex_index"]
                    .iter()
                    .filter_map(|n| element.properties.get(*n))
                    .any(|p| matches!(p.data_type, PropertyType::List(..)));
                if !list {
                    bail!("the face element has no 'vertex_indices' list");
                }
            }
            _ => {}
        }
    }
    Ok(())
}
