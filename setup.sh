#!/usr/bin/env bash
# Set up checker on a fresh machine and render the example report.
#   bash setup.sh            -> .venv with checker + test extras, engine.xlsx, engine.pdf
#   bash setup.sh --no-example   (install only)
set -euo pipefail
cd "$(dirname "$0")"

PY=${PYTHON:-python3}
if ! "$PY" -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else 1)'; then
  echo "setup: Python >= 3.11 is required (found: $("$PY" --version 2>&1))" >&2
  exit 2
fi

# WeasyPrint (the PDF renderer) needs Pango and fonts from the system.
missing_libs() {
  for lib in libpango-1.0.so.0 libpangoft2-1.0.so.0 libharfbuzz-subset.so.0; do
    ldconfig -p 2>/dev/null | grep -q "$lib" || { echo "$lib"; return; }
  done
  fc-list 2>/dev/null | grep -qi dejavu || echo "fonts-dejavu-core"
}
if [ -n "$(missing_libs)" ]; then
  if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
    echo "setup: installing Pango and fonts for WeasyPrint (apt-get)" >&2
    apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
      libpango-1.0-0 libpangoft2-1.0-0 libharfbuzz-subset0 fonts-dejavu-core fontconfig \
      >/dev/null
  else
    echo "setup: WeasyPrint needs Pango and fonts. Install them, e.g. on Debian/Ubuntu:" >&2
    echo "  sudo apt-get install libpango-1.0-0 libpangoft2-1.0-0 libharfbuzz-subset0" \
      "fonts-dejavu-core" >&2
    exit 2
  fi
fi

# pip's output goes to a log, shown only when a step fails (errors stay visible)
LOG=$(mktemp "${TMPDIR:-/tmp}/checker-setup.XXXXXX")
trap 'rm -f "$LOG"' EXIT
quietly() {
  if ! "$@" >"$LOG" 2>&1; then
    echo "setup: failed: $*" >&2
    tail -n 40 "$LOG" >&2
    exit 2
  fi
}

echo "setup: creating the virtual environment .venv" >&2
rm -rf .venv
quietly "$PY" -m venv .venv
echo "setup: updating pip" >&2
quietly .venv/bin/python -m pip install --upgrade pip
echo "setup: installing checker and its dependencies (a few minutes on a fresh machine)" >&2
quietly .venv/bin/python -m pip install --progress-bar off -e ".[test]"
# byte code of checker's own modules written now: an editable install leaves it to the first
# import, which cannot write it where PYTHONDONTWRITEBYTECODE is set or the tree is read-only
# (every command would then compile about 0.15 s of source first)
quietly .venv/bin/python -m compileall -q -j 0 checker

if [ "${1:-}" != "--no-example" ]; then
  echo "setup: writing the example workbook engine.xlsx" >&2
  .venv/bin/checker template engine.xlsx --force 2>/dev/null
  echo "setup: rendering the example report engine.pdf (about 10 s)" >&2
  # exit code 1 is the verdict (the seed's example joints fail their guidelines), not an error
  .venv/bin/checker report engine.xlsx -o engine.pdf --html engine.html -q || [ $? -eq 1 ]
fi
echo "setup: done; run .venv/bin/checker --help" >&2
