#!/usr/bin/env bash
# Draws docs/architecture.svg: the engine's rooms and the packages they link, as CMake builds them
# (tools/check_architecture.py --dot, which also checks them against docs/architecture.md), less
# the arrows that others imply (tred): the picture shows the layering, the doc's table every link.
# Needs Graphviz's dot (tools/install_dependencies.sh installs it).
set -euo pipefail
cd "$(dirname "$0")/.."
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
tools/check_architecture.py --scratch "$scratch" --dot "$scratch/engine.dot"
tred "$scratch/engine.dot" | dot -Tsvg -o docs/architecture.svg
echo "wrote docs/architecture.svg"
