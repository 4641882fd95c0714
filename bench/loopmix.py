#!/usr/bin/env python3
"""Instruction mix of the hottest loop of a function, from the text of
`perf annotate --stdio` (docs/performance.md, "The limit on one core").

    perf record -e cpu-clock -o perf.data build/dembox bench --n 3375 \\
        --steps 3000 --threads 1
    perf annotate -i perf.data --stdio -s dem__pass_loads._omp_fn.0 > ann.txt
    python3 bench/loopmix.py ann.txt

A loop is the range from a backward jump's target to the jump; the
hottest is the one with the largest share of samples that is not inside
another of nearly the same share. Prints its share of the samples, its
length in instructions and how many of them load, store, do arithmetic
(FMA, add/multiply, square root, division), shuffle or blend lanes, make
masks, gather, move registers, or work on integers and addresses.
"""
import re
import sys
from collections import Counter


def kind(ins):
    op = ins.split()[0]
    if re.match(r"vf(n)?m(add|sub)", op):
        return "fma"
    if op.startswith("vsqrt"):
        return "sqrt"
    if op.startswith("vdiv"):
        return "div"
    if re.match(r"v(add|sub|mul|addsub)(p|s)d", op):
        return "add/mul"
    if op.startswith("vgather"):
        return "gather"
    if re.match(r"v(unpck|perm|shuf|insert|extract|broadcast|blend|movddup"
                r"|movhlps|movlhps)", op):
        return "shuffle/blend"
    if re.match(r"v(cmp|and|or|xor|max|min|test)", op):
        return "mask/logic"
    if re.match(r"v(mov|movs|movh|movl|movap|movup)", op):
        args = ins.split(None, 1)[1] if " " in ins else ""
        src, _, dst = args.rpartition(",")
        if "(" in dst:
            return "store"
        return "load" if "(" in src else "register move"
    if op.startswith("j"):
        return "branch"
    return "integer/address"


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: loopmix.py ANNOTATE.txt")
    rows = []
    with open(sys.argv[1]) as f:
        for line in f:
            m = re.match(r"\s*([\d.]+)?\s*:\s*([0-9a-f]+):\s*(\S.*)", line)
            if m:
                rows.append((float(m.group(1) or 0), int(m.group(2), 16),
                             m.group(3).strip()))
    if not rows:
        sys.exit("loopmix.py: no annotated instructions in " + sys.argv[1])
    loops = []
    for _, addr, ins in rows:
        m = re.match(r"j\w+\s+([0-9a-f]+)", ins)
        if m and int(m.group(1), 16) < addr:
            lo = int(m.group(1), 16)
            body = [r for r in rows if lo <= r[1] <= addr]
            loops.append((sum(r[0] for r in body), addr - lo, lo, addr, body))
    if not loops:
        sys.exit("loopmix.py: no loop found")
    # the hottest loop; among loops of nearly its share, the shortest
    top = max(l[0] for l in loops)
    share, _, lo, hi, body = min((l for l in loops if l[0] > 0.9 * top),
                                 key=lambda l: l[1])
    count, weight = Counter(), Counter()
    for pct, _, ins in body:
        count[kind(ins)] += 1
        weight[kind(ins)] += pct
    print("loop %x-%x: %.1f %% of the samples, %d instructions" %
          (lo, hi, share, len(body)))
    for k, n in count.most_common():
        print("  %-16s %4d  (%.1f %% of the samples)" % (k, n, weight[k]))


if __name__ == "__main__":
    main()
