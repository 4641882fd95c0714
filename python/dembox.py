"""dembox from Python: run the DEM laboratory and read its results.

A thin ctypes layer over libdembox.so (the C API of include/dembox.h);
nothing to compile. The library is found through the environment
variable DEMBOX_LIB (a path), next to this file in an installed tree
(PREFIX/lib/python3*/*-packages -> PREFIX/lib), or by the system's
library search, and loaded at the first call that needs it: the readers
of a run's files (timeseries, summary, particles, contacts, dump_local,
sweep_summary) work without it.

    import dembox
    out = dembox.run("biaxial2d", "out", sets=["contact.mu=0.3"])
    ts = dembox.timeseries(out)          # column name -> numpy array
    summary = dembox.summary(out)        # summary.json as a dict
    print(summary["peak"]["phi_deg"])
    c = dembox.contacts(out)             # contacts_final.csv, by column
    sw = dembox.sweep("biaxial2d", "sw", ["contact.mu=0.1,0.3"])
    print(dembox.sweep_summary(sw)["friction_vs_mu"])

Every failure raises dembox.Error with the library's one-line message
(naming the key, the file and the line for a bad config). The library's
warnings are Python warnings of category dembox.DemboxWarning, or go to
the list given as warnings=.

A run or a sweep can be stopped and taken up again, as with the dembox
command: Ctrl-C (SIGINT) during dembox.run saves a checkpoint after the
run's step under way and raises KeyboardInterrupt, and dembox.resume(outdir)
goes on from it, to the same bytes as a run never stopped; SIGTERM saves
it too, then ends the process as it would have. run, resume and sweep
take progress=callable, called about four times a second with a
Progress (SweepProgress) tuple; it returns True to stop the run (sweep)
the same way, which then raises dembox.Interrupted.

The readers give each column as a numpy array of float64 (an empty field
is NaN) when numpy is installed (Debian: python3-numpy), else as a list
of floats (an empty field is None); dembox.numpy is the module or None.
"""
import csv
import ctypes
import ctypes.util
import errno
import io
import json
import math
import numbers
import os
import re
import signal
import sys
import threading
import warnings as _warnings
from collections import namedtuple

try:
    import numpy
except ImportError:  # the module works without it, with lists
    numpy = None

__all__ = ["Error", "Interrupted", "DemboxWarning", "Progress",
           "SweepProgress", "version", "build", "examples", "example_text",
           "run", "resume", "analyze", "plot", "timeseries", "summary",
           "particles", "contacts", "dump_local", "DumpFrame", "sweep",
           "sweep_summary"]

_DEM_EINTERRUPTED = -5  # include/dembox.h


class Error(Exception):
    """A failure reported by libdembox: its status code and message."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


class Interrupted(Error):
    """A run or sweep stopped before its end because its progress
    callback asked for it; its checkpoints are saved: resume(outdir) (a
    run) or the same sweep call (a sweep) goes on from them. .outdir is
    its folder."""

    def __init__(self, code, message, outdir):
        super().__init__(code, message)
        self.outdir = outdir


class DemboxWarning(UserWarning):
    """A warning of the library (a time step above t_c/10, a loading that
    is not quasi-static, an isotropic stage that ended at its max_time, a
    summary left out of a plot, ...), when no list was given for them."""


Progress = namedtuple("Progress", "stage nstages stage_type t fraction eta "
                      "eta_is_bound speed stage_done")
Progress.__doc__ = """Where a run stands (struct dem_progress): stage
(1-based) of nstages, its type ("isotropic", "compress", ...), the
simulated time t (s), the fraction of the stage done (0 to 1), eta the
wall-clock seconds left in the stage (an upper bound when eta_is_bound,
an isotropic stage that may end early; NaN until measured, in the first
half second after a start or resume), speed in particle-steps per
second, stage_done True at the stage's last report."""

SweepProgress = namedtuple("SweepProgress",
                           "points skipped ran resumed failed")
SweepProgress.__doc__ = """Where a sweep stands (struct dem_sweep_report):
its grid points, those finished before it started (skipped), those run
or resumed by it and ended (ran), of these the resumed and the failed."""


def _find_library():
    given = os.environ.get("DEMBOX_LIB")
    if given:
        return given
    here = os.path.dirname(os.path.abspath(__file__))
    for rel in ("../../libdembox.so.0", "../../../libdembox.so.0"):
        path = os.path.normpath(os.path.join(here, rel))
        if os.path.exists(path):
            return path
    found = ctypes.util.find_library("dembox")
    if not found:
        raise OSError("libdembox.so not found: set DEMBOX_LIB to its path")
    return found


_WARN = ctypes.CFUNCTYPE(None, ctypes.c_char_p, ctypes.c_void_p)


class _ErrorStruct(ctypes.Structure):
    # struct dem_error (include/dembox.h)
    _fields_ = [("code", ctypes.c_int),
                ("msg", ctypes.c_char * 1024),
                ("warn", _WARN),
                ("warn_user", ctypes.c_void_p)]


class _ProgressStruct(ctypes.Structure):
    # struct dem_progress (include/dembox.h)
    _fields_ = [("stage", ctypes.c_int), ("nstages", ctypes.c_int),
                ("stage_type", ctypes.c_char_p), ("t", ctypes.c_double),
                ("fraction", ctypes.c_double), ("eta", ctypes.c_double),
                ("eta_is_bound", ctypes.c_int), ("speed", ctypes.c_double),
                ("stage_done", ctypes.c_int)]


_RUN_PROGRESS = ctypes.CFUNCTYPE(None, ctypes.POINTER(_ProgressStruct),
                                 ctypes.c_void_p)


class _RunOptions(ctypes.Structure):
    # struct dem_run_options (include/dembox.h)
    _fields_ = [("outdir", ctypes.c_char_p),
                ("progress", _RUN_PROGRESS),
                ("progress_user", ctypes.c_void_p),
                ("threads", ctypes.c_int),
                ("max_steps", ctypes.c_long),
                ("stop", ctypes.c_void_p),
                ("stop_after_steps", ctypes.c_long),
                ("split", ctypes.c_int),
                ("timing", ctypes.c_void_p),
                ("any_build", ctypes.c_int)]


class _SweepReport(ctypes.Structure):
    # struct dem_sweep_report (include/dembox.h)
    _fields_ = [("points", ctypes.c_long), ("skipped", ctypes.c_long),
                ("ran", ctypes.c_long), ("resumed", ctypes.c_long),
                ("failed", ctypes.c_long)]


_SWEEP_PROGRESS = ctypes.CFUNCTYPE(None, ctypes.POINTER(_SweepReport),
                                   ctypes.c_void_p)


class _SweepOptions(ctypes.Structure):
    # struct dem_sweep_options (include/dembox.h)
    _fields_ = [("target", ctypes.c_char_p),
                ("outdir", ctypes.c_char_p),
                ("sets", ctypes.POINTER(ctypes.c_char_p)),
                ("nsets", ctypes.c_int),
                ("jobs", ctypes.c_int),
                ("threads", ctypes.c_int),
                ("quiet", ctypes.c_int),
                ("max_steps", ctypes.c_long),
                ("stop", ctypes.c_void_p),
                ("progress", _SWEEP_PROGRESS),
                ("progress_user", ctypes.c_void_p),
                ("any_build", ctypes.c_int)]


class _Example(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("text", ctypes.c_char_p)]


_loaded = None


def _library():
    """libdembox.so, loaded and its prototypes set at the first call that
    needs it: the readers of a run's files (timeseries, summary, particles,
    contacts, dump_local, sweep_summary) work without the library."""
    global _loaded
    if _loaded is not None:
        return _loaded
    lib = ctypes.CDLL(_find_library())
    # first: a library built for another CPU would stop this process with
    # an illegal instruction in any other call (include/dembox.h)
    lib.dem_cpu_check.argtypes = [ctypes.c_char_p, ctypes.c_size_t]
    msg = ctypes.create_string_buffer(768)
    if lib.dem_cpu_check(msg, ctypes.sizeof(msg)):
        raise OSError("dembox: %s: %s" %
                      (lib._name, msg.value.decode(errors="replace")))
    lib.dem_config_size.restype = ctypes.c_size_t
    lib.dem_struct_size.restype = ctypes.c_size_t
    lib.dem_struct_size.argtypes = [ctypes.c_char_p]
    # the structs mirrored above must be the library's, field for field: a
    # size that differs means this module and libdembox.so do not match
    for _name, _mirror in (("dem_error", _ErrorStruct),
                           ("dem_run_options", _RunOptions),
                           ("dem_sweep_options", _SweepOptions),
                           ("dem_sweep_report", _SweepReport),
                           ("dem_example", _Example),
                           ("dem_progress", _ProgressStruct)):
        if lib.dem_struct_size(_name.encode()) != ctypes.sizeof(_mirror):
            raise OSError("dembox: struct %s of %s has %d bytes, this "
                          "module's copy %d: the module and the library do "
                          "not match" % (_name, lib._name, lib.dem_struct_size(
                              _name.encode()), ctypes.sizeof(_mirror)))
    lib.dem_version.restype = ctypes.c_char_p
    lib.dem_build.restype = ctypes.c_char_p
    lib.dem_example_find.restype = ctypes.POINTER(_Example)
    lib.dem_example_find.argtypes = [ctypes.c_char_p]
    lib.dem_example_nearest.restype = ctypes.POINTER(_Example)
    lib.dem_example_nearest.argtypes = [ctypes.c_char_p]
    lib.dem_config_load_target.argtypes = [ctypes.c_void_p, ctypes.c_char_p,
                                           ctypes.c_void_p, ctypes.c_int,
                                           ctypes.POINTER(_ErrorStruct)]
    lib.dem_run.argtypes = [ctypes.c_void_p, ctypes.POINTER(_RunOptions),
                            ctypes.POINTER(_ErrorStruct)]
    lib.dem_run_resume.argtypes = [ctypes.c_char_p,
                                   ctypes.POINTER(_RunOptions),
                                   ctypes.POINTER(_ErrorStruct)]
    lib.dem_analyze.argtypes = [ctypes.c_char_p, ctypes.POINTER(_ErrorStruct)]
    lib.dem_plot_run.argtypes = [ctypes.c_char_p, ctypes.POINTER(_ErrorStruct)]
    lib.dem_mpi_world.argtypes = [ctypes.POINTER(ctypes.c_int),
                                  ctypes.POINTER(ctypes.c_int)]
    lib.dem_mpi_world.restype = None
    lib.dem_sweep_grid_bytes.restype = ctypes.c_size_t
    lib.dem_sweep_param_add.argtypes = [ctypes.c_void_p, ctypes.c_char_p,
                                        ctypes.POINTER(_ErrorStruct)]
    lib.dem_sweep_grid_free.argtypes = [ctypes.c_void_p]
    lib.dem_sweep_run.argtypes = [ctypes.c_void_p,
                                  ctypes.POINTER(_SweepOptions),
                                  ctypes.POINTER(_SweepReport),
                                  ctypes.POINTER(_ErrorStruct)]
    _loaded = lib
    return lib


class _LazyLibrary:
    def __getattr__(self, name):
        return getattr(_library(), name)


_lib = _LazyLibrary()


def _caller_level():
    """The stacklevel of warnings.warn, called from here, that names the
    first frame outside this module: the user's call."""
    level, frame = 1, sys._getframe(1)  # the frame that calls warn
    while frame is not None and frame.f_globals.get("__name__") == __name__:
        level, frame = level + 1, frame.f_back
    return level


def _error(warnings=None):
    """A struct dem_error whose warnings go to the list warnings, or, when
    it is None, to Python's warnings as DemboxWarning. An exception from
    those (a filter "error") is raised by _check after the call."""
    if warnings is not None and not callable(getattr(warnings, "append",
                                                     None)):
        # (a tuple's warnings were lost, each with a traceback printed
        # from the callback)
        raise TypeError("warnings must be a list (or None), not %s"
                        % type(warnings).__name__)
    err = _ErrorStruct()
    err.pending = None

    def warn(line, user):
        text = line.decode(errors="replace")
        if warnings is not None:
            warnings.append(text)
            return
        try:
            _warnings.warn(text, DemboxWarning, stacklevel=_caller_level())
        except BaseException as e:  # raised in a callback: kept for later
            if err.pending is None:
                err.pending = e
    err.warn = _WARN(warn)
    return err


def _check(rc, err):
    """Raise the failure of a call, or the exception a warning became."""
    if rc != 0:
        raise Error(rc, err.msg.decode(errors="replace"))
    if err.pending is not None:
        pending, err.pending = err.pending, None
        raise pending


def _value(v, key):
    """A Python value as a config file writes it: a number (an int as an
    integer, a float with its point or exponent), a string quoted, a
    list, tuple or array of numbers as an array of floats (a config's
    arrays do not mix integers and floats), a bool as true/false; numpy's
    scalars and 0-d arrays as Python's. A number must be finite."""
    if numpy is not None and isinstance(v, (numpy.generic, numpy.ndarray)) \
            and numpy.ndim(v) == 0:
        v = v.item()  # numpy.bool_, a 0-d array: Python's bool, float, ...
    if isinstance(v, numbers.Real) and \
            not isinstance(v, numbers.Integral) and not math.isfinite(v):
        raise ValueError("%s = %r: not a finite number" % (key, v))
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):  # also numpy's integers
        return str(int(v))
    if isinstance(v, numbers.Real):  # also numpy's floats
        return repr(float(v))
    if isinstance(v, str):
        return '"%s"' % v.replace("\\", "\\\\").replace('"', '\\"')
    if not isinstance(v, (bytes, dict)) and hasattr(v, "__iter__"):
        v = list(v)  # a list, a tuple, a numpy array
        if all(isinstance(x, numbers.Real) and not isinstance(x, bool)
               for x in v):
            for x in v:
                if not isinstance(x, numbers.Integral) and \
                        not math.isfinite(x):
                    raise ValueError("%s = %r: not a finite number"
                                     % (key, x))
            return "[%s]" % ", ".join(repr(float(x)) for x in v)
    raise TypeError("%s: a value of type %s (give a number, a string or a "
                    "list of numbers)" % (key, type(v).__name__))


def _int(name, v, bits=32):
    """An int argument for a C int (or long, bits=64): TypeError for
    another type (a float, a str, a bool), ValueError beyond the C type's
    range, which ctypes would cut silently (threads=2**32 + 1 ran with
    one thread)."""
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise TypeError("%s must be an int, not %s (%r)" %
                        (name, type(v).__name__, v))
    v = int(v)
    if not -2 ** (bits - 1) <= v < 2 ** (bits - 1):
        raise ValueError("%s = %d: out of range" % (name, v))
    return v


def _key(k):
    """A key of a mapping of overrides: "a.b", or linked keys as a tuple
    ("a", "b") (a swept key's also as "a,b", as --param writes them)."""
    if isinstance(k, tuple) and k and all(isinstance(x, str) for x in k):
        return ",".join(k)
    if isinstance(k, str):
        return k
    raise TypeError("%r: a key is a string such as \"contact.mu\", or a "
                    "tuple of them (linked keys)" % (k,))


def _texts(items):
    """KEY=VALUE overrides: a list of texts, one text, or a mapping KEY ->
    value (a tuple of keys: each of them to the value)."""
    if isinstance(items, str):
        return [items]
    if isinstance(items, dict):
        out = []
        for k, v in items.items():
            _key(k)  # the check of its type
            for key in k if isinstance(k, tuple) else (k,):
                out.append("%s=%s" % (key, _value(v, key)))
        return out
    if not hasattr(items, "__iter__") or isinstance(items, bytes):
        raise TypeError("%r: give a list of texts \"KEY=VALUE\", one such "
                        "text, or a mapping KEY -> value" % (items,))
    out = list(items)
    for t in out:
        if not isinstance(t, str):
            raise TypeError("%r (%s) is not a text \"KEY=VALUE\" (or give "
                            "a mapping KEY -> value)" %
                            (t, type(t).__name__))
    return out


def _params(items):
    """--param texts: as _texts, or a mapping KEY (linked keys: a tuple or
    "a,b") -> its values (an iterable)."""
    if not isinstance(items, dict):
        return _texts(items)
    out = []
    for k, vs in items.items():
        if isinstance(vs, (str, bytes, dict)) or not hasattr(vs, "__iter__"):
            raise TypeError("%r: the values of a swept key are a list, e.g. "
                            "[0.1, 0.3]" % (k,))
        out.append("%s=%s" % (_key(k), ",".join(_value(v, k) for v in vs)))
    return out


def _path(p):
    """A path (str, bytes or os.PathLike, e.g. pathlib.Path) as the bytes
    the library takes."""
    return os.fsencode(os.fspath(p))


def version():
    """The library's version, e.g. "0.1.0"."""
    return _lib.dem_version().decode()


def build():
    """The library's build, "source ID, cc COMPILER" (its source id and
    compiler, as `dembox --version` and checkpoints name them)."""
    return _lib.dem_build().decode()


def examples():
    """The names of the built-in examples."""
    n = ctypes.c_int.in_dll(_library(), "dem_n_examples").value
    table = (_Example * n).in_dll(_library(), "dem_examples")
    return [table[k].name.decode() for k in range(n)]


def example_text(name):
    """The config text of a built-in example."""
    if not isinstance(name, str):
        raise TypeError("an example's name is a str, not %s (%r)"
                        % (type(name).__name__, name))
    ex = _lib.dem_example_find(name.encode())
    if not ex:
        near = _lib.dem_example_nearest(name.encode())
        raise Error(-6, "no built-in example '%s' (%s)" % (
            name, "did you mean %s?" % near.contents.name.decode() if near
            else "see examples()"))
    return ex.contents.text.decode()


def _config(target, sets, err):
    """Parse target as `dembox run` does: a built-in example's name (which
    wins over a file of that name here, with a warning), else a config
    file's path."""
    buf = ctypes.create_string_buffer(_lib.dem_config_size())
    arr = (ctypes.c_char_p * max(len(sets), 1))(*[s.encode() for s in sets])
    _check(_lib.dem_config_load_target(buf, _path(target), arr, len(sets),
                                       ctypes.byref(err)), err)
    return buf


class _Stop:
    """While a run or a sweep is in the library: SIGINT and SIGTERM (when
    called from the main thread), a progress callback's True and its
    exceptions set the library's stop flag, at which the runs save
    checkpoints after their step under way and return; end() then does what
    Python would have done. The library calls back about four times a
    second, which is when Python runs its signal handlers."""

    def __init__(self, progress, view):
        if progress is not None and not callable(progress):
            raise TypeError("progress must be a callable or None, not %s"
                            % type(progress).__name__)
        self.flag = ctypes.c_int(0)  # volatile sig_atomic_t, an int here
        self.user = progress
        self.view = view  # the library's struct -> what progress gets
        self.signum = None
        self.raised = None
        self.old = {}
        self.follows = False  # an MPI rank > 0 of a split run: rank 0 stops

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            for sig in (signal.SIGINT, signal.SIGTERM):
                old = signal.getsignal(sig)
                if old in (signal.SIG_IGN, None):
                    continue  # ignored, or a handler not set from Python
                self.old[sig] = old
                signal.signal(sig, self._on_signal)
        return self

    def __exit__(self, *exc):
        for sig, old in self.old.items():
            signal.signal(sig, old)
        return False

    def _on_signal(self, sig, frame):
        if self.signum is not None:
            # a second signal: its default action at once, as with the
            # dembox command
            signal.signal(sig, signal.SIG_DFL)
            os.kill(os.getpid(), sig)
            return
        self.signum = sig
        self.flag.value = 1

    def callback(self, report, user):
        if self.user is None or self.raised is not None:
            return
        try:
            item = self.view(report)
            # True stops, not any value that is true (a progress bar's
            # update() returned one, and stopped the run)
            if item is not None and _is_true(self.user(item)):
                self.flag.value = 1
        except BaseException as e:  # raised again after the call
            self.raised = e
            self.flag.value = 1

    def end(self, rc, err, outdir, hint):
        """After the call, with the handlers restored: the callback's
        exception, the signal's action, Interrupted or Error."""
        msg = (err.msg.decode(errors="replace") +
               (hint if rc == _DEM_EINTERRUPTED else ""))
        if self.raised is not None:
            if rc == _DEM_EINTERRUPTED and hasattr(self.raised, "add_note"):
                self.raised.add_note("dembox: " + msg)
            raise self.raised
        if self.signum is not None:
            if (rc == _DEM_EINTERRUPTED and self.old.get(self.signum)
                    is signal.default_int_handler):
                raise KeyboardInterrupt(msg)
            signal.raise_signal(self.signum)  # the handler it had decides
        if rc == _DEM_EINTERRUPTED and (self.flag.value or self.follows):
            raise Interrupted(rc, msg, outdir)
        _check(rc, err)


def _is_true(v):
    """v is True (Python's or numpy's)."""
    return v is True or (numpy is not None and isinstance(v, numpy.bool_)
                         and bool(v))


def _progress(p):
    q = p.contents
    return Progress(q.stage, q.nstages, q.stage_type.decode(), q.t,
                    q.fraction, q.eta, bool(q.eta_is_bound), q.speed,
                    bool(q.stage_done))


def _sweep_progress(p):
    if not p:
        return None  # an MPI rank other than 0: no counts
    q = p.contents
    return SweepProgress(q.points, q.skipped, q.ran, q.resumed, q.failed)


def _run_outdir(call, outdir, threads, max_steps, split, analyze, plot,
                progress, err, any_build=False):
    """call(options, err) (dem_run or dem_run_resume) stoppable, then the
    analysis and the pictures."""
    rank, size = ctypes.c_int(0), ctypes.c_int(1)
    if split:
        _lib.dem_mpi_world(ctypes.byref(rank), ctypes.byref(size))
    # split over ranks, rank 0 decides the stop: only its progress counts
    stop = _Stop(progress, _progress if rank.value == 0 else lambda p: None)
    stop.follows = rank.value != 0
    opt = _RunOptions(outdir=_path(outdir), threads=_int("threads", threads),
                      max_steps=_int("max_steps", max_steps, 64),
                      split=int(bool(split)),
                      progress=_RUN_PROGRESS(stop.callback),
                      stop=ctypes.addressof(stop.flag),
                      any_build=int(bool(any_build)))
    with stop:
        rc = call(ctypes.byref(opt), ctypes.byref(err))
    stop.end(rc, err, outdir, " (from Python: dembox.resume(%r))" % outdir)
    if analyze and rank.value == 0:
        _check(_lib.dem_analyze(_path(outdir), ctypes.byref(err)), err)
    if plot and rank.value == 0:
        _check(_lib.dem_plot_run(_path(outdir), ctypes.byref(err)), err)
    return outdir


def run(target, outdir, sets=(), threads=0, max_steps=0, analyze=True,
        plot=False, warnings=None, split=False, progress=None):
    """Run a built-in example or a config file into outdir, as `dembox run`
    does: then the analysis (summary.json) and, with plot=True, the
    pictures. sets are "KEY=VALUE" overrides, or a mapping KEY -> value
    ({"contact.mu": 0.3}); max_steps > 0 ends the run early.
    threads=N runs on N OpenMP threads; threads=0 (the default) on all
    cores or on one, whichever runs the steps faster, timed now and then
    in the run, as `dembox run` without --threads. Warnings are appended
    to the list warnings when given, else they are Python warnings of
    category DemboxWarning.
    split=True: every rank of the MPI world (a script under mpirun that
    imported mpi4py) calls run with the same arguments, the sample is
    split over the ranks (docs/parallel.md), and rank 0 writes the
    outputs, the analysis and the pictures.
    progress: a callable given a Progress about four times a second and
    at the end of each stage; when it returns True (or raises) the run
    saves a checkpoint after its step under way and stops, raising
    Interrupted (or what it raised). Ctrl-C does the same, raising
    KeyboardInterrupt; resume(outdir) goes on. Returns outdir."""
    err = _error(warnings)
    cfg = _config(target, _texts(sets), err)
    return _run_outdir(lambda opt, e: _lib.dem_run(cfg, opt, e), outdir,
                       threads, max_steps, split, analyze, plot, progress,
                       err)


def resume(outdir, threads=0, analyze=True, plot=False, warnings=None,
           split=False, progress=None, any_build=False):
    """Go on with the run stopped in outdir (Ctrl-C, SIGTERM, a progress
    callback, a checkpoint interval) from outdir/checkpoint.bin, as
    `dembox run --resume` does: the outputs are those of a run never
    stopped, byte for byte, for any thread count. A checkpoint another
    build wrote (build()) is refused, unless any_build=True, as
    --any-build: the run then goes on, with a warning, and is not bit
    for bit either build's. The rest as run()."""
    err = _error(warnings)
    return _run_outdir(
        lambda opt, e: _lib.dem_run_resume(_path(outdir), opt, e), outdir,
        threads, 0, split, analyze, plot, progress, err, any_build)


def analyze(outdir, warnings=None):
    """Write outdir/summary.json from a finished run's files."""
    err = _error(warnings)
    _check(_lib.dem_analyze(_path(outdir), ctypes.byref(err)), err)


def plot(outdir, warnings=None):
    """Draw outdir/plots/ (gnuplot and cairo)."""
    err = _error(warnings)
    _check(_lib.dem_plot_run(_path(outdir), ctypes.byref(err)), err)


def _run_file(outdir, name):
    """outdir/name, a file of a finished run: FileNotFoundError saying the
    run has not finished where only its timeseries.csv.part is there, or
    that outdir is a sweep's folder."""
    path = os.path.join(outdir, name)
    if (not os.path.exists(path) and
            os.path.exists(os.path.join(outdir, "timeseries.csv.part"))):
        raise FileNotFoundError(
            errno.ENOENT, "the run has not finished (only timeseries.csv.part"
            "): dembox.resume(%r) finishes a stopped one" % (outdir,), path)
    if (not os.path.exists(path) and
            os.path.exists(os.path.join(outdir, "runs", "index"))):
        raise FileNotFoundError(
            errno.ENOENT, "a sweep's folder, not a run's: its runs are "
            "%s (listed in runs/index); dembox.sweep_summary(%r) reads its "
            "sweep.json" % (os.path.join(outdir, "runs", "NAME"), outdir),
            path)
    return path


def timeseries(outdir):
    """outdir/timeseries.csv as a dict: column name -> its values (a numpy
    array, or a list without numpy)."""
    return _csv(_run_file(outdir, "timeseries.csv"))


def summary(outdir):
    """outdir/summary.json as a dict."""
    return _json(_run_file(outdir, "summary.json"))


def _text(path):
    """A text file's contents, UTF-8 as dembox writes; ValueError naming
    the file and the line of a byte that is not."""
    with open(path, "rb") as f:
        raw = f.read()
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ValueError("%s:%d: not UTF-8 text (%s)" %
                         (path, raw.count(b"\n", 0, e.start) + 1,
                          e.reason)) from None


def _json(path):
    """A JSON file dembox wrote: numbers as RFC 8259 writes them (no NaN
    or Infinity, which json.load takes); ValueError naming the file and
    line otherwise."""
    def constant(name):
        raise ValueError("%s is not a number of JSON" % name)

    def number(text):  # 1e400 would be inf
        v = float(text)
        if not math.isfinite(v):
            raise ValueError("%s is beyond a double" % text[:40])
        return v
    text = _text(path)
    try:
        return json.loads(text, parse_constant=constant, parse_float=number)
    except json.JSONDecodeError as e:
        raise ValueError("%s:%d: %s (column %d)" % (path, e.lineno, e.msg,
                                                     e.colno)) from None
    except RecursionError:  # arrays in arrays thousands deep
        raise ValueError("%s: nested too deeply: not a file dembox wrote"
                         % path) from None
    except ValueError as e:
        line = _json_bad_line(text)
        raise ValueError("%s%s: %s" % (path, ":%d" % line if line else "",
                                       e)) from None


_JSON_TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|NaN|-?Infinity|-?(?:0|[1-9]'
                         r'[0-9]*)(?:\.[0-9]+)?(?:[eE][-+]?[0-9]+)?')


def _json_bad_line(text):
    """The line of the first NaN, Infinity or number beyond a double of a
    JSON text (outside its strings), or 0."""
    for m in _JSON_TOKEN.finditer(text):
        tok = m.group()
        if tok[0] != '"' and (tok[-1] in "Ny" or
                              not math.isfinite(float(tok))):
            return text.count("\n", 0, m.start()) + 1
    return 0


def _number(text, path, line, name):
    """A CSV field: a finite float, None when empty; ValueError naming
    the file, line and column otherwise."""
    text = text.strip()
    if text == "":
        return None
    try:
        v = float(text)
    except ValueError:
        v = None
    if v is None or not math.isfinite(v):
        raise ValueError("%s:%d: column %s: %r is not a finite number (an "
                         "undefined value is an empty field)" %
                         (path, line, name, text))
    return v


def _column(values):
    """A column: a float64 numpy array (None -> NaN), or the list itself
    without numpy."""
    if numpy is None:
        return values
    return numpy.array([numpy.nan if v is None else v for v in values],
                       dtype=numpy.float64)


def _csv(path):
    """A CSV file of numbers under a header, read as the library reads
    them: lines starting with # and blank lines skipped, fields trimmed;
    ValueError naming the file and line of what is not such a file."""
    head, cols = None, None
    with io.StringIO(_text(path), newline="") as f:
        rows = csv.reader(f)
        try:
            for r in rows:
                if (not r or not "".join(r).strip() or
                        r[0].lstrip()[:1] == "#"):
                    continue
                if head is None:
                    head = [name.strip() for name in r]
                    seen = set()
                    for name in head:  # one dict key would hold both
                        if name in seen:
                            raise ValueError(
                                "%s:%d: column %r named twice in the "
                                "header" % (path, rows.line_num, name))
                        seen.add(name)
                    cols = [[] for _ in head]
                    continue
                if len(r) != len(head):
                    raise ValueError("%s:%d: %d fields for the header's %d "
                                     "columns" % (path, rows.line_num,
                                                  len(r), len(head)))
                for k, text in enumerate(r):
                    cols[k].append(_number(text, path, rows.line_num,
                                           head[k]))
        except csv.Error as e:  # a NUL, a field over the reader's limit
            raise ValueError("%s:%d: %s" % (path, rows.line_num,
                                            e)) from None
    if head is None:
        raise ValueError("%s: no header: not a CSV file dembox wrote" % path)
    return {name: _column(c) for name, c in zip(head, cols)}


def particles(outdir):
    """outdir/particles_final.csv (the final state) as a dict: column ->
    its values (numpy array or list)."""
    return _csv(_run_file(outdir, "particles_final.csv"))


def contacts(outdir):
    """outdir/contacts_final.csv (every closed contact at the end: ids,
    contact point, normal, overlap, normal and tangential force, sliding,
    the history values of the models in force: xi_x.., dmax, ...)
    as a dict: column -> its values (numpy array or list)."""
    return _csv(_run_file(outdir, "contacts_final.csv"))


class DumpFrame(tuple):
    """A frame of dump_local: the pair (step, columns), with the box's
    bounds at that step as .box, ((xlo, xhi), (ylo, yhi), (zlo, zhi)); a
    periodic cell's tilts as .tilt, (xy, xz, yz) (0 between walls; its
    edges are (xhi - xlo, 0, 0), (xy, yhi - ylo, 0), (xz, yz, zhi -
    zlo)), and which axes are periodic as .periodic (three bools)."""

    def __new__(cls, step, columns, box, tilt=(0.0, 0.0, 0.0),
                periodic=(False, False, False)):
        frame = super().__new__(cls, (step, columns))
        frame.box = box
        frame.tilt = tilt
        frame.periodic = periodic
        return frame

    @property
    def step(self):
        return self[0]

    @property
    def columns(self):
        return self[1]


def dump_local(outdir):
    """outdir/dump_local.lammpstrj (written with output.dump_interval > 0):
    a list of frames, each a DumpFrame (step, dict column -> its values,
    numpy array or list) of the closed contacts at that step, with the
    box's bounds as frame.box (a periodic cell's tilts as frame.tilt).
    ValueError naming the file and line of
    what is not such a file."""
    path = _run_file(outdir, "dump_local.lammpstrj")
    lines = _text(path).splitlines()

    def line(k, what):
        if k >= len(lines):
            raise ValueError("%s:%d: the file ends before %s" %
                             (path, len(lines) + 1, what))
        return lines[k]

    def item(k, title):
        text = line(k, title)
        if not text.startswith(title):
            raise ValueError("%s:%d: %r where %r belongs" %
                             (path, k + 1, text[:40], title))
        return text[len(title):].split()

    def count(k, what):
        text = line(k, what).strip()
        if not (text.isascii() and text.isdigit()):  # (not "²")
            raise ValueError("%s:%d: %s %r is not a count" %
                             (path, k + 1, what, text[:40]))
        return int(text)

    def numbers(k, names, what, more=False):
        fields = line(k, what).split()
        if len(fields) < len(names) or (len(fields) > len(names) and
                                        not more):
            raise ValueError("%s:%d: %d fields for %d columns" %
                             (path, k + 1, len(fields), len(names)))
        return [_number(t, path, k + 1, name)
                for t, name in zip(fields, names)]

    frames = []
    k = 0
    while k < len(lines):
        if not lines[k].strip():
            k += 1
            continue
        item(k, "ITEM: TIMESTEP")
        step = count(k + 1, "the step")
        item(k + 2, "ITEM: NUMBER OF ENTRIES")
        n = count(k + 3, "the number of entries")
        flags = item(k + 4, "ITEM: BOX BOUNDS")
        tilted = flags[:3] == ["xy", "xz", "yz"]
        rows = [numbers(k + 5 + a, names + (("tilt",) if tilted else ()),
                        "the box", not tilted)
                for a, names in enumerate((("xlo", "xhi"), ("ylo", "yhi"),
                                           ("zlo", "zhi")))]
        tilt = (0.0, 0.0, 0.0)
        if tilted:  # LAMMPS widens the bounds by the tilts: undone
            xy, xz, yz = tilt = tuple(r[2] for r in rows)
            wide = ((min(0.0, xy, xz, xy + xz), max(0.0, xy, xz, xy + xz)),
                    (min(0.0, yz), max(0.0, yz)), (0.0, 0.0))
            rows = [(r[0] - w[0], r[1] - w[1]) for r, w in zip(rows, wide)]
        box = tuple((r[0], r[1]) for r in rows)
        periodic = tuple(f == "pp" for f in flags[-3:]) \
            if len(flags) >= 3 else (False, False, False)
        head = item(k + 8, "ITEM: ENTRIES")
        rows = [numbers(k + 9 + r, head, "entry %d of %d" % (r + 1, n))
                for r in range(n)]
        frames.append(DumpFrame(step, {
            name: _column([row[c] for row in rows])
            for c, name in enumerate(head)}, box, tilt, periodic))
        k += 9 + n
    return frames


def sweep(target, outdir, params, sets=(), jobs=0, threads=1, max_steps=0,
          quiet=True, progress=None, warnings=None, any_build=False):
    """What `dembox sweep` does: the runs of every combination of params
    ("KEY[,KEY...]=V1,V2,..." as --param, or a mapping KEY -> values,
    {"contact.mu": [0.1, 0.3]}) with the overrides sets, jobs at once
    (0, the default: as many as the cores take at threads each, and the
    memory), then outdir/sweep.json and outdir/plots/; finished runs are
    skipped, so calling it again resumes. progress: a callable given a
    SweepProgress about four times a second and at the end; when it
    returns True (or raises), or on Ctrl-C, the runs under way save
    checkpoints and stop, no other starts, and Interrupted (what it
    raised, KeyboardInterrupt) is raised: the same call goes on from
    them. Its own warnings (each run's are in its run.log) as run()'s.
    An unfinished run's checkpoint from another build is resumed with
    any_build=True (as --any-build), else that run starts again.
    Returns outdir."""
    err = _error(warnings)
    texts = _params(params)
    if not texts:
        raise ValueError("sweep: give at least one swept key in params (a "
                         "single run is dembox.run)")
    grid = ctypes.create_string_buffer(_lib.dem_sweep_grid_bytes())
    try:
        for p in texts:
            _check(_lib.dem_sweep_param_add(grid, p.encode(),
                                            ctypes.byref(err)), err)
        enc = [s.encode() for s in _texts(sets)]
        arr = (ctypes.c_char_p * max(len(enc), 1))(*enc)
        stop = _Stop(progress, _sweep_progress)
        o = _SweepOptions(_path(target), _path(outdir), arr, len(enc),
                          _int("jobs", jobs), _int("threads", threads),
                          int(quiet), _int("max_steps", max_steps, 64),
                          ctypes.addressof(stop.flag),
                          _SWEEP_PROGRESS(stop.callback), None,
                          int(bool(any_build)))
        rep = _SweepReport()
        with stop:
            rc = _lib.dem_sweep_run(grid, ctypes.byref(o), ctypes.byref(rep),
                                    ctypes.byref(err))
        stop.end(rc, err, outdir, " (from Python: the same dembox.sweep call)")
    finally:
        _lib.dem_sweep_grid_free(grid)
    return outdir


def sweep_summary(outdir):
    """outdir/sweep.json (a sweep's cross-run analysis) as a dict."""
    path = os.path.join(outdir, "sweep.json")
    if (not os.path.exists(path) and
            os.path.exists(os.path.join(outdir, "runs", "index"))):
        raise FileNotFoundError(
            errno.ENOENT, "the sweep has not finished (its runs are there, "
            "not its sweep.json): the same dembox.sweep call goes on with "
            "them", path)
    return _json(path)
