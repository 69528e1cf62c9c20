"""truecost_gym: a discrete Gymnasium environment as a truecost stochastic problem file.

    python3 -m truecost_gym export ENV_ID [--kwargs JSON] [--module M] --out env.json
    truecost solve --file env.json --algorithm exact --objective truecost
    truecost discount --file env.json

Standard library and Gymnasium only. See ``docs/guide/gymnasium.md``.
"""

from .importer import FORMAT, ImportRefused, import_table, to_json, truecost_cost
from .rational import recover, simplest_between
from .environment import from_env

__all__ = [
    "FORMAT",
    "ImportRefused",
    "from_env",
    "import_table",
    "recover",
    "simplest_between",
    "to_json",
    "truecost_cost",
]
