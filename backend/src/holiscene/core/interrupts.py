"""Stopping a long command cleanly: Ctrl+C and a process manager's SIGTERM both raise
KeyboardInterrupt, so `finally` blocks run (a batch marks the jobs it had out as failed, a
viewer stops its server). Python's own SIGTERM ends the process without running them."""

from __future__ import annotations

import signal
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
