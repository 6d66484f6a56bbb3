#!/usr/bin/env python3
"""Strong and weak scaling of a distributed run (mpirun) on this box, as a benchmark script.

The scene: the Galvez beam (cases/galvez_beam.toml) with joints on every face
(bodies.0.fracture = "all") and contact off: the elements and joints of the bulk, whose cost
grows with the volume (--contact times the contact scenes). Its element count is set by the crack band's element size. Each configuration runs
for S and 2S steps, and the cost of a step is the difference over S, the median of a few
repeats: meshing, model building and the partition drop out. Per run the log line of the partition gives the own
elements, ghost nodes and messages per step of each process.

  strong: the same beam on 1 process and on P processes (-t 1 each);
  weak:   a beam of about P times the elements on P processes, against the base on 1.

  tests/bench/mpi_scaling.py [--bin build/dspdem] [--procs 2] [--band 0.012] [--steps 2000] [--repeats 3]
  tests/bench/mpi_scaling.py --project [--cost 1.52e-7] [--ghost-k 7] ...   (no runs: the model)
  tests/bench/mpi_scaling.py --contact [--procs 2] [--repeats 3]   (the two contact scenes)

--contact times whole runs (wall_s of summary.json, set-up included) of the contact scenes on 1
and P processes: the Brazilian disc on 20 mm elements (the test's) to its split (the case's
stop rule, checked at each series row), and a packing of 1000
particles falling for 1.6 s. Their contact cost moves through the run (the jaws touch, the
disc splits, the particles land), so a window of steps would not stand for the run. The
partition's line and the contact line of the log give the shares.

Prints a Markdown table on stdout. Run it on a quiet box with one process per core.

--project prints the time of a step projected to 64-1024 processes with the model of
src/par/SCALING.md: the largest share's elements at the measured cost per element-step, plus
its redundant ghost elements, plus per step one message per neighbour (latency alpha), the
ghosts' 48 bytes each (bandwidth beta) and one reduction of log2 P rounds.
"""
import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def run(binary, procs, band, steps, out):
    cmd = ([] if procs == 1 else ["mpirun", "-n", str(procs)]) + [
        binary, "-t", "1", "run", str(ROOT / "cases/galvez_beam.toml"), "--no-progress",
        "--set", "contact.enabled=false", "--set", 'bodies.0.fracture="all"',
        "--set", f"mesh.galvez_beam.band_size={band}", "--set", f"mesh.galvez_beam.size={band}",
        "--set", f"time.max_steps={steps}", "--set", "output.frame_interval=1", "--out", str(out)]
    r = subprocess.run(cmd, capture_output=True, text=True, env=ENV)
    if r.returncode != 0:
        sys.exit(f"mpi_scaling.py: {' '.join(cmd)} failed ({r.returncode}):\n{r.stdout}{r.stderr}")
    s = json.loads((out / "summary.json").read_text())
    m = re.search(r"own elements (\S+), own nodes (\S+), ghost nodes (\S+), messages sent per step (\S+)", r.stderr)
    part = {k: [int(v) for v in m.group(i + 1).split("/")] for i, k in
            enumerate(["elements", "nodes", "ghosts", "messages"])} if m else None
    return s, part


def cost(binary, procs, band, steps, tmp, repeats):
    # The run's wall time includes meshing (or reading the mesh cache) and the set-up, which
    # vary: the median over repeats of the difference of two lengths is the step's cost.
    run(binary, procs, band, 1, Path(tmp) / f"p{procs}_{band}_warm")  # mesh cached before timing
    diffs = []
    for i in range(repeats):
        a, part = run(binary, procs, band, steps, Path(tmp) / f"p{procs}_{band}_a{i}")
        b, _ = run(binary, procs, band, 2 * steps, Path(tmp) / f"p{procs}_{band}_b{i}")
        diffs.append(1e3 * (b["wall_s"] - a["wall_s"]) / steps)
    return {"ms": statistics.median(diffs), "spread": (min(diffs), max(diffs)), "elements": a["elements"],
            "joints": a["joints"], "nodes": a["nodes"], "part": part}


CONTACT_SCENES = {
    "disc": ["cases/brazilian_disc.toml", "--set", "mesh.brazilian_disc.size=0.02",
             "--set", "output.frame_interval=1", "--set", "output.series_interval=1e-4"],
    "packing": ["cases/packing.toml", "--set", "mesh.packing.count=1000", "--set", "time.end=1.6",
                "--set", "output.frame_interval=1", "--set", "output.series_interval=0.1"],
}


def whole_runs(binary, procs, scene, tmp, repeats):
    walls, log = [], ""
    for i in range(repeats + 1):  # the first one meshes (cached for the others) and is dropped
        out = Path(tmp) / f"{scene}_p{procs}_{i}"
        args = [str(ROOT / CONTACT_SCENES[scene][0])] + CONTACT_SCENES[scene][1:]
        cmd = ([] if procs == 1 else ["mpirun", "-n", str(procs)]) + [
            binary, "-t", "1", "run"] + args + ["--no-progress", "--out", str(out)]
        r = subprocess.run(cmd, capture_output=True, text=True, env=ENV)
        if r.returncode != 0:
            sys.exit(f"mpi_scaling.py: {' '.join(cmd)} failed ({r.returncode}):\n{r.stdout}{r.stderr}")
        s = json.loads((out / "summary.json").read_text())
        if i > 0:
            walls.append(s["wall_s"])
        log = r.stderr
    lines = [l.strip() for l in log.splitlines() if "distributed over" in l or "contact per process" in l]
    return {"s": statistics.median(walls), "spread": (min(walls), max(walls)), "steps": s["steps"],
            "elements": s["elements"], "log": lines}


def contact(a):
    P = a.procs
    print(f"Contact scenes, whole runs (set-up included), median of {a.repeats}; -t 1 per process.\n")
    print("| scene | elements | steps | 1 process [s] (min-max) | "
          f"{P} processes [s] (min-max) | speed-up | efficiency |")
    print("|---|---|---|---|---|---|---|")
    notes = []
    with tempfile.TemporaryDirectory(prefix="dspdem_mpi_contact_") as tmp:
        for scene in CONTACT_SCENES:
            one = whole_runs(a.bin, 1, scene, tmp, a.repeats)
            many = whole_runs(a.bin, P, scene, tmp, a.repeats)
            print(f"| {scene} | {one['elements']} | {one['steps']} | {one['s']:.2f} "
                  f"({one['spread'][0]:.2f}-{one['spread'][1]:.2f}) | {many['s']:.2f} "
                  f"({many['spread'][0]:.2f}-{many['spread'][1]:.2f}) | {one['s'] / many['s']:.2f} | "
                  f"{one['s'] / many['s'] / P:.2f} |")
            notes += [f"{scene}: {l}" for l in many["log"]]
    print()
    for n in notes:
        print(f"- {n}")


def step_time(n, P, a):
    """Projected time of a step [s] for n elements per process on P processes."""
    n_max = a.imbalance * n
    ghosts = a.ghost_k * n_max ** (2 / 3)  # ghost nodes of the largest share (surface law, fitted)
    redundant = ghosts / 4  # joints everywhere: 4 nodes per ghost element
    compute = a.cost * (n_max + redundant)
    comm = a.neighbours * a.alpha + 48 * ghosts / a.beta + 2 * a.alpha * math.log2(P)
    return compute, comm, ghosts


def project(a):
    print(f"Model: cost {a.cost:.3g} s per element-step, ghost nodes {a.ghost_k} (n_max)^(2/3), imbalance "
          f"{a.imbalance}, {a.neighbours} neighbours, alpha {a.alpha * 1e6:.3g} us, beta {a.beta / 1e9:.3g} GB/s.\n")
    print(f"Strong scaling, {a.elements:.3g} elements:\n")
    print("| processes | elements per process | ghost nodes | compute [ms] | communication [ms] | step [ms] | "
          "speed-up | efficiency |")
    print("|---|---|---|---|---|---|---|---|")
    serial = a.cost * a.elements
    for P in [64, 128, 256, 512, 1024]:
        c, m, g = step_time(a.elements / P, P, a)
        t = c + m
        print(f"| {P} | {a.elements / P:.0f} | {g:.0f} | {1e3 * c:.3f} | {1e3 * m:.3f} | {1e3 * t:.3f} | "
              f"{serial / t:.0f} | {serial / t / P:.2f} |")
    print(f"\nWeak scaling, {a.per_process:.0f} elements per process:\n")
    print("| processes | elements | step [ms] | efficiency |")
    print("|---|---|---|---|")
    one = a.cost * a.per_process
    for P in [64, 128, 256, 512, 1024]:
        c, m, _ = step_time(a.per_process, P, a)
        print(f"| {P} | {P * a.per_process:.3g} | {1e3 * (c + m):.3f} | {one / (c + m):.2f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--project", action="store_true", help="print the model's projection only")
    ap.add_argument("--contact", action="store_true", help="time the contact scenes' whole runs")
    ap.add_argument("--cost", type=float, default=1.52e-7, help="s per element-step on one process")
    ap.add_argument("--ghost-k", type=float, default=7.0)
    ap.add_argument("--imbalance", type=float, default=1.03)
    ap.add_argument("--neighbours", type=int, default=14)
    ap.add_argument("--alpha", type=float, default=2e-6, help="latency per message [s]")
    ap.add_argument("--beta", type=float, default=10e9, help="bandwidth [bytes/s]")
    ap.add_argument("--elements", type=float, default=4.4e6, help="strong scaling: the model's elements")
    ap.add_argument("--per-process", type=float, default=2e4, help="weak scaling: elements per process")
    ap.add_argument("--bin", default=str(ROOT / "build/dspdem"))
    ap.add_argument("--procs", type=int, default=2)
    ap.add_argument("--band", type=float, default=0.012, help="element size of the strong-scaling beam [m]")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    if a.project:
        return project(a)
    if a.contact:
        return contact(a)
    P = a.procs
    weak_band = a.band / P ** (1 / 3)  # about P times the elements
    with tempfile.TemporaryDirectory(prefix="dspdem_mpi_scaling_") as tmp:
        one = cost(a.bin, 1, a.band, a.steps, tmp, a.repeats)
        many = cost(a.bin, P, a.band, a.steps, tmp, a.repeats)
        weak = cost(a.bin, P, weak_band, a.steps, tmp, a.repeats)
    print(f"Galvez beam, joints everywhere, contact off; cost of a step from runs of {a.steps} and "
          f"{2 * a.steps} steps (set-up excluded), median of {a.repeats}; -t 1 per process.\n")
    print("| run | processes | elements | joints | nodes | ms/step (min-max) | element-steps/s per process | "
          "own elements per process | ghost nodes per process | messages sent per step |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, p, r in [("base", 1, one), ("strong", P, many), ("weak", P, weak)]:
        part = r["part"] or {"elements": [r["elements"]], "ghosts": [0], "messages": [0]}
        rate = r["elements"] / p / (r["ms"] * 1e-3)
        print(f"| {name} | {p} | {r['elements']} | {r['joints']} | {r['nodes']} | {r['ms']:.3f} "
              f"({r['spread'][0]:.3f}-{r['spread'][1]:.3f}) | {rate:.3g} | "
              f"{'/'.join(map(str, part['elements']))} | {'/'.join(map(str, part['ghosts']))} | "
              f"{'/'.join(map(str, part['messages']))} |")
    print(f"\nstrong: speed-up {one['ms'] / many['ms']:.2f} on {P} processes (efficiency "
          f"{one['ms'] / many['ms'] / P:.2f}); weak: {weak['elements'] / one['elements']:.2f}x the elements in "
          f"{weak['ms'] / one['ms']:.2f}x the time per step (efficiency "
          f"{one['ms'] / weak['ms'] * weak['elements'] / one['elements'] / P:.2f})")


if __name__ == "__main__":
    main()
