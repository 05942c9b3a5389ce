"""What run_ensemble's `progress` argument becomes: the library draws its bar on C stderr,
which a Jupyter cell does not show, so progress goes through Python instead: a callable
called with (done, total) realisations over the whole job, or a tqdm bar (tqdm.auto: the
notebook widget in Jupyter, text in a terminal) when tqdm is installed."""


class Progress:
    """on_progress: the callable handed to the extension (or None); library_bar: draw the
    library's own stderr bar instead (progress=True without tqdm); close(): end the tqdm bar."""

    def __init__(self, progress):
        self.library_bar = False
        self.on_progress = None
        self._bar = None
        if progress is None or progress is False:
            return
        if progress is True:
            try:
                from tqdm.auto import tqdm
            except ImportError:
                self.library_bar = True  # as before tqdm: the library's bar, on stderr
                return
            self._tqdm = tqdm
            self.on_progress = self._update_bar
            return
        if callable(progress):
            self.on_progress = progress
            return
        raise TypeError(f"progress = {progress!r}: expected True (a tqdm bar, or the library's on stderr), "
                        "False, or a callable(done, total)")

    def _update_bar(self, done, total):
        if self._bar is None:
            self._bar = self._tqdm(total=total, unit="realisation", desc="stengmc ensemble")
        self._bar.update(done - self._bar.n)

    def close(self):
        if self._bar is not None:
            self._bar.close()
