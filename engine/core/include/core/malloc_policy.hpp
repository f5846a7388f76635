// Freed memory goes back to the system, so that a run's memory per phase (peak_memory.hpp) is what
// the phase uses, not what earlier phases left behind (issue #33: peak resident memory per DOF).
//
// glibc returns freed memory in two ways: blocks of M_MMAP_THRESHOLD bytes and more live in
// mappings of their own, unmapped when freed, and free space at the heap's top beyond
// M_TRIM_THRESHOLD is trimmed. A library may switch both off for the whole process when it loads:
// SuperLU_DIST 8 (Debian's, which PETSc links, so the FEM plugin's statics) calls
// mallopt(M_MMAP_MAX, 0) and mallopt(M_TRIM_THRESHOLD, -1) in its initialiser (seen in gdb on
// `rumble mesh`: a breakpoint on mallopt, called from libsuperlu_dist.so.8 under dlopen). Every
// block then comes from the heap and stays resident after it is freed: at 1e6 DOFs the FEM soil's
// stepping phase kept the statics' 4.9 GB peak (docs/fem-soil.md section 7.2).
#pragma once

namespace rumble {

/// Large blocks in mappings of their own again (from 32 MiB, glibc's own ceiling for its sliding
/// threshold; smaller blocks reuse the heap) and the heap's top trimmed beyond 64 MiB (twice
/// that, glibc's rule). Called after each plugin library is loaded; no effect but on glibc.
void return_freed_memory();

/// Gives the heap's free pages back to the system (malloc_trim): between phases, so that the
/// next phase starts from what is in use. Returns whether any were given back.
bool trim_freed_memory();

}  // namespace rumble
