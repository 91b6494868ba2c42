//! Names, once, how this build computes the blob checksum, as two cfgs the code tests:
//!
//! - `hardware_crc`: the `std` feature on x86, x86-64 or AArch64. The `crc32fast` crate then
//!   uses the CPU's carry-less multiply or CRC32 instructions, which it finds at run time.
//! - `crc_lanes`: otherwise, a target with a byte shuffle (WebAssembly SIMD, SSSE3, NEON): the
//!   core's sixteen-lane CRC.
//!
//! Neither: on bare metal a 16-entry table, half a byte per step (64 bytes of flash instead of
//! 1 KiB); elsewhere the `crc` crate's sixteen tables. Every way gives the same checksum.

use std::env;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(hardware_crc)");
    println!("cargo::rustc-check-cfg=cfg(crc_lanes)");
    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let features = env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default();
    let has = |feature: &str| features.split(',').any(|f| f == feature);
    let std = env::var_os("CARGO_FEATURE_STD").is_some();
    let hardware_crc = std && matches!(arch.as_str(), "x86" | "x86_64" | "aarch64");
    let shuffle = has("simd128") || has("ssse3") || (arch == "aarch64" && has("neon"));
    if hardware_crc {
        println!("cargo::rustc-cfg=hardware_crc");
    } else if shuffle {
        println!("cargo::rustc-cfg=crc_lanes");
    }
}
