"""Progress of a long call: ``progress=True`` shows a bar (tqdm when installed, else one line
on stderr rewritten in place), a callable receives ``(done, total)``; the extension calls it
at most every 0.1 s while the cases run, and once more at the end."""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional


def given(progress: Any, args: str) -> Any:
    """None (no progress), the user's callable, or True (a bar is wanted)."""
    if progress is None or progress is False:
        return None
    if callable(progress) or progress is True:
        return progress
    raise TypeError(f"progress: expected True or a callable ({args}), got "
                    f"{type(progress).__name__}")


def _tqdm() -> Any:
    try:
        from tqdm.auto import tqdm  # type: ignore
    except ImportError:
        return None
    return tqdm


def cases(progress: Any, desc: str) -> Optional[Callable[[int, int], Any]]:
    """The callback for ``progress`` (None, False, True or a callable of (done, total))."""
    chosen = given(progress, "done, total")
    if chosen is not True:
        return chosen
    tqdm = _tqdm()
    if tqdm is None:
        def line(done: int, total: int) -> None:
            end = "\n" if done >= total else ""
            sys.stderr.write(f"\r{desc}: {done}/{total} cases{end}")
            sys.stderr.flush()

        return line
    bar = None

    def show(done: int, total: int) -> None:
        nonlocal bar
        if bar is None:
            bar = tqdm(total=total, desc=desc, unit="case")
        bar.n = done
        bar.refresh()
        if done >= total:
            bar.close()

    return show


def finish(cb: Optional[Callable[[int, int], Any]], total: int) -> None:
    """The last call, when the computation has returned: done = total."""
    if cb is not None:
        cb(total, total)


def share(progress: Any, desc: str) -> Optional[Callable[[float, str], Any]]:
    """The callback for ``progress`` of a computation that reports the share of its work
    settled (0..1) and a message: None, False, True (a bar) or a callable (share, message)."""
    chosen = given(progress, "share, message")
    if chosen is not True:
        return chosen
    tqdm = _tqdm()
    if tqdm is None:
        def line(s: float, message: str) -> None:
            end = "\n" if s >= 1.0 else ""
            sys.stderr.write(f"\r{desc}: {100 * s:.1f} % — {message}{end}")
            sys.stderr.flush()

        return line
    bar = None

    def show(s: float, message: str) -> None:
        nonlocal bar
        if bar is None:
            bar = tqdm(total=1000, desc=desc, unit="‰")
        bar.n = int(min(max(s, 0.0), 1.0) * 1000)
        bar.set_postfix_str(message, refresh=True)
        if s >= 1.0:
            bar.close()

    return show
