"""The studio in a real browser: Playwright driving Debian's chromium.

One browser for the module; each design gets its own server (a thread, a free port). The
latency test prints the repaint times the page measured with ``performance.now()`` (from the
pointer event to the frame after the new geometry is drawn); they are printed, not asserted.
Set ``VOROFORGE_STUDIO_SHOTS=DIR`` to keep screenshots (the docs' pictures come from here)
and ``VOROFORGE_STUDIO_LATENCY=full`` for the whole latency table (20,000 cells, more samples).
"""

from __future__ import annotations

import os
import shutil
import socket
import threading
import time
from pathlib import Path

import numpy as np
import pytest

CHROMIUM = "/usr/bin/chromium"
ARGS = (
    "--headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
    "--disable-background-networking --disable-component-update --disable-sync"
).split()

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
sync_api = pytest.importorskip("playwright.sync_api", reason="PyPI playwright is not installed")
pytestmark = pytest.mark.skipif(
    not Path(CHROMIUM).exists(),
    reason=f"Debian chromium is not installed at {CHROMIUM} (make test installs it with apt-get)",
)

ROOT = Path(__file__).resolve().parents[1]
SHOTS = os.environ.get("VOROFORGE_STUDIO_SHOTS")


class Served:
    """A studio server for one session, in a thread on a free port."""

    def __init__(self, session):
        import uvicorn

        from voroforge.studio.server import create_app, server_config

        self.session = session
        sock = socket.socket()
        sock.bind(("127.0.0.1", 0))
        self.url = f"http://127.0.0.1:{sock.getsockname()[1]}/"
        self.server = uvicorn.Server(server_config(create_app(session)))
        self.thread = threading.Thread(
            target=self.server.run, kwargs={"sockets": [sock]}, daemon=True
        )
        self.thread.start()
        deadline = time.monotonic() + 30
        while not self.server.started and time.monotonic() < deadline:
            time.sleep(0.02)

    def stop(self):
        self.server.should_exit = True
        self.thread.join(10)


class ServedProcess:
    """A studio server for a design (dict), in a process of its own, as ``voroforge studio``.

    For the latency table (``VOROFORGE_STUDIO_SERVER=process``): in a thread of the test's
    process the server shares the GIL with Playwright's client, which parses every WebSocket
    frame the page sends or receives (the driver forwards them all, base64 in JSON), work no
    user's server has beside it. (Two A/B pairs at load 2.5-4.4 showed no difference beyond
    the noise: the driver's and the browser's share of the two cores remains.)
    """

    def __init__(self, data: dict, folder: Path):
        import json
        import subprocess
        import sys
        import urllib.request

        sock = socket.socket()
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
        sock.close()
        self.url = f"http://127.0.0.1:{port}/"
        code = (
            "import json, sys, uvicorn\n"
            "from voroforge.studio.server import create_app, server_config\n"
            "from voroforge.studio.session import Session\n"
            "data, folder, port = json.loads(sys.argv[1]), sys.argv[2], int(sys.argv[3])\n"
            "config = server_config(create_app(Session(data, folder=folder)))\n"
            "config.host, config.port = '127.0.0.1', port\n"
            "uvicorn.Server(config).run()\n"
        )
        self.proc = subprocess.Popen(
            [sys.executable, "-c", code, json.dumps(data), str(folder), str(port)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            try:
                with urllib.request.urlopen(self.url + "health", timeout=1) as r:
                    if r.status == 200:
                        return
            except OSError:
                time.sleep(0.05)
            if self.proc.poll() is not None:
                break
        self.stop()
        raise RuntimeError("the studio server process did not start")

    def stop(self):
        self.proc.terminate()
        try:
            self.proc.wait(10)
        except Exception:
            self.proc.kill()
            self.proc.wait(10)


@pytest.fixture(scope="module")
def browser():
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield b
        b.close()


def _open(browser, session, size=(1280, 760), served=None):
    served = served or Served(session)
    # bypass_csp: Playwright polls with eval, which the page's CSP (rightly) forbids
    page = browser.new_page(
        viewport={"width": size[0], "height": size[1]}, accept_downloads=True, bypass_csp=True
    )
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(served.url)
    page.wait_for_function("window.studio && window.studio.n > 0", timeout=60_000)
    return served, page, errors


def _idle(page, timeout=60_000):
    page.wait_for_function("!studio.inflight && !studio.waiting.length", timeout=timeout)


def _shot(page, name):
    """Keep a screenshot (``VOROFORGE_STUDIO_SHOTS``), in 256 colours as the docs hold them."""
    if SHOTS:
        from PIL import Image

        Path(SHOTS).mkdir(parents=True, exist_ok=True)
        path = Path(SHOTS) / name
        page.screenshot(path=str(path))
        with Image.open(path) as im:
            rgb = im.convert("RGB")
        quantized = rgb.quantize(256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        quantized.save(path, optimize=True)


@pytest.fixture(scope="module")
def panel(browser, tmp_path_factory):
    import tomllib

    from voroforge.studio.session import Session
    from voroforge.studio.tomlfile import dumps

    folder = tmp_path_factory.mktemp("studio")
    data = tomllib.loads((ROOT / "examples" / "laser-panel.toml").read_text(encoding="utf-8"))
    data["output"]["formats"] = ["svg", "dxf"]  # the PNG preview adds time, not coverage
    (folder / "laser-panel.toml").write_text(dumps(data), encoding="utf-8")
    session = Session(folder / "laser-panel.toml")
    served, page, errors = _open(browser, session)
    yield page, session, folder
    assert not errors, errors
    page.close()
    served.stop()


def _drag(page, i, dx, dy, steps=8):
    x, y = page.evaluate(f"studio.toScreen(studio.site({i}))")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, steps + 1):
        page.mouse.move(x + dx * k / steps, y + dy * k / steps)
        page.wait_for_timeout(15)
    page.mouse.up()
    _idle(page)
    return x + dx, y + dy


def _slide(page, key, value):
    """Move a slider as a user does: set its value and fire 'input'."""
    page.eval_on_selector(
        f".vf-ctl[data-key='{key}'] input[type=range]",
        "(e, v) => { e.value = v; e.dispatchEvent(new Event('input')); }",
        value,
    )


def _patched_is_whole(page):
    """Whether the canvas, patched edit by edit, has the pixels of a whole redraw."""
    return page.evaluate(
        """() => { const s = studio, c = s.ctx, W = s.canvas.width, H = s.canvas.height;
             s.paintNow(); const a = c.getImageData(0, 0, W, H).data;
             s.baseValid = false; s.paintNow(); const b = c.getImageData(0, 0, W, H).data;
             let diff = 0; for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) diff++;
             return diff; }"""
    )


def test_page_draws_the_design(panel):
    page, session, _ = panel
    assert page.evaluate("studio.n") == len(session.result.raw)
    assert "cells" in page.inner_text("[data-role=status]")
    page.wait_for_function("studio.violationTotal !== undefined", timeout=60_000)
    legend = page.inner_text("[data-role=legend]")
    assert all(kind in legend for kind in ("web", "opening", "corner", "island"))
    # the canvas is drawn: many distinct colours
    colours = page.evaluate(
        """() => { const c = studio.canvas, d = c.getContext('2d')
             .getImageData(0, 0, c.width, c.height).data, s = new Set();
           for (let i = 0; i < d.length; i += 397) s.add(d[i] + ',' + d[i+1] + ',' + d[i+2]);
           return s.size; }"""
    )
    assert colours > 20
    # the patch path ran with the first drawing (not in the first drag steps), unseen
    assert page.evaluate("studio.warmed") and _patched_is_whole(page) == 0
    keys = page.eval_on_selector_all(".vf-ctl", "els => els.map(e => e.dataset.key)")
    assert {"seeds.radius", "cells.web", "cells.fillet", "fabrication.min_web"} <= set(keys)


def test_drag_a_seed_changes_its_cell(panel):
    page, session, _ = panel
    before = page.evaluate("studio.cellPath(5)")
    _drag(page, 5, 14, -9)
    after = page.evaluate("studio.cellPath(5)")
    assert after != before
    assert _patched_is_whole(page) == 0
    assert session.sites is not None
    assert np.allclose(page.evaluate("studio.site(5)"), session.result.sites[5])
    assert page.evaluate("studio.latencies.filter(l => l.op === 'move' && !l.full).length") >= 1
    page.wait_for_function("studio.violationSeq === studio.seq", timeout=60_000)  # checked
    _shot(page, "laser-panel.png")  # the status line shows a drag step's figures


def test_status_line_is_written_sparingly_during_a_drag(panel):
    """A drag rewrites the status line at most every 250 ms, and shows the last step's figures.

    A text that changes lays the page out and paints it again: on every step, that was a
    frame's work beside the drag's own.
    """
    page, _, _ = panel
    page.wait_for_function("studio.violationSeq === studio.seq", timeout=60_000)  # quiet
    page.evaluate(
        """() => { const s = studio; s.statusWrites = 0; s.dragStart = performance.now();
             new MutationObserver(() => { s.statusWrites++; })
               .observe(s.statusEl, { childList: true, characterData: true, subtree: true }); }"""
    )
    x, y = page.evaluate("studio.toScreen(studio.site(7))")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 13):
        page.mouse.move(x + k, y - k / 2)
        _idle(page)
    page.mouse.up()
    _idle(page)
    writes, ms = page.evaluate("[studio.statusWrites, performance.now() - studio.dragStart]")
    # 12 steps: each wrote it twice before; now the timer's writes, the last step's and
    # maybe a settle's or a check's
    assert 1 <= writes <= 3 + ms / 250, (writes, ms)
    # once the drag ends, the line shows the last step's repaint figure
    page.wait_for_function(
        "studio.statusEl.textContent.includes('repaint ' + studio.roundTrip.toFixed(1) + ' ms')",
        timeout=10_000,
    )


def test_add_and_remove_a_seed_then_undo(panel):
    page, session, _ = panel
    n = page.evaluate("studio.n")
    # an empty spot: the middle between two neighbouring sites, far enough from both
    spot = page.evaluate(
        """() => { const s = studio.sites; let best = null;
           for (let i = 0; i < s.length / 2; i++) for (let j = i + 1; j < s.length / 2; j++) {
             const p = [(s[2*i] + s[2*j]) / 2, (s[2*i+1] + s[2*j+1]) / 2];
             const q = studio.toScreen(p), a = studio.toScreen([s[2*i], s[2*i+1]]);
             const d = Math.hypot(q[0] - a[0], q[1] - a[1]);
             if (d > 20 && d < 40 && studio.nearestSite(p, 15) < 0) return q; }
           return best; }"""
    )
    page.mouse.click(*spot)
    _idle(page)
    assert page.evaluate("studio.n") == n + 1
    page.keyboard.down("Shift")
    page.mouse.click(*spot)
    page.keyboard.up("Shift")
    _idle(page)
    assert page.evaluate("studio.n") == n
    page.click("[data-act=undo]")
    _idle(page)
    assert page.evaluate("studio.n") == n + 1
    page.keyboard.press("Control+z")
    _idle(page)
    assert page.evaluate("studio.n") == n == len(session.result.raw)
    assert _patched_is_whole(page) == 0


def test_slider_changes_the_cell_count_and_bad_values_show_the_error(panel):
    page, session, _ = panel
    n = page.evaluate("studio.n")
    _slide(page, "seeds.radius", 25)
    page.wait_for_function(f"studio.n !== {n}", timeout=60_000)
    _idle(page)
    assert page.evaluate("studio.n") == len(session.result.raw) > n
    assert session.sites is None  # new seeds from [seeds]
    assert _patched_is_whole(page) == 0
    good = page.evaluate("studio.n")
    box = ".vf-ctl[data-key='cells.web'] input[type=number]"
    page.fill(box, "-2")
    page.press(box, "Enter")
    page.wait_for_selector(".vf-ctl.vf-bad[data-key='cells.web']", timeout=30_000)
    message = page.inner_text(".vf-ctl[data-key='cells.web'] .vf-err")
    assert ">= 0" in message
    assert page.evaluate("studio.n") == good  # the last good drawing stays
    held = page.get_attribute(box, "data-last")  # the value the server holds
    page.fill(box, "1e309")  # past float64: the box must not go blank with nothing said
    page.press(box, "Enter")
    page.wait_for_function(
        "document.querySelector(\".vf-ctl[data-key='cells.web'] .vf-err\").textContent"
        ".indexOf('finite') >= 0",
        timeout=30_000,
    )
    assert page.input_value(box) == held != ""
    assert page.evaluate("studio.n") == good


def test_save_rebuild_and_export_are_byte_identical(panel):
    from voroforge.cli import main

    page, session, folder = panel
    _drag(page, 2, -10, 6)
    answers = iter([("accept", "studio-saved.toml"), ("accept", "studio-saved.toml"), ("no", "")])
    asked = []

    def on_dialog(d):
        asked.append((d.type, d.message))
        kind, text = next(answers)
        d.accept(text) if kind == "accept" else d.dismiss()

    page.on("dialog", on_dialog)
    page.click("[data-act=save]")
    page.wait_for_function("studio.saved && studio.saved.name === 'studio-saved.toml'")
    assert (folder / "studio-saved.toml").exists() and (folder / "studio-saved.seeds.csv").exists()
    # saving again asks before overwriting; saying no leaves the file alone
    stamp = (folder / "studio-saved.toml").stat().st_mtime_ns
    page.click("[data-act=save]")
    page.wait_for_function("!studio.inflight")
    deadline = time.monotonic() + 20
    while len(asked) < 3 and time.monotonic() < deadline:
        page.wait_for_timeout(50)
    page.remove_listener("dialog", on_dialog)
    assert [t for t, _ in asked] == ["prompt", "prompt", "confirm"] and "Overwrite" in asked[2][1]
    assert (folder / "studio-saved.toml").stat().st_mtime_ns == stamp
    with page.expect_download() as dl:
        page.click("[data-act=export-dxf]")
    exported = folder / "exported.dxf"
    dl.value.save_as(exported)
    assert main(["build", str(folder / "studio-saved.toml"), "-o", str(folder / "out")]) == 0
    assert (folder / "out" / "laser-panel.dxf").read_bytes() == exported.read_bytes()


# --- speed ---------------------------------------------------------------------------------

HOLED_2000 = {
    "design": {"name": "holed-2000", "seed": 1},
    "boundary": {
        "shape": "polygon",
        "points": [[0, 0], [1000, 0], [1000, 700], [0, 700]],
        "holes": [[[400, 250], [600, 250], [600, 450], [400, 450]]],
    },
    "seeds": {"method": "random", "count": 2000},
    "cells": {"web": 2.0, "fillet": 1.5},
}


def _drag_latencies(page, moves, span=60):
    i = page.evaluate("Math.floor(studio.n / 2)")
    x, y = page.evaluate(f"studio.toScreen(studio.site({i}))")
    page.evaluate("studio.latencies = []")
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, moves + 1):
        page.mouse.move(x + span * np.sin(k / 3.0) / 6, y + span * np.cos(k / 4.0) / 6)
        _idle(page)
    page.mouse.up()
    return page.evaluate("studio.latencies.filter(l => l.op === 'move')")


def _row(name, lat):
    """One table row: p50/p95 to the frame and to the drawn canvas, means of the stages."""
    ms = np.array([entry["ms"] for entry in lat])
    drawn = np.array([entry["drawn"] for entry in lat])

    def mean(key):
        return float(np.mean([entry.get(key) or 0.0 for entry in lat]))

    stages = (
        "queue_ms",
        "server_ms",
        "cpu_ms",
        "encode_ms",
        "wire_ms",
        "up_ms",
        "down_ms",
        "parse_ms",
        "paint_ms",
        "frame_ms",
    )
    return (
        f"| {name:<46} | {lat[0]['n']:>6} | {len(ms):>3} | {np.percentile(ms, 50):>6.1f} | "
        f"{np.percentile(ms, 95):>6.1f} | {np.percentile(drawn, 50):>6.1f} | "
        f"{np.percentile(drawn, 95):>6.1f} | "
        + " | ".join(f"{mean(k):>5.1f}" for k in stages)
        + f" | {mean('bytes') / 1024:>6.1f} |"
    )


HEAD = (
    "| case | cells | n | frame p50 | frame p95 | drawn p50 | drawn p95 | mean: queue | server "
    "| server CPU | encode | wire | up | down | parse | paint | frame | KiB |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
)


def _slider_latencies(page, key, values):
    """Type each value into the slider's number box (Enter), wait for the new drawing."""
    page.evaluate("studio.latencies = []")
    box = f".vf-ctl[data-key='{key}'] input[type=number]"
    for value in values:
        seq = page.evaluate("studio.seq")
        page.fill(box, str(value))
        page.press(box, "Enter")
        page.wait_for_function(f"studio.seq > {seq}", timeout=60_000)
        _idle(page)
        page.wait_for_timeout(40)  # the latency is recorded on the frame after the redraw
    return page.evaluate("studio.latencies.filter(l => l.op === 'set')")


#: Sliders that make new seeds: seeds.count keeps the random stream's first seeds (the cells
#: near added or dropped ones change), design.seed makes every seed new.
SLIDERS = {
    "seeds.count": (1990, 2010, 1995, 2005, 2000, 1985, 2015, 2001),
    "design.seed": (2, 3, 4, 5, 6, 7, 8, 9),
}


def test_latency_table(browser, tmp_path):
    """Repaint latency of seed drags and of the count slider, printed (not asserted).

    ``VOROFORGE_STUDIO_LATENCY=full`` measures every row of the issue's table with more
    samples, ``VOROFORGE_STUDIO_ROUNDS=K`` repeats each row K times (a fresh page each),
    ``VOROFORGE_STUDIO_CASES=TEXT|TEXT...`` only the rows whose name holds one of the texts.
    ``VOROFORGE_STUDIO_SERVER=process`` runs each row's server in a process of its own
    (:class:`ServedProcess`) instead of a thread of this one.
    """
    from voroforge.studio.session import Session

    full = os.environ.get("VOROFORGE_STUDIO_LATENCY") == "full"
    rounds = int(os.environ.get("VOROFORGE_STUDIO_ROUNDS", "1"))
    plain = {**HOLED_2000, "cells": {}}
    big = {**plain, "seeds": {"method": "random", "count": 20000}}
    cases = [("seed drag, 2,000 cells, hole, inset + fillet", HOLED_2000, 30 if full else 5)]
    if full:
        cases.append(("seed drag, 2,000 plain cells", plain, 30))
        cases.append(("seed drag, 20,000 plain cells", big, 15))
        for key in SLIDERS:
            cases.append((f"slider {key}, 2,000 cells, inset + fillet", HOLED_2000, key))
            cases.append((f"slider {key}, 2,000 plain cells", plain, key))
    # "process": each row's server in a process of its own, as users run it (ServedProcess)
    in_thread = os.environ.get("VOROFORGE_STUDIO_SERVER") != "process"
    only = os.environ.get("VOROFORGE_STUDIO_CASES")  # e.g. "seed drag, 2,000 plain|design.seed"
    if only:
        cases = [c for c in cases if any(w in c[0] for w in only.split("|"))]
    rows = []
    for _ in range(rounds):
        for name, data, moves in cases:
            if in_thread:
                served, page, errors = _open(browser, Session(data, folder=tmp_path))
            else:
                served = ServedProcess(data, tmp_path)
                served, page, errors = _open(browser, None, served=served)
            try:
                if isinstance(moves, int):
                    lat = _drag_latencies(page, moves)
                    assert lat and all(not entry["full"] for entry in lat)
                else:
                    lat = _slider_latencies(page, moves, SLIDERS[moves])
                    assert len(lat) == len(SLIDERS[moves])
                rows.append(_row(name, lat))
                assert _patched_is_whole(page) == 0
                if os.environ.get("VOROFORGE_STUDIO_DEBUG"):  # the slowest three, by stage
                    slow = sorted(range(len(lat)), key=lambda k: -lat[k]["drawn"])[:3]
                    beside = sum(bool(entry.get("busy")) for entry in lat)
                    ahead = sum(bool(entry.get("ahead")) for entry in lat)
                    print(
                        f"{name}: {beside} of {len(lat)} steps beside a check or settle, "
                        f"{ahead} computed ahead"
                    )
                    for k in slow:
                        stages = {s: round(v, 1) for s, v in lat[k].items() if s.endswith("_ms")}
                        busy = f" beside the {lat[k]['busy']}" if lat[k].get("busy") else ""
                        sw = lat[k].get("switches")  # the server thread's [slept, preempted]
                        sw = f" switches {sw}" if sw else ""
                        sw += " (computed ahead)" if lat[k].get("ahead") else ""
                        print(f"  step {k}: drawn {lat[k]['drawn']:.1f}{busy}{sw}", stages)
                assert not errors, errors
            finally:
                page.close()
                served.stop()
    load = ", ".join(f"{v:.1f}" for v in os.getloadavg())
    where = "in the test's process" if in_thread else "in a process of its own"
    print(
        f"\nstudio repaint latency, load {load}, server {where}: ms from the input event to the "
        "page's next frame after the redraw (frame) and to the redrawn canvas (drawn)"
    )
    print(HEAD)
    print("\n".join(rows))


def test_scattered_patches_repaint_exactly(browser, tmp_path):
    """Count steps change cells all over the panel: many small repaints, the same pixels."""
    from voroforge.studio.session import Session

    data = {**HOLED_2000, "cells": {}, "seeds": {"method": "random", "count": 800}}
    served, page, errors = _open(browser, Session(data, folder=tmp_path))
    try:
        page.evaluate(
            """() => { const s = studio, paint = s.paintRect.bind(s); s.tiled = 0;
                 s.paintRect = function (rect, r, v, cand) { if (cand) s.tiled++;
                   return paint(rect, r, v, cand); }; }"""
        )
        lat = _slider_latencies(page, "seeds.count", (812, 806))
        assert len(lat) == 2 and not any(entry["full"] for entry in lat)
        assert page.evaluate("studio.tiled") > 3  # the scattered boxes took the tiled path
        assert _patched_is_whole(page) == 0
        assert not errors, errors
    finally:
        page.close()
        served.stop()


def test_facade_screenshot(browser, tmp_path):
    from voroforge.studio.session import Session

    shutil.copy(ROOT / "examples" / "facade-panel.toml", tmp_path / "facade-panel.toml")
    session = Session(tmp_path / "facade-panel.toml")
    served, page, errors = _open(browser, session)
    try:
        page.wait_for_function("studio.violationTotal !== undefined", timeout=60_000)
        # drag the attractor: the field and the webs follow
        a = page.evaluate("studio.toScreen(studio.attractors[0].points[0])")
        page.mouse.move(*a)
        page.mouse.down()
        page.mouse.move(a[0] + 60, a[1] + 20, steps=4)
        page.mouse.up()
        _idle(page)
        assert page.evaluate("studio.attractors[0].points[0][0]") > 300
        _drag(page, 40, 6, -4)  # and a seed: the status line shows a drag step's figures
        page.wait_for_function("studio.violationSeq === studio.seq", timeout=60_000)
        _shot(page, "facade-panel.png")
        # a tighter limit: the live check circles the thin webs near the sun
        box = ".vf-ctl[data-key='fabrication.min_web'] input[type=number]"
        page.fill(box, "12")
        page.press(box, "Enter")
        page.wait_for_function("studio.violationTotal > 0", timeout=60_000)
        total = page.evaluate("studio.violationTotal")
        assert total == len(session.violations) and {v.kind for v in session.violations} == {"web"}
        assert f"web {total}" in page.inner_text("[data-role=legend]")
        _shot(page, "violations.png")
        assert not errors, errors
    finally:
        page.close()
        served.stop()


def test_play_an_animation(browser, tmp_path):
    import tomllib

    from voroforge.studio.session import Session

    data = tomllib.loads((ROOT / "docs" / "studio" / "attractor-animation.toml").read_text())
    data["seeds"]["radius"] = 26
    served, page, errors = _open(browser, Session(data, folder=tmp_path))
    try:
        assert page.is_visible("[data-role=timeline]")
        first = page.evaluate("studio.cellPath(0)")
        sites = page.evaluate("Array.from(studio.sites)")
        page.click("[data-act=play]")
        page.wait_for_function("studio.framesPlayed >= 4", timeout=60_000)
        page.click("[data-act=play]")  # pause
        _idle(page)
        assert page.evaluate("Array.from(studio.sites)") == sites  # seeds stay put
        assert "frame" in page.inner_text("[data-role=timeline]")
        assert page.evaluate("studio.cellPath(0)") == first  # the raw cell is the same...
        assert page.evaluate("studio.header.n") == len(sites) // 2
        _shot(page, "attractor-animation.png")
        assert not errors, errors
    finally:
        page.close()
        served.stop()
