"""How one dialect says a shared rule: the `Voice` a shared rule reads, and `speak`, which registers
a shared rule as the rule of a dialect's module.

A `Voice` holds, for the rule it was made for:

- `codes`: the shared rule's name -> the dialect's own code (M301, A301, ...; codes are stable, so
  a dialect keeps its numbers), taken from the module `speak` is called in;
- `messages`: the message of the rule (and of its variants, `"rule.variant"`) in the dialect's
  own words, a `str.format` template over the fields the rule's docstring documents;
- `words`: the dialect's spelling of a neutral name used in messages (`max_speed` -> `HSPD`);
- `options`: the per-rule choices that differ by dialect (where a finding points);
- `hooks`: the few facts only the dialect knows, as functions (which of its `Native` commands
  stop an axis, the fix that deletes an Arcus `SUB ... ENDSUB`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import ModuleType
from typing import Any, Callable, Mapping

from mcc.compiler.lint import rules
from mcc.compiler.lint.rules import Context


@dataclass(frozen=True)
class Voice:
    """How one dialect says a shared rule: its code, messages and words (data), and hooks."""

    dialect: str
    codes: Mapping[str, str]
    messages: Mapping[str, str]
    words: Mapping[str, str] = field(default_factory=dict)
    options: Mapping[str, Any] = field(default_factory=dict)
    hooks: Mapping[str, Callable] = field(default_factory=dict)

    def say(self, key: str, **fields: Any) -> str:
        return self.messages[key].format(**fields)

    def word(self, name: str) -> str:
        return self.words.get(name, name)

    def hook(self, name: str, default: Callable) -> Callable:
        return self.hooks.get(name, default)


def check_of(shared: ModuleType) -> Callable[[Context, Voice], None]:
    """The function of a shared rule's module (named after the rule: `busy-wait` -> busy_wait)."""
    return getattr(shared, shared.NAME.replace("-", "_"))


def speak(module: str, shared: ModuleType, messages: Mapping[str, str], words: Mapping[str, str] | None = None,
          options: Mapping[str, Any] | None = None, hooks: Mapping[str, Callable] | None = None) -> Voice:
    """Register the shared rule `shared` (a module of this package) as the rule of the dialect's
    module `module` (its `__name__`): the code is the module's, the dialect the one its page names."""
    code = rules.code_of(module)
    info = rules.registry().get(code)
    if info is None or len(info.dialects) != 1:
        raise ValueError(f"{module}: a shared rule is spoken by one dialect; its page must name it")
    name = shared.NAME
    voice = Voice(info.dialects[0], {name: code}, dict(messages), dict(words or {}),
                  {name: dict(options)} if options else {}, dict(hooks or {}))
    check = check_of(shared)

    def run(ctx: Context) -> None:
        check(ctx, voice)

    run.__name__ = check.__name__
    run.__doc__ = check.__doc__
    rules.add(code, run, voice)
    return voice
