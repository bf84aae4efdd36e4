"""Fuzz the command line: random argv, each must end with exit 0, or exit 2 and one line.

    python scripts/fuzz_cli.py [--cases N] [--seed S] [--subprocess M] [--show K]

Builds ``N`` command lines from a seeded generator (subcommands, options, valid and hostile
values: typos, wrong case, Unicode digits, ``1_000``, newlines, escape sequences, huge numbers,
missing files, directories, FIFOs, truncated MERL files, malformed presets) and runs each
in-process through ``tuibrdf.cli.main`` with stdout and stderr captured, plus ``M`` of them as
real subprocesses (stdin not a terminal).  A case passes when:

* the exit status is 0 with nothing on stderr, or 2 with exactly one line on stderr that
  starts with ``tuibrdf``;
* there is no traceback, no warning, and it ends within ``TIMEOUT`` seconds (no hang);
* the viewer is never opened (``view`` must stop at its checks: no terminal here).

Prints the counts (cases, exit 0, exit 2, failures by kind) and the first failures.  The test
suite runs a few hundred cases of the same generator (``tests/cli/test_fuzz.py``).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
import warnings
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TIMEOUT = 60  # seconds per case: a hang, not a slow machine

MODELS = ["lambert", "phong", "blinn-phong", "cook-torrance", "oren-nayar", "oren-nayar-simple",
          "ggx", "gltf", "disney-diffuse", "ue4", "merl", "abc", "sgd"]
MATERIALS = ["gold-metallic-paint", "alum-bronze", "blue-metallic-paint", "GOLD-METALLIC-PAINT",
             "gold", "", "x\ny", "nothere"]
MODEL_NOISE = ["Phong", "GGX", "cook-torance", "phong2", "", "-", "lamb\nert", "ggx\x1b[2J",
               "merl.binary", "ｐｈｏｎｇ"]
PARAMS = ["kd", "ks", "n", "f0", "m", "alpha", "fresnel", "sigma", "base_color", "metallic",
          "roughness", "file", "lookup", "distribution", "KD", "M", "k\nd", "", "material"]
NUMBERS = ["0", "1", "0.5", "30", "45", "89.9", "90", "95", "-1", "-0", "1e-300", "5e-324",
           "1e308", "1e999", "nan", "inf", "-inf", "1_0", "٣", "３", "0x10", "1e", ".", "",
           " 3", "3\n0", "9" * 400, "9" * 5000, "1,2,3", "0.1,0.2", "0.5,0.5,0.5", "abc",
           "10000", "1e4", "360", "-360", "361", "180", "-180"]
CHOICES = ["exact", "schlick", "Exact", "nearest", "trilinear", "ggx", "beckmann", "x"]
VIEWS = ["map", "incidence", "perpendicular", "solid", "albedo", "all", "sphere", "plane",
         "slice", "theta-h", "theta-d", "MAP", "mapp", ""]
COLORS = ["auto", "truecolor", "256", "none", "None", "16"]
SIZES = ["12", "20", "6", "11", "1001", "0", "-5", "x", "1_2", "٣٠"]
STRIDES = ["9,9,45", "45,45,45", "1,3,15", "0,1,1", "1,1", "a,b,c", "46,1,1", "1,٣,1"]
PRESETS = ["diffuse", "specular", "nothere", "bad name", "a\nb", "../x", "x" * 80,
           "big", "deep", "digits", "fifo", "dir", "merlfifo", "ok", "notoml", "Diffuse"]
OPTIONS = {
    "eval": ["--theta-i", "--theta-r", "--phi-r", "--cosine", "--json", "-p", "--theta"],
    "albedo": ["--theta-i", "--json", "-p"],
    "render": ["--theta-i", "--view", "--width", "--height", "--color", "--no-color", "--cmap",
               "--log", "--cosine", "--azimuth", "--elevation", "-p", "--section-azimuth",
               "--exposure", "--gamma", "--theta-d", "--theta-h", "--phi-d", "--linear-theta-h"],
    "fit": ["--model", "-p", "--stride", "--mean", "--json", "--save-preset"],
    "view": ["--theta-i", "--preset", "--color", "--no-color", "-p", "--material", "--fit",
             "--compare-fit", "--compare-material"],
    "models": ["--json"],
    "materials": ["--json", "--color", "--no-color"],
}
COMMANDS = [*OPTIONS, "Models", "evl", "", "-h", "--version", "--help"]


class Sandbox:
    """Files for the fuzz: hostile MERL files and presets in a temporary directory; sets
    ``XDG_CONFIG_HOME`` so presets are read (and written) there."""

    def __init__(self, root: Path):
        self.root = root
        f = root / "files"
        f.mkdir()
        (f / "empty.binary").write_bytes(b"")
        (f / "garbage.binary").write_bytes(b"\x00\x01" * 100)
        (f / "header.binary").write_bytes(
            (90).to_bytes(4, "little") + (90).to_bytes(4, "little")
            + (180).to_bytes(4, "little") + b"\0" * 64)  # right header, truncated data
        (f / "dir.binary").mkdir()
        self.files = [str(f / n) for n in ("empty.binary", "garbage.binary", "header.binary",
                                            "dir.binary", "none.binary")]
        self.files += ["", "x.binary\n", str(f / "dir.binary") + "/"]
        if hasattr(os, "mkfifo"):
            os.mkfifo(f / "fifo.binary")
            (f / "link.binary").symlink_to(f / "fifo.binary")
            self.files += [str(f / "fifo.binary"), str(f / "link.binary")]
        cfg = root / "cfg"
        p = cfg / "tuibrdf" / "presets"
        p.mkdir(parents=True)
        head = 'theta_i = 30\n[[sides]]\nmodel = "phong"\n'
        (p / "big.toml").write_text(head + "params = { kd = " + "9" * 400 + " }\n")
        (p / "deep.toml").write_text("a = " + "[" * 600 + "]" * 600 + "\n")
        (p / "digits.toml").write_text("theta_i = " + "9" * 5000 + "\n")
        (p / "ok.toml").write_text(head + "params = { kd = 0.1 }\n")
        (p / "notoml.toml").write_text("theta_i = = 1\n")
        (p / "dir.toml").mkdir()
        (p / "merlfifo.toml").write_text(
            f'[[sides]]\nmodel = "merl"\nparams = {{ file = "{f / "fifo.binary"}" }}\n')
        if hasattr(os, "mkfifo"):
            os.mkfifo(p / "fifo.toml")
        self.env = {"XDG_CONFIG_HOME": str(cfg)}


def random_argv(rng: random.Random, box: Sandbox) -> list[str]:
    """One command line: mostly well-formed shapes with hostile values, sometimes noise."""
    cmd = rng.choice(COMMANDS)
    argv = [cmd] if cmd else []
    opts = OPTIONS.get(cmd, [])
    if cmd in ("eval", "albedo", "render"):
        argv.append(rng.choice(MODELS + MODEL_NOISE) if rng.random() < 0.9 else "--json")
    elif cmd == "view" and rng.random() < 0.7:
        argv.append(rng.choice(MODELS[:-1] + MODEL_NOISE + box.files))
    elif cmd == "fit":
        argv.append(rng.choice(box.files))
    elif cmd == "models":
        argv += rng.sample(MODELS + MODEL_NOISE, rng.randint(0, 2))
    if cmd == "eval" and rng.random() < 0.8:  # mostly the required options, to get further
        argv += ["--theta-i", rng.choice(NUMBERS[:12]), "--theta-r",
                 *rng.sample(NUMBERS[:12], rng.randint(1, 3)), "--phi-r",
                 *rng.sample(NUMBERS[-8:], rng.randint(1, 2))]
    if cmd == "fit" and rng.random() < 0.8:
        argv += ["--model", rng.choice(MODELS + MODEL_NOISE)]
    for _ in range(rng.randint(0, 4)):
        if not opts or rng.random() < 0.1:
            argv.append(rng.choice(NUMBERS + MODEL_NOISE + ["--", "-x", "--bogus"]))
            continue
        o = rng.choice(opts)
        argv.append(o)
        if o == "-p":
            name = rng.choice(PARAMS)
            value = rng.choice(box.files if name == "file" else
                               CHOICES if name in ("fresnel", "lookup", "distribution")
                               else MATERIALS if name == "material" else NUMBERS)
            argv.append(rng.choice([f"{name}={value}", f"{name}", f"={value}", f"{name}=="]))
        elif o in ("--material", "--compare-material"):
            argv.append(rng.choice(MATERIALS))
        elif o == "--fit":
            argv.append(rng.choice(["abc", "sgd", "ABC", "x"]))
        elif o in ("--theta-i", "--theta-r", "--phi-r", "--azimuth", "--elevation",
                   "--section-azimuth", "--exposure", "--gamma", "--theta-d", "--theta-h",
                   "--phi-d"):
            argv += rng.sample(NUMBERS, rng.randint(1, 2 if cmd == "albedo" else 1))
        elif o == "--view":
            argv.append(rng.choice(VIEWS))
        elif o == "--color":
            argv.append(rng.choice(COLORS))
        elif o in ("--width", "--height"):
            argv.append(rng.choice(SIZES))
        elif o == "--cmap":
            argv.append(rng.choice(["grey", "viridis", "inferno", "jet"]))
        elif o == "--stride":
            argv.append(rng.choice(STRIDES))
        elif o in ("--preset", "--save-preset"):
            argv.append(rng.choice(PRESETS))
        elif o == "--model":
            argv.append(rng.choice(MODELS + MODEL_NOISE))
    if cmd == "render" and "--width" not in argv:
        argv += ["--width", "24", "--height", "8"]  # keep the fuzz fast
    return argv


class Hang(Exception):
    pass


def _alarm(signum, frame):
    raise Hang()


def judge(rc, err: str, timed_out: bool = False) -> str:
    """``""`` for a pass, else the kind of failure."""
    if timed_out:
        return "hang"
    if "Traceback" in err:
        return "traceback"
    if "Warning" in err:
        return "warning"
    if rc == 0:
        return "" if err == "" else "exit 0 with stderr"
    if rc != 2:
        return f"exit {rc}"
    lines = err.strip("\n").split("\n")
    if len(lines) != 1:
        return "exit 2, several lines"
    if not lines[0].startswith("tuibrdf"):
        return "exit 2, unprefixed line"
    return ""


def run_in_process(argv: list[str]) -> tuple[int, str, str, str]:
    """(rc, stdout, stderr, failure kind) of ``main(argv)`` with captured streams."""
    from tuibrdf.cli import main

    out, err = io.StringIO(), io.StringIO()
    old = signal.signal(signal.SIGALRM, _alarm) if hasattr(signal, "SIGALRM") else None
    if old is not None:
        signal.alarm(TIMEOUT)
    timed_out = False
    rc = None
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = main(argv)
    except Hang:
        timed_out = True
    except SystemExit as e:  # main() must return, never exit
        err.write(f"SystemExit({e.code}) escaped main()\n")
        rc = e.code
    except BaseException as e:  # noqa: BLE001 — anything escaping main() is a failure
        import traceback

        err.write("Traceback (escaped main()):\n" + "".join(traceback.format_exception(e)))
    finally:
        if old is not None:
            signal.alarm(0)
            signal.signal(signal.SIGALRM, old)
    e = err.getvalue()
    return rc, out.getvalue(), e, judge(rc, e, timed_out)


def run_subprocess(argv: list[str], env: dict) -> tuple[int, str, str, str]:
    # the tuibrdf this process imported (PYTHONPATH decides which copy: a worktree, main)
    import tuibrdf

    e = {**os.environ, "PYTHONPATH": str(Path(tuibrdf.__file__).resolve().parents[1]), **env}
    try:
        p = subprocess.run([sys.executable, "-m", "tuibrdf", *argv], capture_output=True,
                           stdin=subprocess.DEVNULL, env=e, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return -1, "", "", "hang"
    err = p.stderr.decode("utf-8", "replace")
    return p.returncode, p.stdout.decode("utf-8", "replace"), err, judge(p.returncode, err)


@contextlib.contextmanager
def guarded(box: Sandbox):
    """The sandbox's environment, warnings as errors, and a viewer that must never open."""
    import tuibrdf.cli.view as view

    def never(*a, **k):
        raise AssertionError("the viewer was opened during the fuzz")

    saved_env = {k: os.environ.get(k) for k in box.env}
    os.environ.update(box.env)
    saved_open = getattr(view, "open_viewer", None)
    if saved_open is not None:
        view.open_viewer = never
    try:
        from tuibrdf.app.app import BrdfApp  # older versions open the app directly

        saved_run, BrdfApp.run = BrdfApp.run, never
    except ImportError:
        saved_run = None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            yield
    finally:
        if saved_open is not None:
            view.open_viewer = saved_open
        if saved_run is not None:
            BrdfApp.run = saved_run
        for k, v in saved_env.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def fuzz(cases: int, seed: int, n_sub: int, show: int = 10) -> dict:
    rng = random.Random(seed)
    counts: Counter = Counter()
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        box = Sandbox(Path(tmp))
        argvs = [random_argv(rng, box) for _ in range(cases)]
        t0 = time.perf_counter()
        with guarded(box):
            for argv in argvs:
                rc, _, err, kind = run_in_process(argv)
                counts[f"exit {rc}" if not kind else f"FAIL {kind}"] += 1
                if kind:
                    failures.append(("in-process", argv, kind, err))
        for argv in rng.sample(argvs, min(n_sub, len(argvs))):
            rc, _, err, kind = run_subprocess(argv, box.env)
            counts[f"subprocess exit {rc}" if not kind else f"FAIL subprocess {kind}"] += 1
            if kind:
                failures.append(("subprocess", argv, kind, err))
        seconds = time.perf_counter() - t0
    return {"cases": cases, "subprocesses": min(n_sub, cases), "seed": seed,
            "counts": dict(sorted(counts.items())), "failures": failures, "seconds": seconds}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=3000)
    ap.add_argument("--seed", type=int, default=17)
    ap.add_argument("--subprocess", type=int, default=100, dest="n_sub")
    ap.add_argument("--show", type=int, default=10, help="failures to print")
    ap.add_argument("--timeout", type=int, default=TIMEOUT,
                    help=f"seconds after which a case counts as a hang (default {TIMEOUT})")
    a = ap.parse_args()
    globals()["TIMEOUT"] = a.timeout
    r = fuzz(a.cases, a.seed, a.n_sub)
    print(f"fuzz_cli: {r['cases']} in-process cases + {r['subprocesses']} subprocesses, "
          f"seed {r['seed']}, {r['seconds']:.0f} s")
    for k, v in r["counts"].items():
        print(f"  {k:32s} {v}")
    kinds = Counter(k for _, _, k, _ in r["failures"])
    print(f"failures: {len(r['failures'])}" + (f" ({dict(kinds)})" if kinds else ""))
    for where, argv, kind, err in r["failures"][:a.show]:
        last = err.strip().splitlines()[-1] if err.strip() else ""
        print(f"  [{where}] {kind}: {argv!r}\n      {last[:200]}")
    return 1 if r["failures"] else 0


if __name__ == "__main__":
    sys.exit(main())
