#!/usr/bin/env python3
"""The cost of a step of a case, as a benchmark script (issue 19's measurement on the disc).

Runs `dspdem -q -t N run CASE` for its first steps (default: the Brazilian disc to t = 3.16e-4
s, about 8000 steps, before any joint breaks), on 1 and 2 threads, and reads each run's
summary.json: the time loop's wall time (set-up excluded) per step and per element-step. With
--vs OTHER_DSPDEM the same runs alternate with another binary (A B A B ...), and the ratio is
taken pair by pair, so that a box whose speed drifts still gives a fair ratio; the median of
the pairs is reported. Results go to a Markdown table on stdout.

  tests/bench/case_step.py [--bin build/dspdem] [--vs /path/to/old/dspdem] [--vs-case OLD.toml]
                           [--case cases/brazilian_disc.toml] [--set KEY=VALUE ...]
                           [--pairs 3] [--threads 1 2] [--end 3.16e-4]

The sphere impact at 7.5 m/s to 0.75 ms after the first contact, where contact between its
pieces costs most of a step:
  tests/bench/case_step.py --case cases/sphere_impact.toml --end 8.77e-4 --threads 1

Run it on a quiet box: a second heavy process on a 2-core machine halves what it measures.
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def run(binary, threads, end, out, case, sets):
    cmd = [binary, "-q", "-t", str(threads), "run", str(case), "--set", f"time.end={end}",
           "--set", "output.frame_interval=1", "--out", str(out), "--no-progress"]
    for kv in sets:
        cmd += ["--set", kv]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"case_step.py: {' '.join(cmd)} failed ({r.returncode}):\n{r.stdout}{r.stderr}")
    s = json.loads((out / "summary.json").read_text())
    return {"ms_per_step": 1e3 * s["wall_s"] / s["steps"], "elements": s["elements"], "joints": s["joints"],
            "steps": s["steps"], "element_steps_per_s": s["element_steps_per_s"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=str(ROOT / "build/dspdem"), help="dspdem to measure (A)")
    ap.add_argument("--vs", help="another dspdem to compare with (B), run in turn with A")
    ap.add_argument("--case", default=str(ROOT / "cases/brazilian_disc.toml"), help="the case A runs")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a key of the case set for both binaries (repeatable)")
    ap.add_argument("--vs-case", help="the case B reads (an older binary may not know every key of the "
                    "shipped one; give it the case of its own commit); default: --case")
    ap.add_argument("--pairs", type=int, default=3, help="runs of each binary per thread count")
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--end", type=float, default=3.16e-4, help="simulated time to run [s]")
    a = ap.parse_args()
    rows = {}
    with tempfile.TemporaryDirectory(prefix="dspdem_case_step_") as tmp:
        for t in a.threads:
            A, B = [], []
            for i in range(a.pairs):
                A.append(run(a.bin, t, a.end, Path(tmp) / f"a{t}_{i}", a.case, a.set))
                if a.vs:
                    B.append(run(a.vs, t, a.end, Path(tmp) / f"b{t}_{i}", a.vs_case or a.case, a.set))
            rows[t] = (A, B)
    first = rows[a.threads[0]][0][0]
    sets = "".join(" --set " + kv for kv in a.set)
    print(f"{Path(a.case).name}{sets}, first {first['steps']} steps: {first['elements']} elements, "
          f"{first['joints']} joints; median of {a.pairs} run(s) per cell; set-up excluded.\n")
    head = "| threads | A ms/step | A element-steps/s |"
    if a.vs:
        head += " B ms/step | A/B (median of pairs) |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for t, (A, B) in rows.items():
        ma = statistics.median(r["ms_per_step"] for r in A)
        line = f"| {t} | {ma:.2f} | {statistics.median(r['element_steps_per_s'] for r in A):.3g} |"
        if a.vs:
            mb = statistics.median(r["ms_per_step"] for r in B)
            ratio = statistics.median(x["ms_per_step"] / y["ms_per_step"] for x, y in zip(A, B))
            line += f" {mb:.2f} | {ratio:.3f} |"
        print(line)
    if len(a.threads) > 1:
        t0, t1 = a.threads[0], a.threads[-1]
        for name, k in (("A", 0), ("B", 1)):
            if rows[t0][k] and rows[t1][k]:
                s0 = statistics.median(r["ms_per_step"] for r in rows[t0][k])
                s1 = statistics.median(r["ms_per_step"] for r in rows[t1][k])
                print(f"\n{name}: {t0} -> {t1} threads: {s0 / s1:.2f}x")


if __name__ == "__main__":
    main()
