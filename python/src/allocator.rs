//! The extension's memory allocator for Rust's own allocations: mimalloc, as the `meshq`
//! command uses (see cli/src/allocator.rs), for two reasons measured on the bunny's million
//! random rays. It marks large blocks for transparent huge pages, so a structure's nodes and
//! triangles span a few 2 MiB pages instead of thousands of 4 KiB ones. And it keeps freed
//! memory for the next batch, where the system allocator unmaps every large block on free and
//! the next batch's buffers fault in page by page again. Python's own objects are unaffected;
//! arrays handed to numpy are freed through the same allocator when numpy drops them.

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;
