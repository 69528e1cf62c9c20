#!/usr/bin/env python3
"""Dump Gymnasium's own transition tables for truecost's toy-text conformance tests.

For every environment configuration truecost models (`--env SPEC`), writes
tests/data/gymnasium/<name>.json with Gymnasium's `env.unwrapped.P` (every state, every
action, every listed outcome in Gymnasium's order), its initial state distribution and, for
FrozenLake, the map. Probabilities are written as Python's repr of the float (shortest text
that round-trips), so the Rust tests recover the exact f64 Gymnasium holds.

Usage (from the repository root):
    python3 -m venv /tmp/gym && /tmp/gym/bin/pip install gymnasium
    /tmp/gym/bin/python scripts/gymnasium_dump.py
The Rust tests (tests/envs_conformance.rs) read the dumps and need no Python.
"""
import json
import os

import gymnasium as gym

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "tests", "data", "gymnasium")


def read_map(name):
    with open(os.path.join(OUT, name)) as f:
        return [line.strip() for line in f if line.strip()]


# (file name, truecost --env SPEC, Gymnasium id, keyword arguments)
CONFIGS = [
    ("frozenlake_4x4_slippery", "frozenlake", "FrozenLake-v1", {}),
    ("frozenlake_4x4", "frozenlake:slippery=false", "FrozenLake-v1", {"is_slippery": False}),
    ("frozenlake_8x8_slippery", "frozenlake:map=8x8", "FrozenLake-v1", {"map_name": "8x8"}),
    ("frozenlake_8x8", "frozenlake:map=8x8,slippery=false", "FrozenLake-v1",
     {"map_name": "8x8", "is_slippery": False}),
    ("frozenlake_4x4_success_4_5", "frozenlake:success_rate=4/5", "FrozenLake-v1",
     {"success_rate": 4 / 5}),
    ("frozenlake_8x8_success_1_2", "frozenlake:map=8x8,success_rate=1/2", "FrozenLake-v1",
     {"map_name": "8x8", "success_rate": 1 / 2}),
    ("frozenlake_map_3x5", "frozenlake:map=tests/data/gymnasium/map_3x5.txt", "FrozenLake-v1",
     {"desc": read_map("map_3x5.txt")}),
    ("cliffwalking", "cliffwalking", "CliffWalking-v1", {}),
    ("cliffwalking_slippery", "cliffwalking:slippery=true", "CliffWalkingSlippery-v1", {}),
    ("taxi", "taxi", "Taxi-v4", {}),
]


def main():
    for name, spec, env_id, kwargs in CONFIGS:
        env = gym.make(env_id, **kwargs).unwrapped
        n_states, n_actions = env.observation_space.n, env.action_space.n
        table = []
        for s in range(n_states):
            row = []
            for a in range(n_actions):
                outcomes = []
                for p, s2, r, done in env.P[s][a]:
                    assert float(r) == int(r), (name, s, a, r)
                    outcomes.append([repr(float(p)), int(s2), int(r), bool(done)])
                row.append(outcomes)
            table.append(row)
        dump = {
            "gymnasium_version": gym.__version__,
            "env_id": env_id,
            "kwargs": kwargs,
            "spec": spec,
            "states": int(n_states),
            "actions": int(n_actions),
            "initial_state_distrib": [repr(float(x)) for x in env.initial_state_distrib],
            "P": table,
        }
        if hasattr(env, "desc") and env_id.startswith("FrozenLake"):
            dump["desc"] = [b"".join(r).decode() for r in env.desc]
        path = os.path.join(OUT, name + ".json")
        with open(path, "w") as f:
            json.dump(dump, f, separators=(",", ":"))
            f.write("\n")
        print(f"{path}: {n_states} states x {n_actions} actions")


if __name__ == "__main__":
    main()
