# Code generation flags that keep a compiler from miscompiling the project (docs/toolchain.md §7).
#
# GCC 12's loop distribution (-ftree-loop-distribution, on at -O3: the release build) computes a
# prefix sum written under `if (r > 0)` wrong: starts[r] = starts[r - 1] + counts[r - 1], in a loop
# that also fills the counts, gave the last start 0 for counts {312, 314} (a 20-line reproducer;
# -O2, Clang, and -O3 with this flag off compute 312). In the node rendezvous of the ranks (distributed/node_matching.cpp) that made
# MPI_Alltoallv write past its buffer in every refined run on the ranks. Off for GCC before 13,
# so that no other loop of the kind is miscompiled where no test looks (the tests run -O2 and
# Clang builds only).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  add_compile_options(-fno-tree-loop-distribution)
endif()
