// How the threads of a plugin's OpenMP team wait for each other at a barrier. GCC's libgomp reads
// OMP_WAIT_POLICY and GOMP_SPINCOUNT once, when it is loaded, and it is loaded with the first
// plugin that uses OpenMP (the FEM soil), after main() has started: so the engine can still choose
// for its plugins. Left to itself libgomp spins on a barrier for 300 000 rounds before it sleeps;
// on a machine where another process takes a core, the spinning thread holds the core the
// descheduled one needs, and a FEM run on two threads was 6-30 times slower than on one
// (docs/toolchain.md section 8, bench/threads/busy_machine.py).
#pragma once

namespace rumble {

/// Sets OMP_WAIT_POLICY=PASSIVE (a waiting thread sleeps at once and frees its core) unless the
/// user set OMP_WAIT_POLICY or GOMP_SPINCOUNT, whose choice then stands. Call before the first
/// plugin is loaded; returns true when it set the policy.
bool prefer_passive_thread_waits();

}  // namespace rumble
