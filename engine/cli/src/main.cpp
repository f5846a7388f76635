// rumble: command-line entry point. Dispatches to the commands in cli/commands.hpp.
#include "cli/commands.hpp"

int main(int argc, char** argv) {
  return rumble::cli::main(argc, argv);
}
