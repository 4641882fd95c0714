#!/bin/sh
# The libraries' symbols (CTest: exported_symbols_are_prefixed,
# libraries_depend_downwards_only). nm's own failure (a missing file, no
# binutils) fails the check: through a pipe into grep it passed unseen.
#   symbols.sh exported LIB...   every exported symbol has the dem_ prefix
#                                (STYLE.md; AddressSanitizer's __odr_asan
#                                markers are not ours)
#   symbols.sh downwards ENGINE PLOT
#                                the engine library uses neither the plots,
#                                the sweeps nor cairo; the plots do not use
#                                the sweeps (docs/architecture.md)
set -eu
fail() { echo "FAIL: $*" >&2; exit 1; }
what=$1
shift
case $what in
exported)
    syms=$(nm -g --defined-only "$@")
    [ -n "$syms" ] || fail "nm listed no symbols in $*"
    bad=$(printf '%s\n' "$syms" | awk 'NF == 3 && $2 ~ /[TDBR]/ {print $3}' |
        grep -v -e '^dem_' -e '^__odr_asan' || true)
    [ -z "$bad" ] || fail "exported without the dem_ prefix: $bad"
    ;;
downwards)
    engine=$(nm -u "$1")
    plot=$(nm -u "$2")
    [ -n "$engine" ] && [ -n "$plot" ] || fail "nm listed no undefined symbols"
    bad=$(printf '%s\n' "$engine" |
        grep -e cairo_ -e dem_plot -e dem__gp -e dem_sweep || true)
    [ -z "$bad" ] || fail "the engine library uses: $bad"
    bad=$(printf '%s\n' "$plot" | grep -e dem_sweep || true)
    [ -z "$bad" ] || fail "the plots library uses: $bad"
    ;;
*) fail "usage: symbols.sh exported|downwards LIB..." ;;
esac
