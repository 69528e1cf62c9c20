"""The importer's refusals: one line each, with the exit status of the command line."""

#: Exit status of a refusal: 2 for an environment truecost cannot import (its kind: spaces,
#: no transition table) and for usage errors, 1 for a table that is malformed or inconsistent.
UNSUPPORTED, BAD_TABLE = 2, 1


class ImportRefused(Exception):
    """A one-line refusal with its exit status."""

    def __init__(self, message, status=BAD_TABLE):
        super().__init__(message)
        self.status = status
