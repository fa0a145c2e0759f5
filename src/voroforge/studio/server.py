"""The studio's local web server: starlette + uvicorn, one WebSocket, static files.

:func:`create_app` serves the page (``static/``, shipped with the package: no build step, no
CDN) and ``/ws``, where the page sends JSON edits and gets binary geometry
(:mod:`voroforge.studio.wire`) and JSON state back. :func:`serve` runs it with uvicorn.
Besides the session's edits the page sends ``{"op": "view", "px": ...}``, its pixel size in
design units: the drawn cells travel at that resolution (:func:`geometry_message`).

Safety: the server binds 127.0.0.1 unless told otherwise; requests must name an allowed
host (DNS rebinding); a WebSocket whose ``Origin`` is another site is refused; messages
above :data:`voroforge.config.STUDIO_MAX_MESSAGE` bytes, non-JSON, non-finite numbers and
unknown ops get an error reply and the connection stays up; every edit is computed under
one lock (in the event loop's thread when the session's edits take milliseconds, else in a
worker thread: :func:`_inline`), so a closed tab or a flood of bad messages leaves the
session as it was.
"""

from __future__ import annotations

import asyncio
import base64
import contextlib
import itertools
import json
import math
import time
from importlib import resources
from urllib.parse import urlsplit

import shapely

from .. import config
from .heap import freeze_heap, keep_heap
from .messages import geometry_message, state_message, violations_message
from .session import Reply, Session
from .stop import stoppable_server

__all__ = ["create_app", "geometry_message", "serve", "state_message"]

#: Seconds after the last edit before a drag's provisional cells are settled (made exact)
SETTLE_DELAY = 0.25
LOCAL_HOSTS = ("127.0.0.1", "localhost", "::1", "[::1]")


def _reject_constant(name: str):
    raise ValueError(f"{name} is not a number the studio takes")


class _Hub:
    """The session, its lock and the open pages."""

    def __init__(self, session: Session):
        self.session = session
        self.lock = asyncio.Lock()
        self.clients: dict[int, object] = {}
        self.ids = itertools.count(1)
        self.seq = 0
        self.sent_boundary = None
        self.check_task: asyncio.Task | None = None
        self.busy = ""  # what a worker thread computes now ("check", "settle"): for the timings
        self.checked = None  # the result whose violations the session holds (None: none yet)
        self.check_due = 0.0
        self.settle_due = 0.0
        self.sent: dict = {}  # what the pages have (geometry_message patches against it)
        self.state_text = ""  # the last state message sent (sent again only when it changes)
        self.state_key = None  # what that message was built from
        self.edits = 0  # messages received: a running check stops for a new one
        self.pixels: dict[int, float] = {}  # each page's pixel size in design units
        self.last_edit: float | None = None  # when the last edit came (time.monotonic)
        #: (key, value, task) of the slider value being computed ahead (look_ahead), or None
        self.ahead: tuple | None = None
        self.other_edits = 0  # edits other than the one computed ahead: it stops for them

    @property
    def px(self) -> float | None:
        """The finest pixel size of the open pages (None before any page said)."""
        live = [v for cid, v in self.pixels.items() if cid in self.clients]
        return min(live) if live else None

    async def send(self, ws, payload) -> bool:
        try:
            if isinstance(payload, bytes):
                await ws.send_bytes(payload)
            elif isinstance(payload, str):  # already JSON
                await ws.send_text(payload)
            else:
                await ws.send_text(json.dumps(payload, allow_nan=False))
            return True
        except Exception:  # a closed tab: forget it
            for cid, other in list(self.clients.items()):
                if other is ws:
                    del self.clients[cid]
            return False

    async def broadcast(self, payload) -> None:
        for ws in list(self.clients.values()):
            await self.send(ws, payload)

    async def broadcast_state(self, force: bool = False) -> None:
        """Send the state message to every page, if it changed since the last one.

        What it holds follows from the design, the undo and redo depths, the frame shown
        and the file: while those stay (a drag's steps), it is not even built again.
        """
        s = self.session
        key = (len(s.history), len(s.future), s.frame, s.path)
        same = self.state_key is not None and self.state_key[0] is s.design
        if not force and same and self.state_key[1] == key:
            return
        self.state_key = (s.design, key)  # the design itself: an id could be reused
        text = json.dumps(state_message(s), allow_nan=False)
        if force or text != self.state_text:
            self.state_text = text
            await self.broadcast(text)

    def look_ahead(self, msg: dict, before) -> None:
        """After a slider's step, compute its next step (one more step the same way).

        ``msg`` is the ``set`` just answered and ``before`` the key's value before it. Only
        numbers that moved, and only where the step was a full computation of at least
        :data:`AHEAD_MS` (``design.seed``: every seed new): :data:`AHEAD_DELAY` later the
        next value is computed in a worker thread (:meth:`Session.compute_ahead`), and the
        next step takes it if it asks for that value, waiting for it if need be (else it is
        dropped, and stops at its next stage for the edit that came instead).
        """
        s = self.session
        key, value = msg.get("key"), msg.get("value")
        if msg.get("op") != "set" or not isinstance(key, str) or not _full_step(s):
            return
        if not (_number(value) and _number(before) and type(value) is type(before)):
            return
        guess = value + (value - before)
        if guess == value or not math.isfinite(guess):
            return
        self._ahead_of(key, guess, AHEAD_DELAY)

    def hint(self, msg: dict) -> None:
        """A page's ``{"op": "ahead", "key", "value"}``: an input about to be used.

        The page says so when one of its number inputs gets the focus (a slider is
        pressed), with the value one step up: that first step is computed ahead as the
        next ones are (:meth:`look_ahead`), where the last computation was a full one of at
        least :data:`AHEAD_MS`. Not for ``[seeds]``, ``[relax]`` (their steps are patched
        near the changed seeds) nor sections that keep the cells.
        """
        s = self.session
        key, value = msg.get("key"), msg.get("value")
        if not isinstance(key, str) or not _number(value) or key.split(".")[0] in _NO_AHEAD:
            return
        if not _full_step(s):
            return
        if self.ahead is not None and self.ahead[:2] == (key, value):
            return
        if type(_value_at(s.data, key)) is not type(value):
            return
        self._ahead_of(key, value, 0.0)

    def _ahead_of(self, key: str, value, delay: float) -> None:
        """Compute ``key = value`` ahead in a worker thread, ``delay`` seconds from now."""
        s = self.session
        marker, data, result = self.other_edits, s.data, s.result

        def stale() -> bool:
            return self.other_edits != marker

        def start() -> None:
            if stale() or s.result is not result:
                return
            work = asyncio.to_thread(s.compute_ahead, data, result, key, value, stale)
            task = asyncio.get_running_loop().create_task(work)
            task.add_done_callback(lambda t: t.cancelled() or t.exception())  # none unread
            self.ahead = (key, value, task)

        if delay > 0:  # after the page had the time to take this step and draw it
            asyncio.get_running_loop().call_later(delay, start)
        else:
            start()

    def schedule_check(self, delay: float | None = None, *, edit: bool = False) -> None:
        """Settle a drag's result, then run the fabrication check, once edits pause.

        Later edits push both back. Settling (:meth:`Session.settle`) swaps the drag's
        provisional cells for the full computation's and sends the cells that differ.
        ``delay`` (default :func:`check_delay` of the edits' rhythm) is the wait before the
        check; ``edit``: called for an edit (its time goes into that rhythm).
        """
        now = time.monotonic()
        gap = now - self.last_edit if edit and self.last_edit is not None else None
        if edit:
            self.last_edit = now
        self.settle_due = now + SETTLE_DELAY
        self.check_due = now + (check_delay(gap) if delay is None else delay)
        if self.check_task is None or self.check_task.done():
            self.check_task = asyncio.get_running_loop().create_task(self._check_later())

    async def _settle(self) -> None:
        """Settle a drag's result; edits go on meanwhile (and make the settling moot)."""
        async with self.lock:
            previous = self.session.result
            if not self.session.provisional or time.monotonic() < self.settle_due:
                return
        self.busy = "settle"
        try:
            result = await asyncio.to_thread(self.session.settle_compute, previous)
        finally:
            self.busy = ""
        payload = None
        async with self.lock:
            diff = self.session.settle_finish(previous, result)
            if diff is None:  # an edit came first: settle again once edits pause
                self.settle_due = max(self.settle_due, time.monotonic() + SETTLE_DELAY)
                return
            if len(diff):
                self.seq += 1
                payload = geometry_message(
                    self.session,
                    diff,
                    seq=self.seq,
                    boundary=False,
                    extra={"settled": True},
                    sent=self.sent,
                    px=self.px,
                )
        if payload is not None:
            await self.broadcast(payload)

    async def _check_later(self) -> None:
        while True:
            if self.session.provisional:
                wait = self.settle_due - time.monotonic()
                if wait > 0:
                    await asyncio.sleep(wait)
                else:
                    await self._settle()
                continue
            wait = self.check_due - time.monotonic()
            if wait > 0:
                await asyncio.sleep(wait)
                continue
            async with self.lock:
                seq, result = self.seq, self.session.result
            if result.extra.get("provisional"):
                continue

            # outside the lock: edits go on while a long check runs, and stop it
            edits = self.edits

            def stale(seq=seq, edits=edits) -> bool:  # an edit arrived: it goes first
                return self.seq != seq or self.edits != edits

            self.busy = "check"
            try:
                found = await asyncio.to_thread(self.session.check, result, stale)
            finally:
                self.busy = ""
            if found is None or self.seq != seq:
                await asyncio.sleep(0.05)  # the edit that stopped it is being computed
                continue
            self.checked = result
            await self.broadcast(violations_message(self.session, seq))
            return

    async def first_check(self, wait: float | None = None) -> None:
        """Start the first check; return when it is done or after ``wait`` seconds.

        The app's lifespan awaits this before requests are answered (:func:`create_app`).
        The first check is the longest (every opening is new, and the frame's islands):
        ~65-145 ms for a 2,000-cell panel. Run beside a page that opened at once, it took
        the core from that page's first edits (a seed drag's first steps: 67-81 ms instead
        of 3-10, in the browser test at load 3). A big design's check (20,000 cells: ~1.8 s)
        goes on in the background after ``wait`` (default :data:`FIRST_CHECK_WAIT`), and
        stops for edits as any check does.
        """
        self.check_task = asyncio.get_running_loop().create_task(self._first_check())
        with contextlib.suppress(asyncio.TimeoutError):
            wait = FIRST_CHECK_WAIT if wait is None else wait
            await asyncio.wait_for(asyncio.shield(self.check_task), wait)

    async def _first_check(self) -> None:
        result, edits = self.session.result, self.edits
        found = None
        if not result.extra.get("provisional"):
            self.busy = "check"
            try:
                found = await asyncio.to_thread(
                    self.session.check, result, lambda: self.edits != edits
                )
            except Exception:  # the server runs anyway; the next check tries again
                found = None
            finally:
                self.busy = ""
        if found is not None:
            self.checked = result
        if not self.clients:
            return
        # pages came while it ran (a big design): they get the violations, or a check later
        if found is not None and result is self.session.result:
            await self.broadcast(violations_message(self.session, self.seq))
        else:
            self.check_task = None
            self.schedule_check()


#: Seconds the server waits for the first check before it answers (see _Hub.first_check)
FIRST_CHECK_WAIT = 0.5
#: Edits that come this many seconds apart or closer set the pause before a check (check_delay)
RHYTHM_WINDOW = 0.75


def check_delay(gap: float | None) -> float:
    """Seconds after an edit before the fabrication check, given the gap to the edit before.

    Edits pause when none came for ``STUDIO_CHECK_DELAY`` seconds, or, while they come in a
    rhythm slower than that (a slider's steps, each drawn before the next: 0.25-0.6 s apart
    on a loaded 2-core machine), for twice the last gap: a check started between two such
    steps ran beside the next one (in the browser test at load 5-6, 1 of 8 ``design.seed``
    steps in 2 of 6 rounds: 190-390 ms of server time at 41-49 ms of CPU, the check's
    thread taking 34-38 ms of CPU meanwhile). Gaps over :data:`RHYTHM_WINDOW` are a pause
    already; the delay stays under ``2 * RHYTHM_WINDOW``.
    """
    base = config.STUDIO_CHECK_DELAY
    if gap is None or not 0.0 <= gap <= RHYTHM_WINDOW:
        return base
    return max(base, 2.0 * gap)


def create_app(session: Session, *, hosts=LOCAL_HOSTS):
    """The starlette application of a session.

    The process's objects alive at this point are frozen out of the garbage collector
    (``gc.freeze``): a full collection of them would stall an edit by ~80 ms. Freed memory
    is kept for reuse (:func:`.heap.keep_heap`, glibc): big numpy arrays are not page-faulted
    in anew on every edit. The fabrication check of the session's result runs at start-up
    (the app's lifespan, before requests are answered): a page gets its violations at once;
    so does one seed drag step, dropped (:meth:`Session.warm`): the first drag step is as
    quick as the next ones.

    Parameters
    ----------
    session : Session
    hosts : sequence of str
        Host names the server answers to (others get 400: DNS rebinding).

    Returns
    -------
    starlette.applications.Starlette
    """
    from starlette.applications import Starlette
    from starlette.middleware import Middleware
    from starlette.middleware.trustedhost import TrustedHostMiddleware
    from starlette.responses import HTMLResponse, Response
    from starlette.routing import Mount, Route, WebSocketRoute
    from starlette.staticfiles import StaticFiles
    from starlette.websockets import WebSocket

    freeze_heap()
    keep_heap()
    hub = _Hub(session)
    static = resources.files(__package__).joinpath("static")

    async def index(request):
        text = static.joinpath("index.html").read_text(encoding="utf-8")
        return HTMLResponse(text, headers=_SECURITY_HEADERS)

    async def health(request):
        return Response("ok", media_type="text/plain")

    async def favicon(request):
        return Response(status_code=204)

    async def socket(ws: WebSocket):
        if not _same_origin(ws.headers.get("origin"), ws.headers.get("host", "")):
            await ws.close(code=1008)
            return
        await ws.accept()
        cid = next(hub.ids)
        hub.clients[cid] = ws
        px = canvas_px(session, ws.query_params.get("w"), ws.query_params.get("h"))
        if px is not None:  # the page's canvas: its first drawing at the page's resolution
            hub.pixels[cid] = px
        try:
            async with hub.lock:
                hub.seq += 1
                geom = geometry_message(
                    session, None, seq=hub.seq, boundary=True, sent=hub.sent, px=hub.px
                )
                hub.sent_boundary = boundary_key(session, hub.sent_boundary)
                state = {**state_message(session), "client": cid}
                # the violations of what this page is shown, when known: no check to wait for
                known = hub.checked is session.result
                checked = violations_message(session, hub.seq) if known else None
            await hub.send(ws, state)
            await hub.send(ws, geom)
            if checked is not None:
                await hub.send(ws, checked)
            else:
                hub.schedule_check()
            while True:
                event = await ws.receive()
                if event["type"] == "websocket.disconnect":
                    break
                await _handle(hub, ws, cid, event)
        except Exception:  # a dropped connection mid-send: the session is untouched
            pass
        finally:
            hub.clients.pop(cid, None)
            hub.pixels.pop(cid, None)

    routes = [
        Route("/", index),
        Route("/health", health),
        Route("/favicon.ico", favicon),
        WebSocketRoute("/ws", socket),
        Mount("/static", app=StaticFiles(directory=str(static)), name="static"),
    ]
    middleware = [Middleware(TrustedHostMiddleware, allowed_hosts=list(hosts))]

    @contextlib.asynccontextmanager
    async def lifespan(app):
        # a drag's code runs once before the page is served, not in its first step
        session.warm()
        # the first check runs before the page is served, not beside its first edits
        await hub.first_check()
        yield

    app = Starlette(routes=routes, middleware=middleware, lifespan=lifespan)
    app.state.hub = hub
    return app


_SECURITY_HEADERS = {
    "Content-Security-Policy": (
        "default-src 'self'; connect-src 'self' ws: wss:; img-src 'self' data: blob:; "
        "style-src 'self'; script-src 'self'; frame-ancestors 'none'"
    ),
    "X-Content-Type-Options": "nosniff",
    "Referrer-Policy": "no-referrer",
}


def _same_origin(origin: str | None, host: str) -> bool:
    """A WebSocket from a page of this server (or from no page at all, e.g. a script)."""
    if origin is None:
        return True
    parts = urlsplit(origin)
    return parts.scheme in ("http", "https") and parts.netloc.lower() == host.lower()


async def _handle(hub: _Hub, ws, cid: int, event: dict) -> None:
    text = event.get("text")
    mid = None
    if text is None:
        await hub.send(ws, _error_json("messages are JSON text", None, cid))
        return
    if len(text) > config.STUDIO_MAX_MESSAGE:
        await hub.send(
            ws,
            _error_json(
                f"message of {len(text)} bytes is over the limit of {config.STUDIO_MAX_MESSAGE}",
                None,
                cid,
            ),
        )
        return
    try:
        msg = json.loads(text, parse_constant=_reject_constant)
    except (ValueError, RecursionError) as exc:
        await hub.send(ws, _error_json(f"not JSON: {str(exc)[:80]}", None, cid))
        return
    if isinstance(msg, dict):
        mid = msg.get("id") if isinstance(msg.get("id"), int) else None
        if msg.get("op") == "view":
            await _view(hub, ws, cid, msg, mid)
            return
        if msg.get("op") == "ahead":  # not an edit: no reply
            hub.hint(msg)
            return
    session = hub.session
    received, received_at, busy = time.perf_counter(), time.time(), hub.busy
    ahead = hub.ahead
    wanted = ahead is not None and _asks(msg, ahead[0], ahead[1])
    if not wanted:
        hub.other_edits += 1  # a value computed ahead for another step stops
    hub.edits += 1
    if wanted and not ahead[2].done():  # it is computing what this edit asks: wait for it
        with contextlib.suppress(Exception):
            await asyncio.shield(ahead[2])
    before = _value_at(session.data, msg.get("key")) if isinstance(msg, dict) else None
    async with hub.lock:
        start, proc = time.perf_counter(), time.process_time()
        if _inline(session, msg):
            reply, cpu_ms, switches = _apply_timed(session, msg)
        else:
            reply, cpu_ms, switches = await asyncio.to_thread(_apply_timed, session, msg)
        server_ms = (time.perf_counter() - start) * 1e3
        # the process's other threads meanwhile (a check, a settle): CPU beside the edit's
        others_ms = max(0.0, (time.process_time() - proc) * 1e3 - cpu_ms)
        if reply.kind == "update":
            hub.seq += 1
            bkey = boundary_key(session, hub.sent_boundary)
            known = hub.sent_boundary
            send_boundary = reply.changed is None or known is None or bkey[1] != known[1]
            hub.sent_boundary = bkey
            payload = geometry_message(
                session,
                reply.changed,
                seq=hub.seq,
                px=hub.px,
                boundary=send_boundary,
                extra={
                    "reply_to": mid,
                    "client": cid,
                    "server_ms": round(server_ms, 2),
                    "cpu_ms": round(cpu_ms, 2),
                    "others_ms": round(others_ms, 2),
                    "switches": switches,
                    "ahead": session.ahead_used,  # computed ahead, while the last was drawn
                    "wait_ms": round((start - received) * 1e3, 2),
                    "received_at": round(received_at * 1e3, 2),
                    "busy": busy,
                },
                sent=hub.sent,
            )
    if reply.kind == "update":
        await hub.broadcast(payload)
        hub.look_ahead(msg, before)
        await hub.broadcast_state()
        hub.schedule_check(edit=True)
        return
    base = {"reply_to": mid, "client": cid}
    if reply.kind == "error":
        await hub.send(ws, {"op": "error", "issues": reply.issues, **base})
    elif reply.kind == "file":
        data = base64.b64encode(reply.data).decode("ascii")
        await hub.send(
            ws, {"op": "file", "name": reply.name, "mime": reply.mime, "data": data, **base}
        )
    elif reply.kind == "confirm":
        await hub.send(ws, {"op": "confirm", "name": reply.name, "files": reply.files, **base})
    elif reply.kind == "saved":
        await hub.send(ws, {"op": "saved", "name": reply.name, "files": reply.files, **base})
    else:
        await hub.send(ws, {"op": "info", "note": reply.note, **base})


#: A slider step whose full computation took at least this many milliseconds gets its next
#: step computed ahead (:meth:`_Hub.look_ahead`)
AHEAD_MS = 10.0
#: Sections whose inputs get no first step computed ahead (_Hub.hint)
_NO_AHEAD = ("seeds", "relax", "fabrication", "output", "animation")
#: Seconds after a step's geometry is sent before its next step is computed ahead: the
#: message's bytes and the page's drawing first (started at once, the computation took the
#: GIL from the event loop still writing a 290 KiB message and a core from the page)
AHEAD_DELAY = 0.025


def _full_step(s) -> bool:
    """Whether session ``s``'s last step was a full computation worth computing ahead.

    At least :data:`AHEAD_MS`, not a provisional (incremental) answer, not an animation
    frame, no hand-edited sites.
    """
    return not s.provisional and s.compute_ms >= AHEAD_MS and s.frame is None and s.sites is None


def _number(v) -> bool:
    """A finite int or float (JSON's integers may be too large for a float: not those)."""
    if not isinstance(v, int | float) or isinstance(v, bool):
        return False
    try:
        return math.isfinite(v)
    except OverflowError:
        return False


def _asks(msg, key: str, value) -> bool:
    """Whether ``msg`` sets ``key`` to ``value`` (the same number, the same type)."""
    if not isinstance(msg, dict) or msg.get("op") != "set" or msg.get("key") != key:
        return False
    v = msg.get("value")
    return type(v) is type(value) and v == value


def _value_at(data: dict, key) -> object:
    """The value of a dotted ``key`` in a design mapping (tables only), or None."""
    if not isinstance(key, str):
        return None
    node = data
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


#: An edit runs in the event loop's own thread while the session's last computation took
#: less than this (milliseconds); slower ones go to a worker thread (see _inline)
INLINE_MS = 100.0
_INLINE_OPS = frozenset(
    ("move", "set", "add", "remove", "attractor", "undo", "redo", "reset_sites", "frame")
)


def _inline(session: Session, msg) -> bool:
    """Whether an edit is computed in the event loop's thread instead of a worker thread.

    A seed drag's step (milliseconds) always is; any other edit that makes geometry is
    while the session's last computation took under :data:`INLINE_MS`. The hop to a
    worker thread and back (two thread wake-ups, the GIL handed between threads) cost a
    ``design.seed`` step of the holed 2,000-cell panel 10-20 ms of its 40-80 (two A/B
    pairs in the browser test, load 3-5): the step's CPU time was the same, its wall time
    not. Slower edits, saves and exports go to a worker thread so that the server keeps
    answering meanwhile.
    """
    op = msg.get("op") if isinstance(msg, dict) else None
    if not isinstance(op, str) or op not in _INLINE_OPS:  # (a list or an object is unhashable)
        return False
    if msg.get("op") == "move" and session.incremental:
        return True
    return session.compute_ms < INLINE_MS


def _apply_timed(session: Session, msg) -> tuple[Reply, float, list[int] | None]:
    """``session.apply(msg)``, the CPU milliseconds its thread spent on it and its switches.

    Beside the wall time (``server_ms``) they tell the work from the wait: the thread's
    voluntary context switches (it slept: the GIL held by another thread, or a file) and
    involuntary ones (the system gave its core to another thread), ``[voluntary,
    involuntary]`` (None where the system does not count them per thread).
    """
    before = _switches()
    c0 = time.thread_time()
    reply = session.apply(msg)
    cpu_ms = (time.thread_time() - c0) * 1e3
    after = _switches()
    switches = None if before is None else [a - b for a, b in zip(after, before, strict=True)]
    return reply, cpu_ms, switches


def _switches() -> tuple[int, int] | None:
    """The calling thread's (voluntary, involuntary) context switches so far, or None."""
    try:
        import resource

        use = resource.getrusage(resource.RUSAGE_THREAD)
    except (ImportError, AttributeError, OSError):  # not Linux
        return None
    return use.ru_nvcsw, use.ru_nivcsw


async def _view(hub: _Hub, ws, cid: int, msg: dict, mid) -> None:
    """A page's pixel size (``px``, design units): cells are sent at that resolution.

    When it is finer than what the page was sent (a larger window), the page gets the whole
    drawing again.
    """
    px = msg.get("px")
    if isinstance(px, bool) or not isinstance(px, int | float) or not 1e-300 < px < 1e300:
        # not below 1e-300: a subnormal px made the quantisation step 0 (a division by zero
        # that left the connection without replies)
        text = "view needs px, a number between 1e-300 and 1e300"
        await hub.send(ws, _error_json(text, mid, cid))
        return
    before = hub.px
    hub.pixels[cid] = float(px)
    if before is None or hub.px >= 0.9 * before:
        return
    async with hub.lock:
        hub.seq += 1
        payload = geometry_message(
            hub.session, None, seq=hub.seq, boundary=True, sent=hub.sent, px=hub.px
        )
    await hub.broadcast(payload)


#: The margin around the design in the page's view, a fraction of its size (studio.js view)
VIEW_PAD = 0.04


def canvas_px(session: Session, width, height) -> float | None:
    """The pixel size in design units of a page whose canvas is ``width`` x ``height`` pixels.

    The page says its canvas's size when it connects (``/ws?w=...&h=...``), so its first
    drawing travels as every later one does (thinned to its pixels, uint16 coordinates)
    instead of whole; the page's ``view`` message follows with the size it computed itself
    (the same formula: the design's bounds and :data:`VIEW_PAD` fitted into the canvas).
    None when the sizes are not positive integers.
    """
    try:
        w, h = int(width), int(height)
    except (TypeError, ValueError):
        return None
    if not (0 < w < 100_000 and 0 < h < 100_000):
        return None
    x0, y0, x1, y1 = session.result.boundary.bounds
    bw, bh = max(x1 - x0, 1e-9), max(y1 - y0, 1e-9)
    s = min(w / (bw * (1 + 2 * VIEW_PAD)), h / (bh * (1 + 2 * VIEW_PAD)))
    return 1.0 / s if s > 0 and math.isfinite(s) else None


def boundary_key(session: Session, known=None):
    """``(domain, its WKB)`` of the session's result; ``known`` (an earlier key) when the same.

    The domain object is compared first (a drag keeps it), its WKB only when it differs.
    """
    domain = session.result.domain
    if known is not None and known[0] is domain:
        return known
    return (domain, shapely.to_wkb(domain))


def _error_json(message: str, mid, cid) -> dict:
    return {
        "op": "error",
        "issues": [{"key": "", "message": message}],
        "reply_to": mid,
        "client": cid,
    }


def serve(
    source=None,
    *,
    host: str = "127.0.0.1",
    port: int = 8765,
    open_browser: bool = True,
    session: Session | None = None,
    log_level: str = "warning",
) -> None:
    """Run the studio for a design file until interrupted.

    Parameters
    ----------
    source : str, Path, dict or None
        The design (None: the starter design, saved into the current folder).
    host : str
        Address to bind; anything but a loopback address prints a warning.
    port : int
        TCP port (0: any free one).
    open_browser : bool
        Open the page in the default browser.
    session : Session, optional
        An existing session instead of ``source``.
    log_level : str
        uvicorn's log level.
    """
    import socket
    import sys
    import webbrowser

    session = session or Session(source)
    hosts = list(LOCAL_HOSTS)
    if host not in LOCAL_HOSTS:
        print(
            f"voroforge studio: warning: listening on {host}: anyone who can reach this "
            "address can edit the design and write files into its folder",
            file=sys.stderr,
        )
        hosts = ["*"] if host in ("0.0.0.0", "::") else [*hosts, host]
    sock = socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    sock.bind((host, port))
    sock.listen(128)  # a browser opened before uvicorn is up waits instead of being refused
    port = sock.getsockname()[1]
    shown = "127.0.0.1" if host in ("0.0.0.0", "::") else host
    url = f"http://{'[' + shown + ']' if ':' in shown else shown}:{port}/"
    print(f"voroforge studio: {url}  (Ctrl+C to stop)", flush=True)
    if open_browser:
        webbrowser.open(url)
    app = create_app(session, hosts=hosts)
    stoppable_server(server_config(app, log_level=log_level)).run(sockets=[sock])


def server_config(app, *, log_level: str = "warning"):
    """The uvicorn configuration the studio runs with (:func:`serve`, and the browser tests).

    Returns
    -------
    uvicorn.Config
    """
    import uvicorn

    return uvicorn.Config(
        app,
        log_level=log_level,
        ws_max_size=4 * config.STUDIO_MAX_MESSAGE,
        timeout_graceful_shutdown=config.STUDIO_SHUTDOWN_S,
        # geometry is binary floats that hardly compress: deflate would only cost time
        ws_per_message_deflate=False,
    )
