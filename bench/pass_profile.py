#!/usr/bin/env python3
"""Where the force pass spends its time, by the functions inlined into it.

The pass is one function per compilation and model set (its loops are
always-inline functions, contact/pass.c), so `perf report` gives it as one
symbol. This script splits that symbol's samples by the function of
contact/pass.c (or of the header of the linear law's groups) each sampled
instruction was inlined from, reading the inline chain of its address
with addr2line; with --lines FUNC it gives FUNC's own source lines
instead.

usage:
  perf record -e cpu-clock -o P.data BIN bench --n 3375 --threads 1
  bench/pass_profile.py P.data BIN [--symbol SYM] [--lines FUNC]
  bench/pass_profile.py P.data BIN --threads

With --threads, each thread's samples instead (counts, not shares): its
samples in the pass by part, and outside it those in the OpenMP runtime
(libgomp: a thread that waits at a barrier spins there before it
sleeps) and elsewhere (the main thread's serial work between passes,
and the other passes the start-up and run-time trials time, which are
other symbols than SYM). Where two threads lose shows as one thread's
part costing more than the other's, and the other waiting
(docs/performance-log.md, "Zen 3 again").

BIN must be built with -g (cmake -DCMAKE_C_FLAGS=-g: the same code, with
the line tables). SYM defaults to the hottest symbol whose name starts with
dem__pass. Shares are percent of that symbol's samples. perf's cpu-clock
samples land on the instruction after the one that stalls (skid), so a
line's share is its neighbourhood's; the functions' shares are reliable.
Needs perf and addr2line (binutils). docs/performance-log.md, session 75.
"""
import argparse
import collections
import re
import subprocess
import sys

# the parts of a pass whose shares are reported (a sample goes to the
# innermost of them in its chain: pair_range with the linear law's groups,
# records_fill apart from particle_range, which writes the records with it)
PARTS = ("pair_range", "wall_range", "particle_range", "records_fill",
         "virial_block", "image_records")


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode:
        sys.exit("pass_profile: %s failed: %s" % (cmd[0], r.stderr.strip()))
    return r.stdout


def hottest(data):
    for line in run(["perf", "report", "-i", data, "--stdio"]).splitlines():
        m = re.match(r"\s+([0-9.]+)%\s+\S+\s+\S+\s+\[\.\]\s+(dem__pass\S+)",
                     line)
        if m:
            return m.group(2)
    sys.exit("pass_profile: no dem__pass symbol among the samples")


def samples(data, sym):
    """percent of sym's samples per instruction address (hex, no 0x)"""
    out = run(["perf", "annotate", "-i", data, "--stdio", "-s", sym])
    pct = {}
    for line in out.splitlines():
        m = re.match(r"\s+([0-9.]+)\s+:\s+([0-9a-f]+):", line)
        if m and float(m.group(1)) > 0:
            pct[m.group(2).lstrip("0")] = float(m.group(1))
    if not pct:
        sys.exit("pass_profile: no samples in %s" % sym)
    return pct


def chains(binary, addrs):
    """the inline chain of each address: [(function, file:line)], the
    innermost first"""
    out = run(["addr2line", "-a", "-i", "-f", "-e", binary] +
              ["0x" + a for a in addrs]).splitlines()
    res, cur, i = {}, None, 0
    while i < len(out):
        if out[i].startswith("0x"):
            cur = out[i][2:].lstrip("0")
            res[cur] = []
            i += 1
        else:
            res[cur].append((out[i], out[i + 1].split(" ")[0]))
            i += 2
    return res


def by_thread(data, binary, sym):
    """per thread id: samples by part of the pass, and outside it"""
    out = run(["perf", "script", "-i", data, "-F", "tid,ip,sym,symoff,dso"])
    start = None
    for line in run(["nm", binary]).splitlines():
        f = line.split()
        if len(f) == 3 and f[2] == sym:
            start = int(f[0], 16)
    if start is None:
        sys.exit("pass_profile: %s not in the symbols of %s" % (sym, binary))
    per, where = collections.Counter(), collections.Counter()
    for line in out.splitlines():
        m = re.match(r"\s*(\d+)\s+[0-9a-f]+\s+(\S+?)(?:\+0x([0-9a-f]+))?"
                     r"\s+\((.*)\)\s*$", line)
        if not m:
            continue
        tid, name, off, dso = m.groups()
        if name == sym and off:
            per[(tid, "%x" % (start + int(off, 16)))] += 1
        else:
            where[(tid, "(in libgomp)" if "libgomp" in dso else
                   "(outside the pass)")] += 1
    ch = chains(binary, sorted({a for _, a in per}))
    for (tid, addr), n in per.items():
        part = [f for f, _ in ch.get(addr, []) if f in PARTS]
        where[(tid, part[0] if part else "(the rest of the pass)")] += n
    tids = sorted({t for t, _ in where}, key=int)
    names = sorted({k for _, k in where})
    print("samples of each thread (by id); the pass is %s" % sym)
    print("%-24s" % "" + "".join("%10s" % t for t in tids))
    for k in names:
        print("%-24s" % k + "".join("%10d" % where[(t, k)] for t in tids))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("data")
    ap.add_argument("binary")
    ap.add_argument("--symbol")
    ap.add_argument("--lines", metavar="FUNC")
    ap.add_argument("--threads", action="store_true")
    a = ap.parse_args()
    sym = a.symbol or hottest(a.data)
    if a.threads:
        by_thread(a.data, a.binary, sym)
        return
    pct = samples(a.data, sym)
    ch = chains(a.binary, list(pct))
    if not any(f for c in ch.values() for f, _ in c if f in PARTS):
        sys.exit("pass_profile: no line tables for the pass in %s (build "
                 "with -g)" % a.binary)
    share = collections.Counter()
    for addr, p in pct.items():
        c = ch.get(addr, [])
        if a.lines:
            at = [loc for f, loc in c if f == a.lines]
            if at:
                share[at[0].rsplit("/", 1)[-1]] += p
        else:
            part = [f for f, _ in c if f in PARTS]
            share[part[0] if part else "(the rest)"] += p
    # perf annotate's rounded percentages, summed, miss 100 by a little
    total = sum(pct.values())
    print("%% of the samples of %s" % sym)
    for k, v in share.most_common(40 if a.lines else None):
        print("%6.1f  %s" % (100.0 * v / total, k))


if __name__ == "__main__":
    main()
