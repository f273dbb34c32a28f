"""The host protocol of each dialect, by name (the link's one table of dialects)."""

from __future__ import annotations

import importlib

MODULES = {"mcode": "mcc.link.mcode", "x150": "mcc.link.x150", "arcus": "mcc.link.arcus"}


def get(dialect: str):
    return importlib.import_module(MODULES[dialect]).Protocol


def module(dialect: str):
    return importlib.import_module(MODULES[dialect])
