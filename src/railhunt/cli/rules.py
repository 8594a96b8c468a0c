"""Declared option rules: which options of a command exclude, need or bound each other.

A command lists its rules next to its options, e.g. ::

    @command("sweep", rules=(
        Excludes("--resume", "--overwrite", "{a} and {b} exclude each other"),
        Requires("--samples", "--design=random|lhs",
                 "--samples is for the random and lhs designs, not {design!r}"),
    ))

and :class:`Command` checks them in their order once click has parsed and validated each
option, before the command runs: the first broken rule ends the program with one
``railhunt: error:`` line (exit status 2).

An option is named by its flag: ``"--amplitude"`` holds when the option is given on the
command line (a default does not count); ``"--method=stochastic"`` or
``"--design=random|lhs"`` when its value is one of those; ``"--design!=lines"`` when it is
not. A message is a :meth:`str.format` template: ``{a}`` is the first option of the rule's
first group that holds, ``{b}`` that of its second; every value of the command is there
by its name, e.g. ``{tol_kmh:g}``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import click

from railhunt.cli.errors import CliError

__all__ = ["Command", "Excludes", "Ordered", "Requires", "command"]


@dataclass(frozen=True)
class _Condition:
    """``--flag`` (given), ``--flag=a|b`` (value in) or ``--flag!=a|b`` (value not in)."""

    flag: str
    values: tuple[str, ...] | None = None
    negated: bool = False

    @classmethod
    def parse(cls, text: str) -> _Condition:
        flag, sep, values = text.partition("!=")
        if sep:
            return cls(flag, tuple(values.split("|")), negated=True)
        flag, sep, values = text.partition("=")
        return cls(flag, tuple(values.split("|")) if sep else None)

    def holds(self, ctx: click.Context, name: str) -> bool:
        if self.values is None:
            return ctx.get_parameter_source(name) is click.core.ParameterSource.COMMANDLINE
        return (str(ctx.params[name]) in self.values) != self.negated


def _group(spec: str | Sequence[str]) -> tuple[_Condition, ...]:
    return tuple(_Condition.parse(s) for s in ((spec,) if isinstance(spec, str) else spec))


class _Rule:
    """Base of the rules: its conditions, and the message when it is broken."""

    message: str

    def conditions(self) -> tuple[_Condition, ...]:
        raise NotImplementedError

    def broken(self, ctx: click.Context, names: Mapping[str, str]) -> str | None:
        """The error message when the command line breaks the rule, else None."""
        raise NotImplementedError

    @staticmethod
    def _first(group: tuple[_Condition, ...], ctx: click.Context,
               names: Mapping[str, str]) -> str | None:  # fmt: skip
        return next((c.flag for c in group if c.holds(ctx, names[c.flag])), None)

    def _text(self, ctx: click.Context, **where: str | None) -> str:
        return self.message.format_map({**ctx.params, **where})


@dataclass(frozen=True)
class Excludes(_Rule):
    """No option of ``options`` together with one of ``others``.

    Parameters
    ----------
    options, others : str or sequence of str
        Conditions (see the module); ``{a}`` and ``{b}`` name the first that holds of each.
    message : str
        The error, e.g. ``"{a} cannot be combined with {b}: choose one track"``.
    """

    options: str | Sequence[str]
    others: str | Sequence[str]
    message: str

    def conditions(self) -> tuple[_Condition, ...]:
        return _group(self.options) + _group(self.others)

    def broken(self, ctx: click.Context, names: Mapping[str, str]) -> str | None:
        a = self._first(_group(self.options), ctx, names)
        b = self._first(_group(self.others), ctx, names) if a else None
        return self._text(ctx, a=a, b=b) if b else None


@dataclass(frozen=True)
class Requires(_Rule):
    """An option of ``options`` only applies when ``condition`` holds.

    Parameters
    ----------
    options : str or sequence of str
        Conditions (see the module); ``{a}`` names the first that holds.
    condition : str
        What they need, e.g. ``"--spectrum"`` or ``"--method=stochastic"``; ``{b}`` is its flag.
    message : str
        The error, e.g. ``"{a} only applies with {b}"``.
    """

    options: str | Sequence[str]
    condition: str
    message: str

    def conditions(self) -> tuple[_Condition, ...]:
        return _group(self.options) + _group(self.condition)

    def broken(self, ctx: click.Context, names: Mapping[str, str]) -> str | None:
        a = self._first(_group(self.options), ctx, names)
        (need,) = _group(self.condition)
        if a is None or need.holds(ctx, names[need.flag]):
            return None
        return self._text(ctx, a=a, b=need.flag)


@dataclass(frozen=True)
class Ordered(_Rule):
    """The value of ``low`` is at most (``strict``: below) that of ``high``, when both are set.

    Parameters
    ----------
    low, high : str
        Flags of two number options, e.g. ``"--tol"`` and ``"--step"``.
    message : str
        The error, e.g. ``"--tol {tol_kmh:g} km/h is invalid: must be <= --step {step_kmh:g}
        km/h"``.
    strict : bool
        True: ``low == high`` breaks the rule too.
    """

    low: str
    high: str
    message: str
    strict: bool = False

    def conditions(self) -> tuple[_Condition, ...]:
        return (_Condition(self.low), _Condition(self.high))

    def broken(self, ctx: click.Context, names: Mapping[str, str]) -> str | None:
        low, high = ctx.params[names[self.low]], ctx.params[names[self.high]]
        if low is None or high is None or (low < high if self.strict else low <= high):
            return None
        return self._text(ctx, a=self.low, b=self.high)


Rule = Excludes | Requires | Ordered


class Command(click.Command):
    """A click command that checks its declared :mod:`rules <railhunt.cli.rules>` before it runs.

    Parameters
    ----------
    rules : sequence of Excludes, Requires or Ordered
        Checked in this order after click has parsed and validated every option.
    """

    def __init__(self, *args: Any, rules: Sequence[Rule] = (), **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.params.append(click.Option(
            ["--yes"], is_flag=True, expose_value=False,
            callback=lambda ctx, param, value: ctx.meta.__setitem__("railhunt.yes", value),
            help="Run even when the work is estimated at more than an hour (without it "
            "such a run is refused before it starts)."))  # fmt: skip
        self.rules = tuple(rules)
        self._names = {flag: p.name for p in self.params for flag in p.opts if p.name}
        for rule in self.rules:
            for condition in rule.conditions():
                if condition.flag not in self._names:
                    raise ValueError(f"a rule of command {self.name!r} names "
                                     f"{condition.flag!r}, which is not one of its options")

    def invoke(self, ctx: click.Context) -> Any:
        for rule in self.rules:
            message = rule.broken(ctx, self._names)
            if message is not None:
                raise CliError(message)
        return super().invoke(ctx)


def command(name: str, *, rules: Sequence[Rule] = (),
            **attrs: Any) -> Callable[[Callable[..., Any]], Command]:  # fmt: skip
    """Decorator: a ``railhunt NAME`` command (a :class:`Command`) with these ``rules``.

    ``attrs`` are those of :func:`click.command` (``short_help``, ``help``, ...).
    """
    return click.command(name, cls=Command, rules=rules, **attrs)
