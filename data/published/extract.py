#!/usr/bin/env python3
"""Regenerates deterministic.csv and stochastic.csv in this directory from the paper's public
repository (github.com/filkata123/valit_q_comparison), read from a bare git clone:

    python3 data/published/extract.py /path/to/valit_q_comparison.git

Only numbers are copied, as the text the paper's CSV files hold (never re-rounded); every line
names its source file and the commit that last changed it (see README.md here).
"""
import csv
import io
import re
import subprocess
import sys

GIT = sys.argv[1] if len(sys.argv) > 1 else "."
PAPER_PROBLEMS = [0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]
STEVE_DET = "sims/steve_sims_3000steps/deterministic/example_{}_results_100_samples.csv"
I5_DET = "sims/sims_det_section_3000_steps/examples_i5-12400F_16GBRam_RTX3060/example_{}_results_100_samples.csv"
STEVE_STOCH = "sims/steve_sims_3000steps/stochastic/example_{}_stochastic_results_100_samples.csv"
STEVE_MACHINE = "the paper's timing machine (AMD Ryzen 7 3700X as reported for the paper's timings)"
I5_MACHINE = "Intel i5-12400F (named by the directory)"


def git(*args):
    return subprocess.run(["git", "--git-dir", GIT, *args], check=True, capture_output=True,
                          text=True).stdout


SOURCES = []


def read(path, machine):
    commit = git("log", "-1", "--format=%H", "HEAD", "--", path).strip()
    SOURCES.append((path, commit, machine, 100))
    text = git("show", f"{commit}:{path}")
    return commit, list(csv.DictReader(io.StringIO(text)))


def det_row(name):
    """(algorithm, epsilon) in truecost's names."""
    low = name.lower()
    if low == "model-free dijkstra":
        return "model-free-dijkstra", ""
    if low == "model-free value iteration":
        return "model-free-async-vi", ""
    if low == "model-free synchronous value iteration":
        return "model-free-vi", ""
    eps = re.search(r"epsilon = ([0-9.]+|decaying)", low).group(1)
    if "with pi" in low:
        return "q-learning-pi", eps
    if eps == "decaying":
        return "q-learning-epsilon-decay", "1"
    return "q-learning", eps


# (our metric, mean column, std column) for every row; learning-only and planner-only below.
COMMON = [
    ("mean_time_s", "Avg Time", "STD Time"),
    ("mean_iterations", "Avg Iterations", "STD iterations"),
    ("mean_actions", "Avg action count", "STD action count"),
    ("convergence_rate", "Convergence rate", None),
    ("shortest_path", "Shortest Path", None),
    ("longest_path", "Longest Path", None),
]
LEARNING = [
    ("mean_time_goal_discovered_s", "Avg Time Goal Discovered", "STD Time Goal Discovered"),
    ("mean_actions_goal_discovered", "Avg Actions Goal Discovered", "STD Actions Goal Discovered"),
    ("mean_time_initial_optimal_s", "Avg Time Optimal Initial Cost2Go", "STD Time Optimal Initial Cost2Go"),
    ("mean_actions_initial_optimal", "Avg Actions Optimal Initial Cost2Go", "STD Actions Optimal Initial Cost2Go"),
]


def flag(text):
    return {"True": "1", "False": "0"}[text]


def deterministic(out):
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["problem", "algorithm", "epsilon", "metric", "value", "std", "file"])
    for p in PAPER_PROBLEMS:
        for template, machine, only_decay in [(STEVE_DET, STEVE_MACHINE, False),
                                              (I5_DET, I5_MACHINE, True)]:
            path = template.format(p)
            commit, rows = read(path, machine)
            for r in rows:
                alg, eps = det_row(r["Algorithm"])
                if (alg == "q-learning-epsilon-decay") != only_decay:
                    continue
                metrics = list(COMMON)
                if alg.startswith("model-free"):
                    metrics.append(("mean_planner_actions", "Avg convergence action", "STD convergence action"))
                else:
                    metrics += LEARNING
                    # The paper writes 0 when no sample converged: no mean then.
                    if float(r["Convergence rate"]) > 0:
                        metrics.append(("mean_actions_converged", "Avg convergence action", "STD convergence action"))
                line = lambda m, v, s: w.writerow([p, alg, eps, m, v, s, path])
                for m, mean, std in metrics:
                    if r[mean] != "":
                        line(m, r[mean], r[std] if std else "")
                line("goal_reached_all", flag(r["Goal reached"]), "")
                line("loops_any", flag(r["Loops encountered"]), "")


STOCH_METRICS = [
    ("mean_time_s", "Avg Time", "STD Time"),
    ("mean_actions", "Avg action count", "STD action count"),
    ("convergence_rate", "Convergence rate", None),
]
STOCH_LEARNING = [
    ("initial_within_rate", "Convergence rate Optimal Initial Cost2Go", None),
    ("mean_time_goal_discovered_s", "Avg Time Goal Discovered", "STD Time Goal Discovered"),
    ("mean_actions_goal_discovered", "Avg Actions Goal Discovered", "STD Actions Goal Discovered"),
    ("mean_time_initial_within_s", "Avg Time Optimal Initial Cost2Go", "STD Time Optimal Initial Cost2Go"),
    ("mean_actions_initial_within", "Avg Actions Optimal Initial Cost2Go", "STD Actions Optimal Initial Cost2Go"),
]


def stochastic(out):
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["problem", "gamma", "algorithm", "rho", "epsilon", "metric", "value", "std",
                "file"])
    for p in [1, 10, 11]:
        path = STEVE_STOCH.format(p)
        commit, rows = read(path, STEVE_MACHINE)
        seen = set()
        for r in rows:
            name = r["Algorithm"]
            if name in seen:  # the files repeat some rows verbatim
                continue
            seen.add(name)
            gamma = re.search(r"\((0\.[0-9]+) success\)", name).group(1)
            if "Q-learning" in name:
                alg = "q-learning"
                rho = re.search(r"alpha = ([0-9.]+)", name).group(1)
                eps = re.search(r"epsilon = ([0-9.]+)", name).group(1)
                metrics = STOCH_METRICS + STOCH_LEARNING
                if float(r["Convergence rate"]) > 0:
                    metrics = metrics + [("mean_actions_converged", "Avg convergence action", "STD convergence action")]
            else:
                alg = "stochastic-async-vi" if "Async" in name else "stochastic-vi"
                rho = eps = ""
                metrics = STOCH_METRICS + [("mean_iterations", "Avg Iterations", "STD iterations")]
            for m, mean, std in metrics:
                if r[mean] != "":
                    w.writerow([p, gamma, alg, rho, eps, m, r[mean], r[std] if std else "", path])


if __name__ == "__main__":
    here = __file__.rsplit("/", 1)[0]
    with open(f"{here}/deterministic.csv", "w") as f:
        deterministic(f)
    with open(f"{here}/stochastic.csv", "w") as f:
        stochastic(f)
    with open(f"{here}/sources.csv", "w") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["file", "commit", "machine", "samples"])
        w.writerows(SOURCES)
