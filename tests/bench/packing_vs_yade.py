#!/usr/bin/python3
"""dspdem against YADE on the packing (issue 19): the same tetrahedra in the same open box.

  /usr/bin/python3 tests/bench/packing_vs_yade.py [--dspdem build/dspdem] [--count 500]
      [--threads 1,2] [--out results/packing_vs_yade]

Steps (every run a separate process; run nothing else heavy meanwhile):
 1. dspdem meshes cases/packing.toml with --count particles and runs it until the heap is at
    rest (kinetic energy below 1e-4 of the potential energy released): time to settle.
 2. The settled heap (the last frame's nodes) is written as a mesh of its own.
 3. From the initial column (free fall) and from the settled heap (bed), each code runs a fixed
    number of steps on 1 and 2 threads: particle-steps per second. dspdem's rate is taken from
    two run lengths (their difference drops the set-up); YADE times O.run() itself.
 4. A table in OUT/packing_vs_yade.md and on stdout, with the ratios.

Same tetrahedra (vertex for vertex), density, friction, box and gravity. Differences, by
necessity: dspdem's particles are deformable single-tet bodies with spheropolyhedral contact
and viscous contact damping; YADE's are rigid polyhedra with the volumetric law (its `young`
is a force per overlap volume) and its local damping. YADE's step is set by hand,
0.5 r_min / sqrt(E / rho) (PWaveTimeStep() returns 1.0 s for polyhedra); dspdem uses its own.
YADE (Debian `yade`) is installed if missing: a benchmark dependency, not a build one.
Needs python3-vtk9 (Debian's /usr/bin/python3) to read the frames.
"""
import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
CASE = ROOT / "cases" / "packing.toml"


def sh(args, log):
    with open(log, "w") as f:
        r = subprocess.run([str(a) for a in args], stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        sys.exit(f"packing_vs_yade: {' '.join(map(str, args))} failed (exit {r.returncode}); see {log}")


def ensure_yade():
    if shutil.which("yade"):
        return
    print("yade not found: installing Debian's yade (benchmark dependency)", flush=True)
    cmd = ["apt-get", "install", "-y", "-q", "yade"]
    if os.geteuid() != 0:
        cmd = ["sudo"] + cmd
    if subprocess.run(cmd, env=dict(os.environ, DEBIAN_FRONTEND="noninteractive")).returncode != 0 or not shutil.which("yade"):
        sys.exit("packing_vs_yade: could not install yade (apt-get install yade)")


def read_series(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def time_to_rest(rows, ratio=1e-4):
    """First series time from which kinetic / released potential energy stays below ratio."""
    t_rest = None
    for r in rows:
        released = float(r["external_work"])  # gravity is the only external load
        at_rest = released > 0 and float(r["kinetic"]) < ratio * released
        if at_rest and t_rest is None:
            t_rest = float(r["time"])
        elif not at_rest:
            t_rest = None
    return t_rest


def read_msh_tets(path):
    """Nodes and tetrahedra of the gmsh 4.1 ASCII file dspdem's packing generator writes."""
    lines = Path(path).read_text().split("\n")
    i = lines.index("$Nodes") + 1
    n_blocks = int(lines[i].split()[0])
    i += 1
    nodes = {}
    for _ in range(n_blocks):
        _, _, _, n = map(int, lines[i].split())
        tags = [int(x) for x in lines[i + 1:i + 1 + n]]
        for k, t in enumerate(tags):
            nodes[t] = tuple(map(float, lines[i + 1 + n + k].split()[:3]))
        i += 1 + 2 * n
    i = lines.index("$Elements") + 1
    n_blocks = int(lines[i].split()[0])
    i += 1
    tets = []
    for _ in range(n_blocks):
        _, _, etype, n = map(int, lines[i].split())
        if etype == 4:
            tets += [tuple(map(int, lines[i + 1 + k].split()[1:5])) for k in range(n)]
        i += 1 + n
    return nodes, tets


def settled_vertices(vtu):
    """Per cell the four vertices of a dspdem frame (its points are the deformed positions)."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(vtu))
    r.Update()
    g = r.GetOutput()
    x = vtk_to_numpy(g.GetPoints().GetData())
    cells = []
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        cells.append([tuple(map(float, x[ids.GetId(k)])) for k in range(4)])
    return cells


def write_msh2(path, tets):
    """Each tetrahedron with its own four nodes, physical group 1 'particles' (gmsh 2.2)."""
    with open(path, "w") as f:
        f.write('$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 "particles"\n$EndPhysicalNames\n')
        f.write(f"$Nodes\n{4 * len(tets)}\n")
        for e, v in enumerate(tets):
            for k, p in enumerate(v):
                f.write(f"{4 * e + k + 1} {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}\n")
        f.write(f"$EndNodes\n$Elements\n{len(tets)}\n")
        for e in range(len(tets)):
            f.write(f"{e + 1} 4 2 1 1 {4 * e + 1} {4 * e + 2} {4 * e + 3} {4 * e + 4}\n")
        f.write("$EndElements\n")


def case_on_mesh(path, msh):
    """cases/packing.toml with its generator replaced by the mesh file `msh`."""
    text = re.sub(r"^\[mesh\.packing\]\n(?:(?!\[).*\n)*", "", CASE.read_text(), flags=re.M)
    text = text.replace('generator = "packing"', f'file = "{msh}"')
    Path(path).write_text(text)


def dspdem_rate(a, case, threads, steps, dt, out):
    """Particle-steps/s of dspdem from runs of `steps` and 3 x `steps` steps."""
    out.mkdir(parents=True, exist_ok=True)
    walls = []
    for n in (steps, 3 * steps):
        d = out / f"n{n}"
        sh([a.dspdem, "-q", "-t", threads, "run", case, "--discard-interrupted", "--set", f"time.end={n * dt:.9g}", "--set", f"output.frame_interval={n * dt:.9g}", "--out", d], out / f"n{n}.log")
        s = json.loads((d / "summary.json").read_text())
        walls.append((s["steps"], s["wall_s"], s["elements"]))
        contacts = int(read_series(d / "series.csv")[-1]["contacts"])
    (s1, w1, n), (s3, w3, _) = walls
    return n * (s3 - s1) / (w3 - w1), contacts


def yade_rate(a, particles, threads, steps, out):
    out.mkdir(parents=True, exist_ok=True)
    p = {"particles": particles, "density": a.density, "young": a.young, "young_material": a.young, "poisson": 0.25,
         "friction": 0.5, "damping": 0.3, "gravity": [0.0, -9.81, 0.0], "box": [16.0, 13.8], "steps": steps}
    (out / "in.json").write_text(json.dumps(p))
    sh(["yade", "-n", "-j", threads, "-x", HERE / "yade_packing.py", out / "in.json", out / "out.json"], out / "yade.log")
    r = json.loads((out / "out.json").read_text())
    if not r["finite"]:
        sys.exit(f"packing_vs_yade: YADE's run in {out} went non-finite (step {r['dt']:.3g} s too large?)")
    return len(particles) / r["s_per_step"], r["interactions"], r["dt"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dspdem", default=str(ROOT / "build" / "dspdem"))
    ap.add_argument("--count", type=int, default=500, help="particles (the paper: 5346)")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--settle-end", type=float, default=4.0, help="dspdem's settling run [s]")
    ap.add_argument("--steps", type=int, default=1000, help="timed dspdem steps per run length")
    ap.add_argument("--yade-steps", type=int, default=200, help="timed YADE steps")
    ap.add_argument("--out", default=str(ROOT / "results" / "packing_vs_yade"))
    a = ap.parse_args()
    a.density, a.young = 2000.0, 1.0e9  # cases/packing.toml
    out = Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    threads = [int(t) for t in a.threads.split(",")]
    ensure_yade()

    # 1. The column and dspdem's settling run.
    sh([a.dspdem, "-q", "mesh", CASE, "--set", f"mesh.packing.count={a.count}", "--out", out / "mesh"], out / "mesh.log")
    nodes, tets = read_msh_tets(out / "mesh" / "packing.msh")
    initial = [[nodes[t] for t in tet] for tet in tets]
    settle = out / "dspdem_settle"
    sh([a.dspdem, "-q", "-t", "1", "run", CASE, "--discard-interrupted", "--set", f"mesh.packing.count={a.count}", "--set",
        f"time.end={a.settle_end}", "--set", f"output.frame_interval={a.settle_end}", "--out", settle],
       out / "dspdem_settle.log")
    summ = json.loads((settle / "summary.json").read_text())
    rows = read_series(settle / "series.csv")
    t_rest = time_to_rest(rows)
    dt = summ["dt"]
    frames = sorted((settle / "frames").glob("frame_*.vtu"))
    bed = settled_vertices(frames[-1])

    # 2. Both states as meshes of their own (the same file format for both).
    write_msh2(out / "initial.msh", initial)
    write_msh2(out / "settled.msh", bed)
    for state in ("initial", "settled"):
        case_on_mesh(out / f"{state}.toml", out / f"{state}.msh")

    # 3. Rates.
    res = []
    for state, verts in (("free fall", initial), ("settled bed", bed)):
        key = "initial" if state == "free fall" else "settled"
        for t in threads:
            d_rate, d_contacts = dspdem_rate(a, out / f"{key}.toml", t, a.steps, dt, out / f"dspdem_{key}_t{t}")
            y_rate, y_inter, y_dt = yade_rate(a, verts, t, a.yade_steps, out / f"yade_{key}_t{t}")
            res.append((state, t, d_rate, d_contacts, y_rate, y_inter, y_dt))
            print(f"{state}, {t} thread(s): dspdem {d_rate:.4g}, YADE {y_rate:.4g} particle-steps/s", flush=True)

    # 4. The table.
    lines = [f"# dspdem against YADE: packing of {a.count} tetrahedra", "",
             f"Machine: {os.cpu_count()} cores; command: `{' '.join(sys.argv)}`.", "",
             f"dspdem's settling run (1 thread): at rest (kinetic < 1e-4 of the released potential energy) from "
             f"t = {t_rest if t_rest is not None else 'never'} s of {summ['t_end']:.3g} s simulated; "
             f"{summ['steps']} steps of {dt:.3g} s in {summ['wall_s']:.0f} s wall.", "",
             "| state | threads | dspdem [particle-steps/s] | dspdem contacts | YADE [particle-steps/s] | "
             "YADE interactions | YADE dt [s] | dspdem / YADE per step | dspdem / YADE per simulated second |",
             "|---|---|---|---|---|---|---|---|---|"]
    for state, t, dr, dc, yr, yi, ydt in res:
        lines.append(f"| {state} | {t} | {dr:.4g} | {dc} | {yr:.4g} | {yi} | {ydt:.3g} | {dr / yr:.1f} | "
                     f"{dr / yr * dt / ydt:.1f} |")
    lines += ["", "dspdem counts feature contacts (a face on a face counts 3); YADE counts real interactions "
              "(one per touching pair, walls included). YADE's time to settle was not run: at its measured "
              "settled-bed rate the settling would take "]
    y1 = [r for r in res if r[0] == "settled bed" and r[1] == threads[0]][0]
    if t_rest is not None:
        est = t_rest / y1[6] * a.count / y1[4]
        lines[-1] += f"about {est:.0f} s wall on {threads[0]} thread(s) (estimate: steps to {t_rest:.2f} s at its dt, at the bed's rate)."
    else:
        lines[-1] += "(no estimate: dspdem's heap did not come to rest; raise --settle-end)."
    (out / "packing_vs_yade.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
