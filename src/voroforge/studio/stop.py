"""Stopping ``voroforge studio``: at most ``config.STUDIO_SHUTDOWN_S`` after a stop signal.

An edit's compute runs in a worker thread that nothing can interrupt, and the event loop's
executor is joined on the way out: SIGTERM waited for a minute-long compute (checker21 F4b).
The studio writes its files atomically, so leaving mid-compute loses nothing saved.
"""

from __future__ import annotations

import os
import sys
import threading

from .. import config

__all__ = ["stoppable_server"]


def _leave() -> None:
    print(
        f"voroforge studio: work still running {config.STUDIO_SHUTDOWN_S:g} s after the stop "
        "signal: stopped without it",
        file=sys.stderr,
        flush=True,
    )
    os._exit(0)


def stoppable_server(cfg):
    """A ``uvicorn.Server`` for ``cfg`` that ends the process in time after a stop signal.

    ``STUDIO_SHUTDOWN_S`` after its first SIGTERM/SIGINT, if the graceful shutdown has not
    ended it by then.
    """
    import uvicorn

    class Server(uvicorn.Server):
        def handle_exit(self, sig, frame) -> None:
            super().handle_exit(sig, frame)
            if getattr(self, "_timer", None) is None:
                self._timer = threading.Timer(config.STUDIO_SHUTDOWN_S, _leave)
                self._timer.daemon = True
                self._timer.start()

    return Server(cfg)
