//! Stack high-water marks: cortex-m-rt's `paint-stack` feature fills the stack with a pattern
//! at reset, [`repaint`] repaints the unused part before a phase, and the deepest word no
//! longer holding the pattern afterwards ([`high_water`]) marks the most stack that phase used
//! (counted from the top of the stack, so the callers' frames are included).

/// Repaints the unused part of the stack: the start of a measured phase.
pub fn repaint() {
    cortex_m_stack::repaint_stack();
}

/// The most stack, in bytes, used since the last [`repaint`].
pub fn high_water() -> u32 {
    cortex_m_stack::stack_size().saturating_sub(cortex_m_stack::stack_painted())
}

/// Runs `phase` and returns its result with the stack high-water mark, in bytes, it reached.
/// For small results only: the result is moved once more than with [`repaint`] and
/// [`high_water`] around the call.
#[cfg(not(feature = "remesh"))]
pub fn measured<R>(phase: impl FnOnce() -> R) -> (R, u32) {
    repaint();
    let result = phase();
    (result, high_water())
}
