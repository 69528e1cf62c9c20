"""Storm's value of R{"cost"}min=? [F "goal"] at the initial states of a DRN file, in Storm's
exact mode (exact rationals) or its sound mode (floating point with a sound error bound).

    python storm_check.py MODEL.drn exact|sound

Prints the value at the first initial state (exact: as a fraction; sound: as a float). One
process per check, so that a benchmark times it as a whole, as it times truecost."""

import sys

import stormpy


def main():
    path, mode = sys.argv[1], sys.argv[2]
    if mode == "exact":
        model = stormpy.build_model_from_drn[stormpy.Rational](path)
        env = stormpy.environments.exact()
    elif mode == "sound":
        model = stormpy.build_model_from_drn[float](path)
        env = stormpy.environments.sound()
    else:
        sys.exit("mode must be exact or sound")
    prop = stormpy.parse_properties('R{"cost"}min=? [F "goal"]')[0]
    result = stormpy.model_checking(model, prop, environment=env, only_initial_states=True)
    print(result.get_value(model.initial_states[0]))


if __name__ == "__main__":
    main()
