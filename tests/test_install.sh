#!/bin/sh
# Install the build into a temporary prefix, build tests/install_check.c
# against it with pkg-config (the header and libdembox.so only) and run
# it. usage: test_install.sh BUILD_DIR SOURCE_DIR [CC [PYTHON3]]
set -eu
build=$1 src=$2 cc=${3:-cc} py=${4:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
pc=$(find "$tmp/prefix" -name dembox.pc)
[ -n "$pc" ] || { echo "test_install: no dembox.pc installed" >&2; exit 1; }
for f in bin/dembox include/dembox.h include/dembox_models.h \
    share/man/man1/dembox.1 share/bash-completion/completions/dembox; do
    [ -e "$tmp/prefix/$f" ] || { echo "test_install: $f not installed" >&2; exit 1; }
done
export PKG_CONFIG_PATH="$(dirname "$pc")"
# shellcheck disable=SC2046 # the flags are split on purpose
"$cc" -std=c11 -Wall -Werror "$src/tests/install_check.c" \
    $(pkg-config --cflags --libs dembox) -o "$tmp/check"
libdir=$(pkg-config --variable=libdir dembox)
LD_LIBRARY_PATH="$libdir" "$tmp/check" "$tmp/out"
[ -s "$tmp/out/summary.json" ] || { echo "test_install: no summary.json" >&2; exit 1; }
"$tmp/prefix/bin/dembox" --version >/dev/null
# the man page has every command's help; the completion parses
for sec in SYNOPSIS RUN SWEEP BENCH "CONFIGURATION KEYS"; do
    grep -q "^\.SH $sec\$" "$tmp/prefix/share/man/man1/dembox.1" ||
        { echo "test_install: no section $sec in dembox.1" >&2; exit 1; }
done
grep -q "contact.mu_r" "$tmp/prefix/share/man/man1/dembox.1" ||
    { echo "test_install: dembox.1 lacks the config keys" >&2; exit 1; }
bash -n "$tmp/prefix/share/bash-completion/completions/dembox"
# the Python module installed where python3 looks, finding the installed
# library by itself: into ~/.local (the README's line), python3 imports it
# from its user site without PYTHONPATH (it went to lib/python3/
# dist-packages, where python3 looks for neither ~/.local nor /usr/local)
if [ -n "$py" ]; then
    home="$tmp/home"
    cmake --install "$build" --prefix "$home/.local" >/dev/null
    v=$(cd "$tmp" && env -u DEMBOX_LIB -u PYTHONPATH -u PYTHONNOUSERSITE \
        -u PYTHONUSERBASE HOME="$home" "$py" -c \
        'import dembox; print(dembox.version(), dembox._find_library())')
    want="$("$tmp/prefix/bin/dembox" --version | awk '{print $2}')"
    [ "$v" = "$want $home/.local/lib/libdembox.so.0" ] ||
        { echo "test_install: python3 from ~/.local says '$v'" >&2; exit 1; }
fi
# a prefix that cannot be written (below a plain file: root cannot either)
# fails with a non-zero status naming the path
touch "$tmp/plainfile"
if cmake --install "$build" --prefix "$tmp/plainfile/p" > "$tmp/bad.log" 2>&1; then
    echo "test_install: installing below a file succeeded" >&2; exit 1
fi
grep -q "$tmp/plainfile/p" "$tmp/bad.log" ||
    { echo "test_install: the failure does not name the prefix: $(cat "$tmp/bad.log")" >&2; exit 1; }
