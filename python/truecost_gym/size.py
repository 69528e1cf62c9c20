"""The least size of the importer's file, known before a single value of the table is recovered.

Recovering every float as a fraction, summing expected costs and rewards and laying the file
out takes about 1.5 s and 15 MB of memory per MB written: a table whose file exceeds truecost's
32 MiB readers' limit would be refused only after a minute and half a gigabyte. The bound
here is read from the table's shape alone, in one quick pass over ``P`` that looks at each
entry's next state and ``terminated`` flag and whether its probability is 0 (nothing is
recovered, nothing kept but one number per state), so that such a table is refused at once.

It is a **lower bound** of the file's bytes, whatever the values turn out to be:

* a state entered with ``terminated=True`` (or named a goal) may be a goal, whose entry is
  ``[]``, the least a state takes;
* every other state writes all of its actions, an action at least its outcomes, one per
  distinct next state of positive probability, with the next states' digits as written;
* a cost and a reward take at least one character, a probability ``"1"`` when it is an
  action's only outcome and at least three (``"n/d"``) when the action has two or more.

The layout's bytes (indentation, keys, separators) are measured on the importer's own
:func:`~truecost_gym.importer.to_json`, so the bound follows the layout chosen (``compact``).
"""

from array import array

from .refusal import ImportRefused

#: The least head of a file: its format (every other key of the head only adds bytes).
_HEAD = {"format": "truecost-stochastic/1"}


class Layout:
    """The bytes of a layout (``compact`` or not, moves or not, rewards or not), measured on
    ``to_json``: ``goal`` per goal state, ``row`` per other state, ``action[k]`` per action
    with ``k`` outcomes (``k <= 2``; each outcome beyond the second adds ``outcome``)."""

    def __init__(self, to_json, compact, deterministic_moves, with_rewards):
        def size(rows):
            return len(to_json(dict(_HEAD, actions=rows), compact=compact).encode("utf-8"))

        def template(k):
            if deterministic_moves and k == 1:
                action = {"to": 0, "cost": "1"}
            else:
                action = {"cost": "1"}
            if with_rewards:
                action["reward"] = "0"
            if "to" not in action:
                p = "1" if k == 1 else "1/3"
                action["outcomes"] = [{"to": 0, "p": p} for _ in range(k)]
            return action

        self.empty = size([[]])
        self.goal = size([[], []]) - self.empty
        self.action = {}
        rows = set()
        for k in (1, 2, 3):
            t = template(k)
            one = size([[], [t]])
            self.action[k] = size([[], [t, t]]) - one
            rows.add(one - self.empty - self.action[k])
        assert len(rows) == 1, "the row's own bytes depend on its action"
        self.row = rows.pop()
        self.outcome = self.action[3] - self.action[2]

    def action_bytes(self, k):
        """The least bytes of an action with ``k >= 1`` outcomes ("to": 0), its separator
        included."""
        if k <= 2:
            return self.action[k]
        return self.action[2] + (k - 2) * self.outcome


def least_file_bytes(rows, n_states, layout, goals=()):
    """The least bytes of the file (module docs).

    ``rows`` yields, for every state ``s`` in order and every action, ``(s, entries)`` with
    ``entries`` the action's ``(probability, next_state, terminated)`` (next states in range,
    as :func:`~truecost_gym.importer.import_table` checks them); ``goals``: the states named
    goals. Memory: one number and one byte per state.
    """
    full = array("q", bytes(8 * n_states))  # each state's bytes unless it is a goal
    may_end = bytearray(n_states)  # entered with terminated=True, or named: maybe a goal
    for g in goals:
        may_end[g] = 1
    for s, entries in rows:
        nexts = set()
        for p, nxt, done in entries:
            try:
                positive = bool(p != 0)
            except Exception:  # refused with the values; counted as a possible ending
                positive, done = False, True
            if done:
                may_end[nxt] = 1
            if positive:
                nexts.add(nxt)
        if nexts:
            if not full[s]:
                full[s] = layout.row
            full[s] += layout.action_bytes(len(nexts)) + sum(len(str(y)) - 1 for y in nexts)
    total = layout.empty - layout.goal
    for s in range(n_states):
        total += layout.goal if may_end[s] or not full[s] else full[s]
    return total


def refuse_or_warn(least, limit, env_name, warn):
    """Refuses a file of at least ``least`` bytes over ``limit`` (:class:`ImportRefused`,
    naming both), or, when ``warn`` is a function, passes it the same text and returns."""
    if least <= limit:
        return
    message = (f"{env_name}: the file would take at least {least} bytes (a lower bound from "
               f"the table's shape), more than the {limit} bytes truecost's readers accept")
    if warn is None:
        raise ImportRefused(f"{message}: nothing written (--compact, if not given, makes it "
                            "smaller; --allow-large writes it anyway)")
    warn(f"{message}; written as --allow-large asks")
