"""Writing the importer's output files: all of them or none, never through a planted name.

A target is one of

* ``-``: standard output;
* a **regular file**, or a name that does not exist yet in an existing directory: written to a
  temporary file of unpredictable name beside it (``tempfile.mkstemp``: created with
  ``O_EXCL`` and ``O_NOFOLLOW``, so no symlink planted there is followed), then renamed over
  it, so that an error leaves the old file or the new one, never half of one. A symbolic link
  to a regular file replaces the file it names (the link stays);
* a **pipe** (a FIFO, ``/dev/stdout`` when standard output is a pipe) or a **terminal**: opened
  without creating or truncating anything, and written directly.

Everything else is refused before anything is written: a directory, a device that is not a
terminal (a copy of ``/dev/full``, ``/dev/null``, a disk), a socket, a symbolic link to one of
these, a dangling symbolic link, a directory that does not exist (none is created).
:func:`check` classifies every target first; :func:`write_all` then opens every target,
writes every temporary file, and renames them only when all of that succeeded.
"""

import os
import stat
import sys
import tempfile

from .echo import printable

STDOUT, DIRECT, REPLACE = "standard output", "direct", "replace"


class OutputRefused(Exception):
    """A target that cannot be written, in one line (exit status 2)."""

    status = 2


class Target:
    """One output: ``path`` as given, its ``kind`` (:data:`STDOUT`, :data:`DIRECT`,
    :data:`REPLACE`), the file ``real`` that a replacement renames over, and for a direct
    target the identity ``(st_dev, st_ino)`` checked again once it is opened."""

    __slots__ = ("path", "kind", "real", "identity")

    def __init__(self, path, kind, real=None, identity=None):
        self.path, self.kind, self.real, self.identity = path, kind, real, identity


def _refuse(path, why):
    raise OutputRefused(f"cannot write {printable(path)}: {why}")


def _what(mode):
    """A non-regular file's kind, in words."""
    for test, name in ((stat.S_ISCHR, "character device"), (stat.S_ISBLK, "block device"),
                       (stat.S_ISSOCK, "socket"), (stat.S_ISDIR, "directory"),
                       (stat.S_ISLNK, "symbolic link")):
        if test(mode):
            return name
    return "special file"


def _terminal_devices():
    """The device numbers known to be terminals: those of the standard streams that are
    terminals and of ``/dev/tty``."""
    known = set()
    for fd in (0, 1, 2):
        try:
            if os.isatty(fd):
                known.add(os.fstat(fd).st_rdev)
        except OSError:
            pass
    try:
        known.add(os.stat("/dev/tty").st_rdev)
    except OSError:
        pass
    return known


def _is_terminal(st):
    """Whether the character device ``st`` is a terminal, decided without opening it (opening
    some devices acts on them): one of :func:`_terminal_devices`, or on Linux a virtual
    console, serial line (major 4) or pseudo-terminal (majors 136-143)."""
    if st.st_rdev in _terminal_devices():
        return True
    if sys.platform.startswith("linux"):
        major = os.major(st.st_rdev)
        return major == 4 or 136 <= major <= 143
    return False


def _writable_folder(path, shown):
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        _refuse(shown, f"no such directory {printable(folder)} (none is created)")
    if not os.access(folder, os.W_OK | os.X_OK):
        _refuse(shown, f"no permission to create files in {printable(folder)}")


def check(path):
    """The :class:`Target` of ``path``, or :class:`OutputRefused` (module docs). Nothing is
    created or opened."""
    if path == "-":
        return Target(path, STDOUT)
    if path == "":
        _refuse(path, "empty path")
    try:
        st = os.stat(path)
    except FileNotFoundError:
        if os.path.islink(path):
            _refuse(path, f"it is a symbolic link to {printable(os.readlink(path))}, which does "
                    "not exist")
        _writable_folder(path, path)
        return Target(path, REPLACE, real=path)
    except OSError as e:
        _refuse(path, e.strerror or type(e).__name__)
    mode = st.st_mode
    if stat.S_ISREG(mode):
        real = path
        if os.path.islink(path):
            real = os.path.realpath(path)
            try:
                same = os.path.samestat(os.stat(real), st)
            except OSError:
                same = False
            if not same or os.path.islink(real):
                _refuse(path, "it is a symbolic link whose file cannot be resolved to a path")
        _writable_folder(real, path)
        return Target(path, REPLACE, real=real)
    if stat.S_ISFIFO(mode) or (stat.S_ISCHR(mode) and _is_terminal(st)):
        return Target(path, DIRECT, identity=(st.st_dev, st.st_ino))
    link = " (through a symbolic link)" if os.path.islink(path) else ""
    _refuse(path, f"it is a {_what(mode)}{link}, not a regular file, a pipe or a terminal; "
            "the importer neither replaces nor writes into one")


def check_all(paths):
    """The targets of ``paths`` (``(option, path)`` pairs, ``path`` ``None`` for an option not
    given), each checked, and no two the same file (or both standard output)."""
    targets = []
    for option, path in paths:
        if path is None:
            continue
        try:
            t = check(path)
        except OutputRefused as e:
            raise OutputRefused(f"{option}: {e}") from None
        for other_option, other in targets:
            if _same(t, other):
                raise OutputRefused(f"{other_option} and {option} both name "
                                    f"{printable(path)}: give each output its own file")
        targets.append((option, t))
    return [t for _, t in targets]


def _same(a, b):
    if a.kind == STDOUT or b.kind == STDOUT:
        return a.kind == b.kind
    if a.kind == REPLACE and b.kind == REPLACE:
        if os.path.abspath(a.real) == os.path.abspath(b.real):
            return True
    try:
        return os.path.samefile(a.real or a.path, b.real or b.path)
    except OSError:
        return False


def _mode_for(real):
    """The permissions of the file written at ``real``: those of the file it replaces, else
    ``0o666`` less the umask (as ``open`` gives a new file)."""
    try:
        return stat.S_IMODE(os.stat(real).st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def _open(t):
    """An open file descriptor for ``t`` and, for a replacement, its temporary path."""
    if t.kind == REPLACE:
        folder = os.path.dirname(os.path.abspath(t.real))
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=".truecost_gym.", suffix=".tmp")
        try:
            os.fchmod(fd, _mode_for(t.real))
        except OSError:
            os.close(fd)
            os.unlink(tmp)
            raise
        return fd, tmp
    fd = os.open(t.path, os.O_WRONLY | getattr(os, "O_NOCTTY", 0))
    st = os.fstat(fd)
    if (st.st_dev, st.st_ino) != t.identity or not (stat.S_ISFIFO(st.st_mode) or os.isatty(fd)):
        os.close(fd)
        _refuse(t.path, "it changed since it was checked (no longer the same pipe or terminal)")
    return fd, None


def _write_fd(fd, data):
    view = memoryview(data)
    while view:
        n = os.write(fd, view)
        view = view[n:]


def _write_stdout(data):
    """``data`` on standard output, all of it (a buffered write may stop short when the
    reader leaves)."""
    try:
        sys.stdout.flush()
        try:
            fd = sys.stdout.fileno()
        except (OSError, ValueError, AttributeError):  # not a file (an in-memory stream)
            fd = None
        if fd is None:
            sys.stdout.buffer.write(data)
            sys.stdout.flush()
        else:
            _write_fd(fd, data)
    except BrokenPipeError:
        # The reader took what it wanted (``--out - | head``); later output goes nowhere.
        silence_stdout()


def silence_stdout():
    """Sends the rest of standard output (and Python's flush at exit) to the null device,
    after its reader closed the pipe."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)


def write_all(outputs):
    """Writes every ``(target, text)`` of ``outputs`` (targets from :func:`check_all`), or
    none: every target is opened and every temporary file written before the first rename, and
    on any error the temporary files are removed and :class:`OutputRefused` names the target.
    A pipe closed by its reader is not an error."""
    opened = []  # (target, fd, tmp, data)
    current = None
    try:
        for t, text in outputs:
            current = t
            data = text.encode("utf-8")
            if t.kind == STDOUT:
                opened.append((t, None, None, data))
                continue
            fd, tmp = _open(t)
            opened.append((t, fd, tmp, data))
        for t, fd, tmp, data in opened:
            if t.kind == REPLACE:
                current = t
                _write_fd(fd, data)
        for t, fd, tmp, data in opened:
            current = t
            if t.kind == DIRECT:
                try:
                    _write_fd(fd, data)
                except BrokenPipeError:
                    pass
            elif t.kind == STDOUT:
                _write_stdout(data)
        for t, fd, tmp, data in opened:
            if fd is not None:
                os.close(fd)
        opened = [(t, None, tmp, data) for t, _, tmp, data in opened]
        for i, (t, _, tmp, _) in enumerate(opened):
            if t.kind != REPLACE:
                continue
            current = t
            _replace(tmp, t)
            opened[i] = (t, None, None, None)
    except OutputRefused:
        _clean(opened)
        raise
    except OSError as e:
        _clean(opened)
        _refuse(current.path, e.strerror or str(e))


def _replace(tmp, t):
    """Renames ``tmp`` over ``t.real``, unless ``t.real`` became something else than a
    regular file meanwhile."""
    try:
        st = os.lstat(t.real)
    except FileNotFoundError:
        st = None
    if st is not None and not stat.S_ISREG(st.st_mode):
        _refuse(t.path, f"it became a {_what(st.st_mode)} while it was written")
    os.replace(tmp, t.real)


def _clean(opened):
    for _, fd, tmp, _ in opened:
        if fd is not None:
            try:
                os.close(fd)
            except OSError:
                pass
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass


def all_beside_stdout(targets):
    """Whether every target is a file replaced whole and none of them is standard output's
    file (``/dev/stdout`` redirected to a file): then standard output is free for messages."""
    try:
        out = os.fstat(sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        out = None
    for t in targets:
        if t.kind != REPLACE:
            return False
        try:
            if out is not None and os.path.samestat(os.stat(t.real), out):
                return False
        except OSError:
            pass
    return True
