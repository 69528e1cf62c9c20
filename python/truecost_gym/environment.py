"""Reading a Gymnasium environment object: its spaces, ``P`` and initial distribution."""

from .importer import UNSUPPORTED, ImportRefused, _space_size, import_table


def from_env(env, env_name=None, *, initial=None, **options):
    """``import_table`` on a Gymnasium environment (wrapped or not).

    The observation and action spaces must be ``Discrete`` (starting at 0) and the unwrapped
    environment must carry the toy-text table ``P``; the initial distribution is
    ``initial_state_distrib`` or ``isd`` unless ``initial`` (a state) is given. Refusals are
    :class:`ImportRefused` with exit status 2 for these requirements; any exception the
    environment's own code raises (a ``P`` property, a space's ``n``) is one refusal naming the
    exception's type.
    """
    try:
        return _from_env(env, env_name, initial, options)
    except (ImportRefused, KeyboardInterrupt):
        raise
    except BaseException as e:  # the environment's own code, SystemExit included: one line
        name = env_name if env_name is not None else type(env).__name__
        raise ImportRefused(f"{name}: the environment raised {type(e).__name__}: {e}") from None


def _from_env(env, env_name, initial, options):
    raw = getattr(env, "unwrapped", env)
    if env_name is None:
        spec = getattr(env, "spec", None)
        env_name = spec.id if spec is not None else type(raw).__name__
    n_states = _space_size(raw.observation_space, "observation", env_name)
    n_actions = _space_size(raw.action_space, "action", env_name)
    P = getattr(raw, "P", None)
    if P is None:
        raise ImportRefused(
            f"{env_name}: no transition table env.unwrapped.P (the toy-text convention "
            "P[s][a] = [(probability, next_state, reward, terminated), ...])",
            UNSUPPORTED,
        )
    if initial is None:
        for attr in ("initial_state_distrib", "isd"):
            initial = getattr(raw, attr, None)
            if initial is not None:
                initial = list(initial)
                break
    return import_table(P, n_states, n_actions, initial, env_name=env_name, **options)
