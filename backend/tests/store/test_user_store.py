"""Whether accounts exist, asked on every request: a "no" is believed for a moment (it saves
a database round trip per request of a local server), a "yes" for good, and an account made
through the same store counts at once."""

from __future__ import annotations

import time
from datetime import timedelta

import pytest
from holiscene.core.settings import Settings
from holiscene.services.workbench import Workbench
from holiscene.store.users import UserStore

pytestmark = pytest.mark.both_databases

PASSWORD = "tram-lilac-47-orbit"
IDLE = timedelta(hours=1)


def test_no_accounts_is_believed_for_a_moment_then_asked_again(settings: Settings) -> None:
    workbench = Workbench(settings)
    try:
        engine = workbench.engine
        believing = UserStore(engine, IDLE, no_users_recheck_s=3600)
        rechecking = UserStore(engine, IDLE, no_users_recheck_s=0.2)
        assert (believing.any_users(), rechecking.any_users()) == (False, False)
        # `holiscene users add` in another process: a store of its own.
        UserStore(engine, IDLE).create("ada", "admin", PASSWORD)
        assert believing.any_users() is False, "a no is believed until it is asked again"
        time.sleep(0.3)
        assert rechecking.any_users() is True
        assert UserStore(engine, IDLE).any_users() is True
    finally:
        workbench.close()


def test_an_account_made_through_the_store_counts_at_once(settings: Settings) -> None:
    workbench = Workbench(settings)
    try:
        store = UserStore(workbench.engine, IDLE, no_users_recheck_s=3600)
        assert store.any_users() is False
        store.create("ada", "admin", PASSWORD)
        assert store.any_users() is True
    finally:
        workbench.close()
