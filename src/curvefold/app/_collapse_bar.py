"""The progress bar of a collapse path (``--nonlinear``): the states found and the load factor
reached, on stderr when it is a terminal (``curvefold.app._outputs._bar``)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from ._loading import PROGRESS
from ._outputs import _bar

__all__ = ["collapse_progress"]


@contextmanager
def collapse_progress(show: bool) -> Iterator[None]:
    """While the block runs, a collapse path (:func:`curvefold.app._loading.analyse`) draws a bar
    of its states (of at most ``curvefold.mechanics._collapse.STEPS``) if ``show`` and
    stderr is a terminal."""
    from ..mechanics._collapse import STEPS

    bar = _bar(
        show,
        lambda rich: (
            rich.TextColumn("{task.description:<28}"),
            rich.BarColumn(),
            rich.TextColumn("{task.completed} states"),
            rich.TimeElapsedColumn(),
        ),
    )
    if bar is None:
        yield
        return
    bar.start()
    task = bar.add_task("collapse", total=STEPS)

    def step(path) -> None:
        bar.update(
            task,
            description=f"collapse: λ = {float(path.factors[-1]):.4g}",
            completed=len(path.factors) - 1,
        )

    token = PROGRESS.set(step)
    try:
        yield
    finally:
        PROGRESS.reset(token)
        bar.stop()
