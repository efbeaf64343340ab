"""The one exception type for bad user input (reported as one line, exit status 2)."""


class PostError(Exception):
    """An input problem the user can fix: names the option or file and what was expected."""
