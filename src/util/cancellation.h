// Ctrl-C (SPEC §15: "Ctrl-C writes what is done; never lose a finished result"). One process-wide
// flag: the interrupt handler sets it, long loops look at it at coarse points (between tiles,
// passes, shots, form-factor rows) and stop early, leaving what they finished; the caller writes
// that and exits with 130. Nothing is thrown.
#pragma once

namespace candela {

// SIGINT and SIGTERM set the flag. A second signal while the flag is set restores the default
// action and raises it again, so a run that does not stop can still be killed.
void install_interrupt_handler();

// Whether an interrupt (or request_cancellation) arrived. Cheap: a relaxed atomic load.
bool cancel_requested();

// What the handler does; for tests and for callers that stop a run themselves.
void request_cancellation();
void reset_cancellation();

// The exit status of an interrupted run (the shell's 128 + SIGINT).
inline constexpr int kInterruptedExitCode = 130;

}  // namespace candela
