// The rumble command-line interface: one function per sub-command, dispatched by main().
#pragma once

#include <string>
#include <vector>

namespace rumble::cli {

/// Parses argv and runs a sub-command; returns the process exit code (see exit_codes.hpp).
int main(int argc, char** argv);

int run_command(const std::vector<std::string>& args);
int validate_command(const std::vector<std::string>& args);
int plugins_command(const std::vector<std::string>& args);
int schema_command(const std::vector<std::string>& args);
int soil_frf_command(const std::vector<std::string>& args);
int mesh_command(const std::vector<std::string>& args);
int calibrate_command(const std::vector<std::string>& args);
int new_plugin_command(const std::vector<std::string>& args);
int study_command(const std::vector<std::string>& args);

}  // namespace rumble::cli
