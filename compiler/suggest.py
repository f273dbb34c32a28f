"""Suggestions for a word that is not known ("did you mean ..."): difflib's close matches.

difflib is imported on the first suggestion, not by every module that may make one: a check of a
file without mistakes never loads it (start-up, issue 26).
"""

from __future__ import annotations

from typing import Iterable


def close_matches(word: str, known: Iterable[str], n: int = 3, cutoff: float = 0.6) -> list[str]:
    """`difflib.get_close_matches(word, known, n, cutoff)`."""
    import difflib

    return difflib.get_close_matches(word, known, n=n, cutoff=cutoff)
