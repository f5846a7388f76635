// The rumble command-line interface: one function per sub-command, dispatched by main().
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rumble::post {
struct PostOptions;
}

namespace rumble::cli {

/// Parses argv and runs a sub-command; returns the process exit code (see exit_codes.hpp).
int main(int argc, char** argv);

/// The help text of a command (its options, each with its meaning and default); null when
/// there is no such command.
const char* command_help(const std::string& command);

int run_command(const std::vector<std::string>& args);
int validate_command(const std::vector<std::string>& args);
int plugins_command(const std::vector<std::string>& args);
int schema_command(const std::vector<std::string>& args);
int soil_frf_command(const std::vector<std::string>& args);
int stability_command(const std::vector<std::string>& args);
int mesh_command(const std::vector<std::string>& args);
int calibrate_command(const std::vector<std::string>& args);
int new_plugin_command(const std::vector<std::string>& args);
int post_command(const std::vector<std::string>& args);
int study_command(const std::vector<std::string>& args);

/// The vibration indicators of the run in results_dir into results_dir/post (warnings logged).
/// Throws what post::post_process throws.
void post_process_run(const std::filesystem::path& results_dir, const post::PostOptions& options);

}  // namespace rumble::cli
