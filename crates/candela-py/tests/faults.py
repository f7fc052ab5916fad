"""Work-unit functions that fail once, for the retry tests.

Pickled by value (cloudpickle) so worker processes need not import this file.
The first call that matches `cell` and `sample_range` creates `marker` (an
exclusive create, so exactly one call across all processes wins) and fails;
every other call renders normally.
"""

import os
import signal

import candela.distributed as dist


class FailOnce:
    def __init__(self, marker, cell, sample_range, how):
        self.marker, self.cell, self.sample_range, self.how = str(marker), tuple(cell), tuple(sample_range), how

    def _first(self, cell, sample_range):
        if (tuple(cell), tuple(sample_range)) != (self.cell, self.sample_range):
            return False
        try:
            os.close(os.open(self.marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
            return True
        except FileExistsError:
            return False

    def __call__(self, path, strict, settings, cell, sample_range):
        first = self._first(cell, sample_range)
        if first and self.how == "raise":
            raise RuntimeError("injected failure")
        film = dist.render_unit(path, strict, settings, cell, sample_range)
        if first and self.how == "kill":
            # The unit's work is done but its result never leaves the worker.
            os.kill(os.getpid(), signal.SIGKILL)
        return film
