"""The studio as a Jupyter widget (anywidget): the page's editor in a notebook cell.

:func:`widget` returns a :class:`StudioWidget` showing the design with the same drawing,
dragging, sliders, live check, undo/redo, save and export as ``voroforge studio``; the
page's messages go over the widget's comm instead of a WebSocket (same
:class:`~voroforge.studio.session.Session`, same binary geometry). The current state is
readable from Python at any time: ``w.design`` (the validated design), ``w.result`` (its
geometry), ``w.sites``, ``w.toml`` (the design as it would be saved) with ``w.seeds_csv``
(the hand-placed sites it names), and ``w.save(name)`` writes both into the design's folder.

Examples
--------
>>> from voroforge.studio import widget  # doctest: +SKIP
>>> w = widget("examples/laser-panel.toml")  # doctest: +SKIP
>>> w  # doctest: +SKIP
"""

from __future__ import annotations

import json
import threading
from importlib import resources

import anywidget
import traitlets

from .. import config
from .server import boundary_key, geometry_message, state_message, violations_message
from .session import Session
from .tomlfile import dumps

__all__ = ["StudioWidget", "widget"]

_STATIC = resources.files(__package__).joinpath("static")

_GLUE = r"""
export default {
  render({ model, el }) {
    const root = document.createElement("div");
    root.className = "vf-studio vf-widget";
    root.innerHTML = `
      <header class="vf-bar"><strong class="vf-title">voroforge studio</strong>
        <span class="vf-file" data-role="file"></span>
        <button data-act="undo">Undo</button><button data-act="redo">Redo</button>
        <button data-act="reset_sites">Reset seeds</button><button data-act="save">Save…</button>
        <button data-act="export-svg">SVG</button><button data-act="export-dxf">DXF</button>
        <button data-act="export-png">PNG</button></header>
      <main class="vf-main"><div class="vf-canvas-wrap"><canvas data-role="canvas"></canvas>
        <div class="vf-legend" data-role="legend"></div>
      <div class="vf-timeline" data-role="timeline" hidden><button data-act="play">Play</button>
      <input type="range" min="0" max="1" step="1" value="0" data-role="scrub">
      <span data-role="frame"></span></div></div>
        <aside class="vf-panel" data-role="panel"></aside></main>
      <footer class="vf-status"><span data-role="status">starting…</span>
        <span class="vf-message" data-role="message"></span></footer>`;
    el.appendChild(root);
    const studio = new VoroStudio.Studio(root, { send: (text) => model.send({ text }) });
    model.on("msg:custom", (msg, buffers) => {
      if (msg.op === "geom" && buffers && buffers.length) {
        const v = buffers[0];
        studio.receive(v.buffer.slice(v.byteOffset, v.byteOffset + v.byteLength));
      } else {
        studio.receive(msg);
      }
    });
    requestAnimationFrame(() => { studio.resize(); model.send({ text: '{"op":"hello"}' }); });
    return () => root.remove();
  },
};
"""


#: The page's scripts, in the order index.html loads them.
_SCRIPTS = ("raster.js", "geom.js", "studio.js")


class StudioWidget(anywidget.AnyWidget):
    """A live design editor in a notebook (see the module docstring)."""

    _esm = traitlets.Unicode(
        "".join(_STATIC.joinpath(f).read_text(encoding="utf-8") for f in _SCRIPTS) + _GLUE
    ).tag(sync=True)
    _css = traitlets.Unicode(
        _STATIC.joinpath("studio.css").read_text(encoding="utf-8")
        + ".vf-widget { height: 560px; }\n"
    ).tag(sync=True)
    #: Cells in the current drawing (updates after every edit).
    cells = traitlets.Int(0).tag(sync=True)

    def __init__(self, session: Session, **kwargs):
        super().__init__(**kwargs)
        self.session = session
        self.cells = len(session.result.raw)
        self._seq = 0
        self._timer: threading.Timer | None = None
        self._lock = threading.Lock()
        self._check_lock = threading.Lock()  # one live check at a time (timers may overlap)
        self._sent: dict = {}  # what the view has (patches are made against it)
        self._px: float | None = None  # the view's pixel size in design units
        self._boundary = None  # (domain, WKB) last sent
        self.on_msg(self._on_msg)

    @property
    def design(self):
        """The current validated design (:class:`~voroforge.design.schema.Design`)."""
        return self.session.design

    @property
    def result(self):
        """The current geometry (:class:`~voroforge.design.compute.Result`, no ``frame``).

        Always the full computation's (a drag's provisional cells are settled first).
        """
        with self._lock:
            self.session.settle()
        return self.session.result

    @property
    def sites(self):
        """The current sites, (n, 2) float64 (a copy)."""
        return self.session.result.sites.copy()

    @property
    def toml(self) -> str:
        """The design as TOML, as *Save* writes it.

        Once sites were placed by hand it reads them from ``design.seeds.csv``
        (``[seeds] method = "file"``; ``design.seeds.geojson`` when the sites came from a
        seed file with attribute columns, which it keeps): write :attr:`seeds_csv` to that
        file beside it, or use :meth:`save`, which writes both files.
        """
        data, _ = self.session.saved_data("design.seeds.csv")
        return dumps(data)

    @property
    def seeds_csv(self) -> str | None:
        """The text of the seeds file that :attr:`toml` names, or None.

        The hand-placed sites, bit for bit (CSV ``x,y``; GeoJSON points with each site's
        row of attributes when they came from a seed file with attribute columns); None
        while the sites come from ``[seeds]``.
        """
        return self.session.saved_data("design.seeds.csv")[1]

    def save(self, name: str, *, overwrite: bool = False):
        """Save as the page's *Save* does: ``name`` (``*.toml``) in the design's folder.

        With hand-placed sites, ``<stem>.seeds.csv`` beside it (``<stem>.seeds.geojson``
        when the seed file had attribute columns); each file written atomically.

        Returns
        -------
        Reply
            ``kind == "saved"`` with the file names, or ``"confirm"`` naming the files that
            exist already (nothing written; pass ``overwrite=True``).

        Raises
        ------
        ValueError
            For a name that is not a plain ``*.toml`` file name.
        """
        with self._lock:
            reply = self.session.apply({"op": "save", "name": name, "overwrite": overwrite})
        if reply.kind == "error":
            raise ValueError("; ".join(i["message"] for i in reply.issues))
        return reply

    def apply(self, msg: dict):
        """Apply one edit from Python, as the page does (``{"op": "set", ...}``); the view follows.

        Returns
        -------
        Reply
        """
        return self._apply(msg, None)

    def _on_msg(self, _widget, content, _buffers) -> None:
        text = content.get("text") if isinstance(content, dict) else None
        if not isinstance(text, str) or len(text) > config.STUDIO_MAX_MESSAGE:
            self.send({"op": "error", "issues": [{"key": "", "message": "bad message"}]})
            return
        try:
            msg = json.loads(text, parse_constant=_reject)
        except (ValueError, RecursionError):
            self.send({"op": "error", "issues": [{"key": "", "message": "not JSON"}]})
            return
        mid = msg.get("id") if isinstance(msg, dict) else None
        if isinstance(msg, dict) and msg.get("op") == "hello":
            self._send_geometry(None, mid)
            self._schedule_check()
            return
        if isinstance(msg, dict) and msg.get("op") == "view":
            px = msg.get("px")
            if isinstance(px, int | float) and not isinstance(px, bool) and 0 < px < 1e300:
                finer = self._px is not None and px < 0.9 * self._px
                self._px = float(px)
                if finer:
                    self._send_geometry(None, None)
            return
        self._apply(msg, mid)

    def _apply(self, msg, mid):
        import base64

        with self._lock:
            reply = self.session.apply(msg)
        base = {"reply_to": mid}
        if reply.kind == "update":
            self._send_geometry(reply.changed, mid)
            self._schedule_check()
        elif reply.kind == "file":
            data = base64.b64encode(reply.data).decode("ascii")
            self.send({"op": "file", "name": reply.name, "mime": reply.mime, "data": data, **base})
        elif reply.kind == "error":
            self.send({"op": "error", "issues": reply.issues, **base})
        elif reply.kind in ("confirm", "saved"):
            self.send({"op": reply.kind, "name": reply.name, "files": reply.files, **base})
        else:
            self.send({"op": "info", "note": reply.note, **base})
        return reply

    def _send_geometry(self, changed, mid) -> None:
        with self._lock:
            self._seq += 1
            key = boundary_key(self.session, self._boundary)
            boundary = changed is None or self._boundary is None or key[1] != self._boundary[1]
            self._boundary = key
            payload = geometry_message(
                self.session,
                changed,
                seq=self._seq,
                boundary=boundary,
                extra={"reply_to": mid},
                sent=self._sent,
                px=self._px,
            )
            state = state_message(self.session)
        self.cells = len(self.session.result.raw)
        self.send(state)
        self.send({"op": "geom"}, buffers=[payload])

    def _schedule_check(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
        seq = self._seq
        self._timer = threading.Timer(config.STUDIO_CHECK_DELAY, self._check, args=(seq,))
        self._timer.daemon = True
        self._timer.start()

    def _check(self, seq: int) -> None:
        with self._lock:
            diff = self.session.settle() if self._seq == seq else None
        if diff is not None and len(diff):
            self._send_geometry(diff, None)
            seq = self._seq
        with self._check_lock:
            found = self.session.check(self.session.result, lambda: self._seq != seq)
        if found is not None and self._seq == seq:
            self.send(violations_message(self.session, seq))


def _reject(name: str):
    raise ValueError(f"{name} is not a number the studio takes")


def widget(design=None, *, folder=None) -> StudioWidget:
    """The studio editor as a notebook widget.

    Parameters
    ----------
    design : str, Path, dict, Session or None
        A TOML design file, a design mapping, an existing session, or None (the starter).
    folder : str or Path, optional
        Where *Save* writes (default: the design file's folder, else the current folder).

    Returns
    -------
    StudioWidget
        Display it (last expression of a cell); read ``w.design``, ``w.result``,
        ``w.sites`` and ``w.toml`` from Python.
    """
    session = design if isinstance(design, Session) else Session(design, folder=folder)
    return StudioWidget(session)
