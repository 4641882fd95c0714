#!/bin/sh
# Regenerate the key table in docs/config.md from the descriptor table
# (src/config/keys.c): test_config, built now from the current sources,
# writes it to build/tests/config-keys.md when the doc differs (and
# then fails).
set -eu
cd "$(dirname "$0")/.."
gen=build/tests/config-keys.md
cmake --build build --target test_config >/dev/null
rm -f "$gen"
if (cd build/tests && DEMBOX_SOURCE_DIR=../.. ./test_config >/dev/null 2>&1); then
    echo "update-config-docs.sh: docs/config.md is up to date"
    exit 0
fi
if [ ! -s "$gen" ]; then
    echo "update-config-docs.sh: test_config failed without writing $gen" \
        "(run it: build/tests/test_config)" >&2
    exit 1
fi
awk -v gen="$gen" '
  /<!-- keys:begin/ { print; while ((getline l < gen) > 0) print l; skip = 1; next }
  /<!-- keys:end/ { skip = 0 }
  !skip { print }' docs/config.md > docs/config.md.tmp
mv docs/config.md.tmp docs/config.md
