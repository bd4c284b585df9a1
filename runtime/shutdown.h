// Clean shutdown on SIGINT and SIGTERM. The handler only sets a flag (async-signal-safe); loops
// poll ShutdownRequested() between bounded waits (LCM handleTimeout, serial reads with timeouts)
// and then stop their devices and return normally.
#pragma once

namespace slammtt {

// Installs the SIGINT/SIGTERM handlers (and ignores SIGPIPE, so a closed TCP peer is an error
// return, not a dead process). Safe to call more than once.
void InstallShutdownHandlers();

bool ShutdownRequested();
// The signal that asked for shutdown, or 0 (also 0 after RequestShutdown()).
int ShutdownSignal();
// Asks every loop to stop, as a signal would (used by tests and on fatal conditions).
void RequestShutdown();
// Forgets a previous request (tests that run several loops in one process).
void ResetShutdown();
// A file descriptor that becomes readable when shutdown is requested, for poll()/select() loops.
int ShutdownFd();

}  // namespace slammtt
