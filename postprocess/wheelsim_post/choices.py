"""Comma-separated option values: 'a, b,c' lists and lists of allowed names."""

from .errors import PostError


def split_list(text):
    """'a, b,c' -> ['a', 'b', 'c'] (empty items dropped)."""
    return [item.strip() for item in text.split(",") if item.strip()]


def parse_choices(text, allowed, option):
    """The names of ``text`` (comma-separated), each one of ``allowed``; PostError naming
    ``option`` and the allowed names if one is unknown or the list is empty."""
    names = split_list(text)
    if not names or any(n not in allowed for n in names):
        raise PostError(
            f"{option}: '{text}' is not a comma-separated list of {', '.join(allowed)}"
        )
    return names
