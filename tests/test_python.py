"""The Python module (python/dembox.py) against the built libdembox.so:
a short run through it gives the same timeseries as the dembox command,
and a bad key raises dembox.Error naming the key. Run by CTest with
PYTHONPATH and DEMBOX_LIB set; argv[1]: the dembox binary, argv[2]: a
scratch folder."""
import os
import subprocess
import sys

import dembox

dembox_bin, tmp = sys.argv[1], sys.argv[2]
assert "biaxial2d" in dembox.examples(), dembox.examples()
assert "dimension = 2" in dembox.example_text("biaxial2d")
assert dembox.version() == subprocess.run(
    [dembox_bin, "--version"], capture_output=True, text=True,
    check=True).stdout.split()[-1], dembox.version()

sets = ["particles.count=60", "output.interval=5.0e-6"]
out_py = dembox.run("biaxial2d", os.path.join(tmp, "py"), sets=sets,
                    max_steps=400)
args = [dembox_bin, "run", "biaxial2d", "-o", os.path.join(tmp, "cli"),
        "--threads", "1", "--quiet", "--max-steps", "400"]
for s in sets:
    args += ["--set", s]
subprocess.run(args, check=True)
with open(os.path.join(out_py, "timeseries.csv")) as a, \
        open(os.path.join(tmp, "cli", "timeseries.csv")) as b:
    assert a.read() == b.read(), "timeseries differ"
ts = dembox.timeseries(out_py)
assert len(ts["t"]) > 10 and ts["t"] == sorted(ts["t"]), ts["t"][:5]
assert "sigma_xx" in ts
summary = dembox.summary(out_py)
assert summary["dimension"] == 2, summary.get("dimension")

try:
    dembox.run("biaxial2d", os.path.join(tmp, "bad"), sets=["contact.mu=-1"])
except dembox.Error as e:
    assert "contact.mu" in str(e), str(e)
else:
    raise AssertionError("a negative friction was accepted")
print("test_python: ok (%d rows, dembox %s)" % (len(ts["t"]), dembox.version()))
