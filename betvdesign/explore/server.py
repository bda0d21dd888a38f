"""The ``betv explore`` server: a Bokeh server on 127.0.0.1 in this process.

The numba solver stays in this process (the orbit stage of every change) and in the
worker processes of :class:`betvdesign.explore.jobs.Workers`; the page gets its
updates over Bokeh's websocket. Only 127.0.0.1 is bound and only pages served from it
may open the websocket. Every request must name a local host in its ``Host`` header
(:data:`LOCAL_HOSTS`: 127.0.0.1, localhost or [::1]); any other gets 403 before any
handler runs: a page of another site whose name was made to resolve to 127.0.0.1 (DNS
rebinding) reads nothing and opens no session. Besides the page, one route serves
finished reports (``/report/TOKEN``, as a download). Ctrl-C or SIGTERM stops the server,
the workers and the browser connection cleanly.
"""

from __future__ import annotations

import contextlib
import logging
import re
import socket
import sys
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from betvdesign.errors import UsageError

__all__ = ["ADDRESS", "DEFAULT_PORT", "LOCAL_HOSTS", "serve"]

#: Where the server listens (never another interface).
ADDRESS = "127.0.0.1"
#: The port tried first; a busy default falls back to a free one.
DEFAULT_PORT = 5006
#: The host names a request may give (its ``Host`` header without the port).
LOCAL_HOSTS = ("127.0.0.1", "localhost", "[::1]")
#: Tornado host pattern of every other host (matched against the Host header's name).
FOREIGN_HOST = r"(?!(?:" + "|".join(re.escape(h) for h in LOCAL_HOSTS) + r")$).*"


def _free_port(port: int, explicit: bool) -> int:
    """``port`` when it can be bound on 127.0.0.1; else (not given explicitly) a free
    one; :class:`UsageError` when an explicit port is taken."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        try:
            s.bind((ADDRESS, port))
            return s.getsockname()[1]
        except OSError as exc:
            if explicit:
                raise UsageError(
                    f"--port {port}: cannot listen on {ADDRESS}:{port} ({exc.strerror})"
                ) from None
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((ADDRESS, 0))
        return s.getsockname()[1]


def _report_handler(reports: dict[str, tuple[str, str]]) -> Any:
    from tornado.web import HTTPError, RequestHandler

    class ReportHandler(RequestHandler):
        def get(self, token: str) -> None:
            if token not in reports:
                raise HTTPError(404)
            name, html = reports[token]
            self.set_header("Content-Type", "text/html; charset=utf-8")
            self.set_header("Content-Disposition", f'attachment; filename="{name}"')
            self.write(html)

    return ReportHandler


def _foreign_host_handler() -> Any:
    from tornado.web import RequestHandler

    class ForeignHost(RequestHandler):
        """403 for every method and path: the Host header names no local host."""

        def initialize(self, port: int) -> None:
            self.port = port

        def prepare(self) -> None:
            self.set_status(403)
            self.set_header("Content-Type", "text/plain; charset=utf-8")
            self.finish(
                f"betv explore: Host {self.request.host!r} refused; open the page at "
                f"http://{ADDRESS}:{self.port}/ (hosts served: {', '.join(LOCAL_HOSTS)})\n"
            )

    return ForeignHost


def _bokeh_server(app: Any, port: int, extra_patterns: list[Any]) -> Any:
    """A Bokeh server of ``app`` on 127.0.0.1:``port`` that refuses foreign hosts (see
    the module docstring): Bokeh's own parts (its Tornado application, HTTP server and
    :class:`bokeh.server.server.BaseServer`) assembled as Bokeh documents it, with the
    host rule ahead of every route."""
    from bokeh.application import Application
    from bokeh.application.handlers.function import FunctionHandler
    from bokeh.server.server import BaseServer
    from bokeh.server.tornado import BokehTornado
    from bokeh.server.util import bind_sockets, create_hosts_allowlist
    from tornado.httpserver import HTTPServer
    from tornado.ioloop import IOLoop

    sockets, port = bind_sockets(ADDRESS, port)
    # pages that may open the websocket: those served by this server under a name of
    # 127.0.0.1 (the only address bound: a page at [::1] cannot reach it)
    origins = [f"{h}:{port}" for h in LOCAL_HOSTS if not h.startswith("[")]
    tornado_app = BokehTornado(
        {"/": Application(FunctionHandler(app))},
        extra_websocket_origins=create_hosts_allowlist(origins, port),
        absolute_url=f"http://{ADDRESS}:{port}",
        extra_patterns=extra_patterns,
    )
    tornado_app.add_handlers(FOREIGN_HOST, [(r".*", _foreign_host_handler(), {"port": port})])
    http = HTTPServer(tornado_app, xheaders=False)
    http.add_sockets(sockets)
    return BaseServer(IOLoop.current(), tornado_app, http)


def serve(
    path: str | Path,
    *,
    port: int | None = None,
    open_browser: bool = True,
    target_speed_m_s: float | None = None,
    select: tuple[str, ...] = (),
    ignore: tuple[str, ...] = (),
    say: Callable[[str], None] = print,
) -> None:
    """Serve the explore page of the device file ``path`` until Ctrl-C or SIGTERM.

    Parameters
    ----------
    path : str or Path
        The device file (read and validated before anything starts: a bad file raises
        its :class:`~betvdesign.errors.SpecError`).
    port : int, optional
        Port on 127.0.0.1 (default :data:`DEFAULT_PORT`, or a free one when busy).
    open_browser : bool
        Open the page in the default browser.
    target_speed_m_s : float, optional
        Required speed [m/s] (the ``target-speed`` rule, as ``betv check``).
    select, ignore : tuple of str
        Rules that count / do not count (as ``betv check --select/--ignore``).
    say : callable
        Where the URL and the stop message go.

    Over 80 lines on purpose: the server's start, its signal handling and its shutdown
    belong together (the workers are started and stopped in one place).
    """
    t0 = time.perf_counter()
    _default_sigint()
    from betvdesign.explore.design import Design

    design = Design.from_file(path)  # bad input stops here, before any server
    options = {
        "target_speed_m_s": target_speed_m_s,
        "select": tuple(select),
        "ignore": tuple(ignore),
    }
    compute = workers = server = first = None
    try:
        # the first verdict is computed in a forked child (its compiled kernels load there)
        # while this process imports Bokeh and what the page's build needs; the page is
        # served with it, "ready" is said when it can be, the worker processes start and
        # the kernels load on the compute thread once the browser has drawn it
        # (ExplorePage), so nothing competes with the first verdict
        chosen = _free_port(DEFAULT_PORT if port is None else port, explicit=port is not None)
        from betvdesign.explore.compute import evaluate

        first = _Forked(
            evaluate, design.spec, "orbit", source_file=str(path), with_traces=True, **options
        )
        from betvdesign.explore import jobs
        from betvdesign.explore.fields import designer_fields
        from betvdesign.explore.page import ExploreApp

        designer_fields(design.original, 0)  # its lazy imports, before the first page
        for name in ("tornado.access", "bokeh", "tornado.application"):
            logging.getLogger(name).setLevel(logging.CRITICAL)
        workers = jobs.Workers()
        compute = ThreadPoolExecutor(1, thread_name_prefix="betv-explore")
        app = ExploreApp(
            design.text, str(path), options, workers, compute=compute, first=first.result()
        )
        server = _bokeh_server(
            app, chosen, [(r"/report/([0-9a-f]+)", _report_handler(app.reports))]
        )
        server.start()
        url = f"http://{ADDRESS}:{chosen}/"
        ready = time.perf_counter() - t0
        say(f"betv explore: {design.original.name} at {url} (ready in {ready:.1f} s; Ctrl-C stops)")
        sys.stdout.flush()
        if open_browser:
            server.io_loop.add_callback(lambda: _open(url))
        server.io_loop.start()
    except KeyboardInterrupt:  # Ctrl-C or SIGTERM, at any moment of the start too
        pass
    finally:
        if first is not None:
            first.close()
        with contextlib.suppress(Exception):
            if server is not None:
                server.stop()
        if workers is not None:
            workers.close()
        if compute is not None:
            compute.shutdown(wait=False, cancel_futures=True)
        say("betv explore: stopped")


class _Forked:
    """``fn(*args, **kwargs)`` computed in a forked child process while this one goes
    on; :meth:`result` waits for it (pickled through a pipe). Computed here instead where
    there is no ``fork`` or this process runs threads (a fork copies only the calling
    thread), and here again when the child fails (its error is then raised here)."""

    def __init__(self, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> None:
        import os
        import threading

        self.call = (fn, args, kwargs)
        self.pid = 0
        self.value: Any = None
        self.done = False
        if not hasattr(os, "fork") or threading.active_count() > 1:
            self.value, self.done = fn(*args, **kwargs), True
            return
        sys.stdout.flush()
        sys.stderr.flush()
        r, w = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: answer, then leave without any of the parent's exits
            try:
                _child(w, fn, args, kwargs)
            finally:
                os._exit(0)
        os.close(w)
        self.pid, self.fd = pid, r

    def result(self) -> Any:
        import os
        import pickle

        if not self.done:
            with os.fdopen(self.fd, "rb") as f:
                data = f.read()
            self.close()
            self.done = True
            try:
                ok, self.value = pickle.loads(data)
            except Exception:
                ok = False
            if not ok:
                fn, args, kwargs = self.call
                self.value = fn(*args, **kwargs)
        return self.value

    def close(self) -> None:
        """Stop and reap the child (nothing when it has answered)."""
        import os
        import signal

        if self.pid:
            pid, self.pid = self.pid, 0
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
            with contextlib.suppress(OSError):
                os.waitpid(pid, 0)


def _child(fd: int, fn: Callable[..., Any], args: Any, kwargs: Any) -> None:
    """In the forked child of :class:`_Forked`: write ``(True, value)`` or ``(False,
    message)`` pickled to ``fd``; Ctrl-C is the parent's to handle (it kills the child)."""
    import os
    import pickle
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        data = pickle.dumps((True, fn(*args, **kwargs)))
    except BaseException as exc:  # the parent computes it again and raises it there
        data = pickle.dumps((False, f"{type(exc).__name__}: {exc}"))
    with contextlib.suppress(OSError), os.fdopen(fd, "wb") as f:
        f.write(data)


def _default_sigint() -> None:
    """Ctrl-C (SIGINT) stops the server even where it was started ignoring SIGINT: a
    command started in the background (``betv explore FILE &``) by a shell without job
    control inherits SIGINT ignored, and Python then keeps it ignored."""
    import signal
    import threading

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.default_int_handler)


def _open(url: str) -> None:
    import webbrowser

    with contextlib.suppress(Exception):
        webbrowser.open(url)
