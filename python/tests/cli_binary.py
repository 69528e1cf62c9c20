"""The ``truecost`` binary the Python tests run: ``$TRUECOST_BIN`` (or ``$TRUECOST``) if set,
else the newer of target/release/truecost and target/debug/truecost (the one built from the
current source; a stale release binary may predate it), else ``truecost`` on the PATH."""

import os
import shutil

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def truecost_binary():
    for variable in ("TRUECOST_BIN", "TRUECOST"):
        if os.environ.get(variable):
            return os.environ[variable]
    built = [os.path.join(REPO, "target", b, "truecost") for b in ("release", "debug")]
    built = [p for p in built if os.access(p, os.X_OK)]
    if built:
        return max(built, key=os.path.getmtime)
    return shutil.which("truecost")
