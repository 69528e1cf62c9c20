"""Which states end the episode, and which of those are goals.

The table says where episodes end (``terminated=True``) and what they earn there; it does not
say which endings are successes. The rule (the importer's module docs): the **terminal
states** are those entered with ``terminated=True`` from a state where the episode runs; the
**goals** are the states entered with the **greatest terminal reward of the table** — taken
over the terminated transitions of the running states and of the states no episode reaches
(a terminal state's own terminated self-loop, how toy-text tables mark it, does not count).
When that reward is entered only from states no episode reaches (a FrozenLake map whose goal
is walled off by holes), those goals are kept, unreachable, and every reachable terminal state
is a trap: every policy's success probability is 0, as in Gymnasium, where no episode earns
that reward; the importer says so.

A state entered with the greatest terminal reward is a goal even where it is also entered
with a smaller one (a goal reached from a muddy cell pays the mud's toll on the way in).

Where the table cannot tell success from failure the importer refuses and asks for
``--goals``: a state entered with the greatest terminal reward from a state no episode reaches
but without termination by the episodes, and two or more terminal states that all end with one
reward no greater than the greatest reward of a step (FrozenLake's holes on a map without a
goal: truecost's ``--env`` refuses such a map too).
"""

from .refusal import ImportRefused


def _at(where):
    s, a, i = where
    return f"P[{s}][{a}][{i}]"


def terminal_states(table, start, named, env_name):
    """The states where episodes run and the states they end in.

    ``table[s][a]``: outcomes ``(probability, next_state, reward, terminated, where)``;
    ``start``: ``(state, probability)`` pairs; ``named``: the goals given (they end the
    episode). Returns ``(running, ended)``: ``running`` maps each state an episode reaches
    without ending to where it is first entered, ``ended`` each state entered with
    ``terminated=True`` from a running state to its ``[(reward, where)]``. A state in both is
    refused."""
    running = {}
    ended = {}
    frontier = []
    for x, _ in start:
        if x not in named and x not in running:
            running[x] = f"initial_state_distrib[{x}]"
            frontier.append(x)
    while frontier:
        s = frontier.pop()
        for outcomes in table[s]:
            for _, nxt, reward, done, where in outcomes:
                if done:
                    ended.setdefault(nxt, []).append((reward, where))
                elif nxt not in named and nxt not in running:
                    running[nxt] = _at(where)
                    frontier.append(nxt)
    for x in sorted(ended):
        if x in running:
            raise ImportRefused(
                f"{env_name}: state {x} is entered with terminated=True "
                f"({_at(ended[x][0][1])}) and without ({running[x]}); "
                "truecost's terminal states end every episode that enters them"
            )
    return running, ended


def _unreached_endings(table, running, ended, named):
    """``{state: [(reward, where)]}``: the terminated transitions out of the states no episode
    reaches that are not terminal themselves, self-loops left out."""
    out = {}
    for s, row in enumerate(table):
        if s in running or s in ended or s in named:
            continue
        for outcomes in row:
            for _, nxt, reward, done, where in outcomes:
                if done and nxt != s:
                    out.setdefault(nxt, []).append((reward, where))
    return out


def _step_reward(table, running):
    """The greatest reward of a transition that does not end the episode from a running state,
    with where it is (``None`` when there is none)."""
    best = None
    for s in running:
        for outcomes in table[s]:
            for _, _, reward, done, where in outcomes:
                if not done and (best is None or reward > best[0]):
                    best = (reward, where)
    return best


def _states_text(states, limit=8):
    states = sorted(states)
    if len(states) <= limit:
        return "[" + ", ".join(map(str, states)) + "]"
    return "[" + ", ".join(map(str, states[:limit])) + f", ... {len(states)} in all]"


def choose_goals(table, running, ended, named, env_name):
    """The goal states by the rule of the module docs: ``(goals, rule, warnings)``, ``rule``
    saying why (for the report), ``warnings`` the lines the importer prints; or
    :class:`ImportRefused` where the table cannot tell which endings are goals."""
    unreached = _unreached_endings(table, running, ended, named)
    endings = {}
    for source in (ended, unreached):
        for x, lst in source.items():
            endings.setdefault(x, []).extend(lst)
    if not endings:
        raise ImportRefused(
            f"{env_name}: no episode ends (no terminated transition is reachable), so there "
            "is no goal: name the goal states with --goals"
        )
    best = max(r for lst in endings.values() for r, _ in lst)
    goals = {x for x, lst in endings.items() if any(r == best for r, _ in lst)}
    for x in sorted(goals):
        if x in running:
            where = next(w for r, w in endings[x] if r == best)
            raise ImportRefused(
                f"{env_name}: state {x} is entered with terminated=True and the greatest "
                f"terminal reward {best} ({_at(where)}, from a state no episode reaches) and "
                f"without termination ({running[x]}): whether it is a goal is ambiguous; name "
                "the goal states with --goals"
            )
    rewards = {r for lst in endings.values() for r, _ in lst}
    step = _step_reward(table, running)
    if len(rewards) == 1 and len(goals) >= 2 and step is not None and best <= step[0]:
        raise ImportRefused(
            f"{env_name}: every ending ({_states_text(goals)}) has the same reward {best}, no "
            f"more than a step's ({step[0]} at {_at(step[1])}): which endings are goals and "
            "which are failures cannot be told; name the goal states with --goals"
        )
    rule = f"the states entered with the greatest terminal reward ({best})"
    warnings = []
    if not goals & set(ended):
        first = min(w for x in goals for r, w in endings[x] if r == best)
        traps = sorted(set(ended))
        trap_text = (f"the terminal states episodes reach, {_states_text(traps)}, are traps"
                     if traps else "no episode ends")
        rule += ", entered only from states no episode reaches: no goal is reachable"
        warnings.append(
            f"{env_name}: no goal is reachable: the greatest terminal reward, {best}, is "
            f"entered only from states no episode reaches (first {_at(first)}); goals "
            f"{_states_text(goals)} are kept and {trap_text}, so every policy's success "
            "probability is 0, as no Gymnasium episode earns that reward (--goals names "
            "other goals)"
        )
    return goals, rule, warnings
