//! The panic-free proof. This handler calls a function that exists nowhere, so the firmware
//! links only if the optimiser removed every call to the panic handler: no panic is reachable
//! from blob validation, the golden-file lookup and the queries. The normal build uses the
//! semihosting crate's handler instead (it reports and exits with status 101).

use core::panic::PanicInfo;

unsafe extern "C" {
    /// Deliberately undefined: a link error naming it means a panic is reachable.
    fn meshq_firmware_a_panic_is_reachable() -> !;
}

#[panic_handler]
fn panic(_: &PanicInfo<'_>) -> ! {
    // SAFETY: never executed — the program links only when this handler is unreachable.
    unsafe { meshq_firmware_a_panic_is_reachable() }
}
