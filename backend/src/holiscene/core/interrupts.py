"""Stopping a long command cleanly: Ctrl+C and a process manager's SIGTERM both raise
KeyboardInterrupt, so `finally` blocks run (a batch marks the jobs it had out as failed, a
viewer stops its server). Python's own SIGTERM ends the process without running them."""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType


def _interrupt(_signum: int, _frame: FrameType | None) -> None:
    raise KeyboardInterrupt


@contextmanager
def stop_signals_interrupt() -> Iterator[None]:
    """SIGTERM and SIGINT raise KeyboardInterrupt inside the block; the handlers before it
    come back after. SIGINT is set too: a process started in the background inherits it
    ignored, and then Python never raises KeyboardInterrupt (CI found this)."""
    before = {sig: signal.signal(sig, _interrupt) for sig in (signal.SIGTERM, signal.SIGINT)}
    try:
        yield
    finally:
        for sig, handler in before.items():
            signal.signal(sig, handler)


@contextmanager
def stop_signals_deferred() -> Iterator[None]:
    """Hold SIGTERM and SIGINT inside the block and hand them to their handlers as it ends,
    so a short step is done whole or not begun (a batch's job made and sent out, or a result
    stored): cut between the two, the job would stay queued or running for good. Outside
    the main thread, where handlers cannot be set, the block runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held: list[int] = []
    before = {sig: signal.getsignal(sig) for sig in (signal.SIGTERM, signal.SIGINT)}
    for sig, handler in before.items():
        if callable(handler):  # an ignored or default signal stays as it is
            signal.signal(sig, lambda signum, _frame: held.append(signum))
    try:
        yield
    finally:
        for sig, handler in before.items():
            signal.signal(sig, handler)
        if held:  # one stop is enough; its own handler raises as it would have
            first = before[signal.Signals(held[0])]
            assert callable(first)  # only callable handlers were replaced
            first(held[0], None)
