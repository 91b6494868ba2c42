//! Stack high-water marks: cortex-m-rt's `paint-stack` feature fills the stack with a pattern
//! at reset, [`measured`] repaints the unused part before a phase, and the deepest word no
//! longer holding the pattern afterwards marks the most stack that phase used (counted from
//! the top of the stack, so the callers' frames are included).

/// Runs `phase` and returns its result with the stack high-water mark, in bytes, it reached.
pub fn measured<R>(phase: impl FnOnce() -> R) -> (R, u32) {
    cortex_m_stack::repaint_stack();
    let result = phase();
    let used = cortex_m_stack::stack_size().saturating_sub(cortex_m_stack::stack_painted());
    (result, used)
}
