"""Printing text that came from outside (an environment id, a path, an exception's message).

Every message of the importer is **one printable line**, as truecost's own: control
characters (newlines, tabs, ``ESC`` of terminal escape sequences, ``DEL``, the C1 controls),
Unicode direction and zero-width formatting characters, and the lone surrogates by which
Python carries a path's undecodable bytes become visible escapes (``\\n``, ``\\x1b``,
``\\u{202e}``), and a long message is shortened with "…".
"""

import unicodedata

#: The most characters of a whole message line (without its ``error: `` prefix).
MAX_LINE = 300

_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _hidden(c):
    """Whether ``c`` must not reach a terminal raw."""
    if unicodedata.category(c) in ("Cc", "Cs"):
        return True
    o = ord(c)
    return 0x200B <= o <= 0x200F or 0x202A <= o <= 0x202E or 0x2066 <= o <= 0x2069 or o == 0xFEFF


def _escaped(c):
    if c in _NAMED:
        return _NAMED[c]
    if not _hidden(c):
        return c
    o = ord(c)
    return f"\\x{o:02x}" if o < 0x100 else f"\\u{{{o:x}}}"


def printable(text):
    """``text`` with every control, direction-formatting character and lone surrogate escaped.

    >>> printable("m\\n\\x1b[2J\\u202e")
    'm\\\\n\\\\x1b[2J\\\\u{202e}'
    """
    return "".join(_escaped(c) for c in str(text))


def one_line(text, limit=MAX_LINE):
    """``text`` as one printable line of at most ``limit`` characters (an escape is never cut).

    >>> one_line("bad\\ninput \\x1b[2J")
    'bad\\\\ninput \\\\x1b[2J'
    >>> len(one_line("x" * 10000))
    300
    """
    pieces = [_escaped(c) for c in str(text)]
    if sum(len(p) for p in pieces) <= limit:
        return "".join(pieces)
    out, used = [], 0
    for p in pieces:
        if used + len(p) > limit - 1:
            break
        out.append(p)
        used += len(p)
    return "".join(out) + "…"
