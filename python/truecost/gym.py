"""The Gymnasium importer (:mod:`truecost_gym`) under the ``truecost`` package.

``truecost.gym.from_env(env)`` is ``truecost_gym.from_env(env)``; the command line is
``truecost-gym export ENV_ID --out FILE.json`` (or ``python -m truecost_gym``). See
``docs/guide/gymnasium.md``.
"""

from truecost_gym import *  # noqa: F401,F403
from truecost_gym import __all__  # noqa: F401
from truecost_gym.__main__ import main  # noqa: F401
