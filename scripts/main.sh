#!/usr/bin/env bash
# The main job: set up, build, then run the built-in scenes on every built backend and print a
# side-by-side table.
# Usage: scripts/main.sh
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/setup.sh
bash scripts/build.sh build
build/bin/anyphys compare
