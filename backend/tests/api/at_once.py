"""Requests by several accounts at the same moment, each in its own real thread, released
together by a barrier (for the tests of what two people doing the same thing at once get)."""

from __future__ import annotations

import threading
from collections.abc import Callable

from httpx import Response

from .conftest import Accounts

# A request by `who` on a scene: request(accounts, who, scene_id).
Request = Callable[[Accounts, str, str], Response]


def at_once(accounts: Accounts, scene_id: str, *requests: tuple[Request, str]) -> list[Response]:
    """The answers to each (request, who), in the order given."""
    barrier = threading.Barrier(len(requests))
    answers: list[Response | None] = [None] * len(requests)

    def run(index: int) -> None:
        request, who = requests[index]
        barrier.wait()
        answers[index] = request(accounts, who, scene_id)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(requests))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=60)
    assert all(a is not None for a in answers), "a request did not come back"
    return [a for a in answers if a is not None]
