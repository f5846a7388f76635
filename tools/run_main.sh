#!/usr/bin/env bash
# The main job: install what is missing, build (release), run the paper's scenario and plot it.
#   tools/run_main.sh [SCENARIO]     (default: scenarios/paper/medium_soil_gauss_seidel.json)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_dependencies.sh
cmake --preset release >/dev/null
cmake --build --preset release
scenario=${1:-scenarios/paper/medium_soil_gauss_seidel.json}
build/release/bin/rumble run "$scenario"   # writes the results and their plots
