#!/bin/sh
# Regenerate the key table in docs/config.md from the descriptor table
# (src/config/keys.c), after the test test_config has written it to
# build/tests/config-keys.md.
set -eu
cd "$(dirname "$0")/.."
gen=build/tests/config-keys.md
[ -f "$gen" ] || (cd build/tests && DEMBOX_SOURCE_DIR=../.. ./test_config >/dev/null 2>&1 || true)
awk -v gen="$gen" '
  /<!-- keys:begin/ { print; while ((getline l < gen) > 0) print l; skip = 1; next }
  /<!-- keys:end/ { skip = 0 }
  !skip { print }' docs/config.md > docs/config.md.tmp
mv docs/config.md.tmp docs/config.md
