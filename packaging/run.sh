#!/usr/bin/env bash
# Installs sorgui with the system libraries Qt and VTK need, then opens it (or runs `sorgui ARGS`).
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
if command -v apt-get >/dev/null; then
  $SUDO apt-get update -qq
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    $(grep -v '^#' .ci/apt-packages.txt) >/dev/null
fi
python3 -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e ".[cad]"
# matplotlib (the typesetting of formulas) builds its font cache once, which takes seconds on a
# fresh home folder: done here, at install time, rather than during the first analysis.
.venv/bin/python -c "import matplotlib.font_manager" 2>/dev/null || true
exec .venv/bin/sorgui "$@"
