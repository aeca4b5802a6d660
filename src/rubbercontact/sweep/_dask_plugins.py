"""Dask plugins of the local cluster (imported only when Dask runs)."""

from __future__ import annotations

import logging

from distributed import WorkerPlugin

HEARTBEAT_AFTER_CLOSE = "Failed to communicate with scheduler during heartbeat"


class HeartbeatAfterCloseFilter(logging.Filter):
    """Drops the worker's "Failed to communicate with scheduler during heartbeat" record.

    When a local cluster closes while a worker's heartbeat is in flight (likely on a
    loaded machine), the worker logs that error with a traceback although nothing was
    lost (dask/distributed#7192). A scheduler that really dies fails the client's calls,
    which the sweep reports, so only this one message is dropped.
    """

    def filter(self, record: logging.LogRecord) -> bool:
        return not str(record.msg).startswith(HEARTBEAT_AFTER_CLOSE)


class QuietShutdown(WorkerPlugin):
    """Installs :class:`HeartbeatAfterCloseFilter` in each worker of the local cluster."""

    def setup(self, worker) -> None:
        logging.getLogger("distributed.worker").addFilter(HeartbeatAfterCloseFilter())
