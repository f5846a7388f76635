#!/usr/bin/env bash
# The main job: install what is missing, build (release), run the seed paper's quick study (the
# medium soil on the 3D FEM soil, two-step against Gauss-Seidel) and write its report.
#   tools/run_main.sh [FILE]     a study (*.study.json) or a scenario (default:
#                                scenarios/paper/study/quick.study.json)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_dependencies.sh
cmake --preset release >/dev/null
cmake --build --preset release
target=${1:-scenarios/paper/study/quick.study.json}
if [[ "$target" == *.study.json ]]; then
  build/release/bin/rumble study "$target"   # every run's results, then report.html
else
  build/release/bin/rumble run "$target"     # writes the results and their plots
fi
