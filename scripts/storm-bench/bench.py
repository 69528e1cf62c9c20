"""Times truecost's exact optimum against Storm's exact and sound engines, whole processes,
interleaved (every round runs each tool once on each case, in turn), on benchmark grids and
Gymnasium environments. See README.md.

    python bench.py [--rounds N] [--timeout S] [--cases NAME,...] > table.md
"""

import argparse
import os
import re
import platform
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
TRUECOST = os.environ.get("TRUECOST", os.path.join(REPO, "target", "release", "truecost"))
CHECK = os.path.join(HERE, "storm_check.py")

# (name, export source, gamma for the grid): grids are solved by truecost from their
# deterministic file with --gamma (paper noise), Storm from the DRN export of the same MDP.
CASES = [
    ("random 20x20, gamma 0.99", ["--grid", "20x20", "--pattern", "random"], "0.99"),
    ("walls 20x20, gamma 0.99", ["--grid", "20x20", "--pattern", "walls"], "0.99"),
    ("random 50x50, gamma 0.99", ["--grid", "50x50", "--pattern", "random"], "0.99"),
    ("walls 50x50, gamma 0.99", ["--grid", "50x50", "--pattern", "walls"], "0.99"),
    ("walls 100x100, gamma 0.999", ["--grid", "100x100", "--pattern", "walls"], "0.999"),
    ("random 100x100, gamma 0.999", ["--grid", "100x100", "--pattern", "random"], "0.999"),
    ("FrozenLake 8x8", ["--env", "frozenlake:map=8x8"], None),
    ("CliffWalking (slippery)", ["--env", "cliffwalking:slippery=true"], None),
    ("Taxi", ["--env", "taxi"], None),
]


def run(cmd, timeout, out=None):
    """Wall time of a whole process and its standard output (written to the file `out` instead,
    if given: the JSON reports with every value are hundreds of megabytes); None on a timeout."""
    start = time.perf_counter()
    try:
        if out is None:
            done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        else:
            with open(out, "w") as f:
                done = subprocess.run(cmd, stdout=f, stderr=subprocess.PIPE, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "timeout"
    elapsed = time.perf_counter() - start
    if out is not None:
        os.remove(out)
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed: {done.stderr.strip()}")
    return elapsed, done.stdout or ""


def answer_digits(text):
    """Digits of the exact answer (numerator + denominator) from truecost's text report."""
    m = re.search(r"a (\d+)-digit numerator over a (\d+)-digit denominator", text)
    if m:
        return int(m.group(1)) + int(m.group(2))
    m = re.search(r"^(?:G\*\(x1\)|cost_to_go_initial)\s+(-?\d+)(?:/(\d+))?(?: =| ~|$)", text, re.M)
    return len(m.group(1).lstrip("-")) + len(m.group(2) or "") if m else None


def prepare(tmp, name, source, gamma):
    """The files of a case and the commands of each tool."""
    base = os.path.join(tmp, "".join(c if c.isalnum() else "-" for c in name))
    drn = base + ".drn"
    export = [TRUECOST, "export", *source, "--format", "drn", "--out", drn]
    if gamma:
        export += ["--gamma", gamma]
    subprocess.run(export, check=True, capture_output=True)
    if gamma:
        own = base + ".json"
        subprocess.run([TRUECOST, "export", *source, "--out", own], check=True, capture_output=True)
        truecost = [TRUECOST, "solve", "--file", own, "--gamma", gamma, "--algorithm", "exact", "--quiet"]
    else:
        truecost = [TRUECOST, "solve", *source, "--algorithm", "exact", "--objective", "truecost"]
    commands = {
        "truecost exact": (truecost, None),
        "Storm exact": ([sys.executable, CHECK, drn, "exact"], None),
        "Storm sound": ([sys.executable, CHECK, drn, "sound"], None),
    }
    if gamma:
        # Every state's exact value, as JSON, written to a file (as a user would keep it).
        commands["truecost JSON"] = (truecost + ["--format", "json"], base + ".out.json")
    return commands


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--cases", help="comma-separated prefixes of case names")
    args = ap.parse_args()
    cases = CASES
    if args.cases:
        wanted = args.cases.split(",")
        cases = [c for c in CASES if any(c[0].startswith(w) for w in wanted)]
    tools = ["truecost exact", "truecost JSON", "Storm exact", "Storm sound"]
    with tempfile.TemporaryDirectory() as tmp:
        commands = {c[0]: prepare(tmp, *c) for c in cases}
        times = {(c[0], t): [] for c in cases for t in tools}
        digits = {}
        timed_out = set()
        for _ in range(args.rounds):
            for name, _, _ in cases:
                for tool in tools:
                    if (name, tool) in timed_out or tool not in commands[name]:
                        continue
                    cmd, out = commands[name][tool]
                    elapsed, text = run(cmd, args.timeout, out)
                    if elapsed is None:
                        timed_out.add((name, tool))
                    else:
                        times[(name, tool)].append(elapsed)
                    if tool == "truecost exact" and elapsed is not None:
                        digits[name] = answer_digits(text)
                    print(f"{name} | {tool} | {elapsed}", file=sys.stderr)
    load = os.getloadavg()
    print(f"Date: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; machine: "
          f"{platform.machine()}, {os.cpu_count()} cores ({platform.processor() or platform.platform()}); "
          f"load average at the end {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f}; "
          f"{args.rounds} round(s), the best wall time of each.\n")
    print("| model | answer digits | truecost exact | truecost JSON | Storm exact | Storm sound "
          "| Storm exact / truecost | truecost / Storm sound | truecost JSON / Storm sound |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, _, _ in cases:
        best = {t: (min(times[(name, t)]) if times[(name, t)] else None) for t in tools}
        cell = {
            t: (f"{best[t]:.2f} s" if best[t] is not None
                else (f"> {args.timeout:.0f} s" if (name, t) in timed_out else "-"))
            for t in tools
        }
        tc, tj = best["truecost exact"], best["truecost JSON"]
        se, ss = best["Storm exact"], best["Storm sound"]
        r1 = f"{se / tc:.0f}x" if tc and se else (f"> {args.timeout / tc:.0f}x" if tc else "-")
        r2 = f"{tc / ss:.1f}x" if tc and ss else "-"
        r3 = f"{tj / ss:.1f}x" if tj and ss else "-"
        print(f"| {name} | {digits.get(name) or '-'} | {cell['truecost exact']} | {cell['truecost JSON']} "
              f"| {cell['Storm exact']} | {cell['Storm sound']} | {r1} | {r2} | {r3} |")


if __name__ == "__main__":
    main()
