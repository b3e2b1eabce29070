"""Stop signals held over a step that must be done whole (core.interrupts)."""

from __future__ import annotations

import os
import signal
import threading

import pytest
from holiscene.core.interrupts import stop_signals_deferred, stop_signals_interrupt


def test_a_sigterm_inside_a_deferred_step_is_raised_once_the_step_is_done() -> None:
    steps: list[str] = []
    with pytest.raises(KeyboardInterrupt), stop_signals_interrupt():
        with stop_signals_deferred():
            steps.append("job made")
            os.kill(os.getpid(), signal.SIGTERM)
            steps.append("job sent out")  # reached: the stop waits for the block's end
        steps.append("after the step")  # not reached: the stop is raised as the block ends
    assert steps == ["job made", "job sent out"]


def test_without_a_stop_the_deferred_step_raises_nothing_and_the_handlers_come_back() -> None:
    with stop_signals_interrupt():
        before = signal.getsignal(signal.SIGTERM)
        with stop_signals_deferred():
            pass
        assert signal.getsignal(signal.SIGTERM) is before
    # and with SIGTERM at Python's default, a deferred step leaves it so
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL
    with stop_signals_deferred():
        assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL


def test_outside_the_main_thread_the_step_runs_as_it_is() -> None:
    ran: list[bool] = []

    def step() -> None:
        with stop_signals_deferred():
            ran.append(True)

    worker = threading.Thread(target=step)
    worker.start()
    worker.join()
    assert ran == [True]
