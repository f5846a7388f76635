// The rumble command-line interface: one function per sub-command, dispatched by main().
#pragma once

#include <string>
#include <vector>

namespace rumble::cli {

/// Parses argv and runs a sub-command; returns the process exit code (see exit_codes.hpp).
int main(int argc, char** argv);

}  // namespace rumble::cli
