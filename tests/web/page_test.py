#!/usr/bin/env python3
"""The web page in a real browser (docs/web.md): headless chromium, driven by selenium, loads web/dist
served by `python3 -m http.server` on a free loopback port; the page must load without console
errors, and its settle() with zygomaticus_major_left at 1 and gravity off must move the left mouth
corner as `myoshell pose --set zygomaticus_major_left=1 --gravity off` does (its OBJ), to 1e-3 cm;
the shipped take (scenes/demo.json, packed into face.myoweb) must play to its end (the clock reaches
its duration) and its last frame must be `myoshell run scenes/demo.json`'s last frame, every vertex
within 1e-4 cm (the same ScenePlayer, the same steps); AU12 at 0.8 through the page's FACS path must
drive both zygomatici at 0.8 and settle to `pose --set zygomaticus_major_left=0.8 --set
zygomaticus_major_right=0.8 --gravity off`'s shape, every vertex within 1e-3 cm; a mouse grab of a
cheek vertex moved by δ must settle with that vertex moved by δ (the force is sized on the basis's
compliance, along the pull within 20 %), and the release must bring the face back.

The page's picture of that last frame (the native front view's camera, 600×600) and `myoshell render
scenes/demo.json --frames 150:150 --view front`'s must agree in silhouette: the intersection over
union of their non-background pixels at least 0.99.

usage: page_test.py DIST MYOSHELL SCENES [--screenshot PNG] [--figure PNG] [--measure]
Exit 77 (ctest's skip) with a message when chromium, chromedriver, selenium or emscripten are absent.
"""
import argparse
import json
import struct
import zlib
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

SKIP = 77


def skip(why):
    print(f"SKIPPED: {why}")
    sys.exit(SKIP)


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def obj_vertices(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                out.append([float(x) for x in line.split()[1:4]])
    return out


def read_png(data):
    """8-bit RGB or RGBA PNG bytes → (width, height, rows of bytes, channels)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 6), f"PNG depth {depth} colour type {colour}"
            ch = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), width * ch, [], bytearray(width * ch)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, rows, ch


def write_png(path, width, height, rows):
    """RGB rows (bytes of width·3) → a PNG file."""
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    chunk = lambda k, b: struct.pack(">I", len(b)) + k + b + struct.pack(">I", zlib.crc32(k + b) & 0xffffffff)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def silhouette(png):
    """The non-background pixels (off the corner pixel's colour, the flat background, by more than 8 of 255:
    the dark sides of both pictures are within 24 of it), and RGB rows."""
    w, h, rows, ch = png
    bg = rows[0][:3]
    mask = [[max(abs(r[x * ch + c] - bg[c]) for c in range(3)) > 8 for x in range(w)] for r in rows]
    rgb = [bytes(b for x in range(w) for b in r[x * ch:x * ch + 3]) for r in rows]
    return mask, rgb


def check_picture(browser, native_png, figure):
    """The page's picture of the shape it holds in the native front view's camera against the native
    render of the same frame: silhouettes' intersection over union."""
    native = read_png(native_png)
    size = native[0]
    browser.execute_script(f"window.myoshell.pictureView({size});")
    time.sleep(0.5)  # a few frames drawn at the new size
    canvas = browser.find_element("id", "canvas")
    page = read_png(canvas.screenshot_as_png)
    browser.execute_script("window.myoshell.pictureView(0);")
    if page[0] != size or page[1] != native[1]:
        print(f"FAILED: the page's picture is {page[0]}×{page[1]}, the native {native[0]}×{native[1]}")
        return False
    (pm, prgb), (nm, nrgb) = silhouette(page), silhouette(native)
    inter = sum(a and b for ra, rb in zip(pm, nm) for a, b in zip(ra, rb))
    union = sum(a or b for ra, rb in zip(pm, nm) for a, b in zip(ra, rb))
    iou = inter / max(union, 1)
    print(f"picture of the take's last frame, page vs `myoshell render --view front` ({size}×{native[1]}): "
          f"silhouette IoU {iou:.4f} ({union - inter} of {union} pixels differ)")
    if figure:
        write_png(figure, 2 * size + 8, native[1],
                  [pr + bytes([255, 255, 255]) * 8 + nr for pr, nr in zip(prgb, nrgb)])
        print(f"wrote {figure}")
    if not iou >= 0.99:
        print("FAILED: the page's silhouette and the native renderer's differ (IoU below 0.99)")
        return False
    return True


def all_vertices(browser, what="vertex"):
    return browser.execute_script(f"const m = window.myoshell, out = []; for (let i = 0; i < m.vertexCount; ++i) "
                                  f"out.push(m.{what}(i)); return out;")


def check_action_unit(browser, native, native_rest):
    """AU12 at 0.8 through the page's FACS path (the zygomaticus slider back at 0) against pose with both
    zygomatici at 0.8, settled with gravity off."""
    got = browser.execute_script("""
        const m = window.myoshell;
        m.setActivation('zygomaticus_major_left', 0);
        m.setActionUnit(12, 0.8);
        m.settle();
        const a = {left: m.activation('zygomaticus_major_left'), right: m.activation('zygomaticus_major_right'),
                   other: m.muscleNames.filter((n) => !n.startsWith('zygomaticus_major')).map((n) => m.activation(n))};
        return {a, aus: m.actionUnits.length};""")
    page = all_vertices(browser)
    browser.execute_script("window.myoshell.setActionUnit(12, 0);")
    ok = True
    a = got["a"]
    if not (a["left"] == 0.8 and a["right"] == 0.8 and max(a["other"]) == 0.0):
        print(f"FAILED: AU12 at 0.8 drives {a}, not the two zygomatici at 0.8")
        ok = False
    error = max(abs(p[c] - n[c]) for p, n in zip(page, native) for c in range(3))
    moved = max(sum((n[c] - r[c]) ** 2 for c in range(3)) ** 0.5 for n, r in zip(native, native_rest))
    print(f"AU12 0.8 ({got['aus']} action units offered): page vs pose with both zygomatici at 0.8, largest vertex "
          f"difference {error:.2e} cm (pose moves up to {moved:.3f} cm)")
    if not (moved > 0.1 and error <= 1e-3):
        print("FAILED: the AU's settled shape differs from pose's by more than 1e-3 cm (or pose barely moves)")
        ok = False
    return ok


def check_grab(browser, vertex=205, delta=(0.3, 0.2, 0.4)):
    """Grabs a cheek vertex, pulls it by delta (cm), settles (gravity off, nothing else on)."""
    got = browser.execute_script(f"""
        const m = window.myoshell;
        m.settle();
        const before = m.vertex({vertex});
        const seconds = m.grab({vertex});
        const force = m.moveGrab({delta[0]}, {delta[1]}, {delta[2]});
        m.settle();
        const after = m.vertex({vertex});
        return {{seconds, force, before, after}};""")
    pulled = all_vertices(browser)
    browser.execute_script("const m = window.myoshell; m.release(); m.settle();")
    unpulled = all_vertices(browser)
    released = browser.execute_script(f"return window.myoshell.vertex({vertex});")
    moved = [got["after"][c] - got["before"][c] for c in range(3)]
    length = sum(d * d for d in delta) ** 0.5
    size = sum(m * m for m in moved) ** 0.5
    cosine = sum(m * d for m, d in zip(moved, delta)) / (size * length)
    # What moved beyond the grip (1 cm at rest from the grabbed vertex): reported, not asserted (the
    # basis's response to a local force is not local: docs/web.md, "Mouse drag").
    rest = all_vertices(browser, "restVertex")
    settled = unpulled
    r0 = rest[vertex]
    far = max(sum((p[c] - q[c]) ** 2 for c in range(3)) ** 0.5 - 0.0
              for p, q, r in zip(pulled, settled, rest) if sum((r[c] - r0[c]) ** 2 for c in range(3)) > 1.0)
    back = max(abs(released[c] - got["before"][c]) for c in range(3))
    print(f"grab of vertex {vertex}: {got['seconds'] * 1000:.3f} ms, |f| {got['force']:.0f} dyn; pulled by {length:.3f} cm, "
          f"it moved {size:.3f} cm (cosine {cosine:.4f} with the pull); beyond the 1 cm grip the most any vertex moved "
          f"{far:.3f} cm; after the release {back:.1e} cm from where it was")
    ok = got["seconds"] >= 0 and cosine >= 0.95 and 0.8 * length <= size <= 1.2 * length and back <= 1e-9
    if not ok:
        print("FAILED: the grabbed vertex did not follow the pull (cosine 0.95, length within 20 %), or the release "
              "did not bring it back")
    return ok


def check_take(browser, native_end, speed=2.5):
    """Plays the shipped take in the page (at `speed` take seconds per wall second) to its end and
    compares its last frame with `myoshell run`'s."""
    start = browser.execute_script(f"""
        const m = window.myoshell;
        return {{takes: m.takes, duration: m.play('demo', {speed}), dt: 1 / 240}};""")
    t0 = time.time()
    duration = start["duration"]
    state = None
    while time.time() - t0 < 5 + duration / speed * 4:
        state = browser.execute_script("const m = window.myoshell; return {playing: m.playing, time: m.time, "
                                       "error: m.error};")
        if not state["playing"] or state["error"]:
            break
        time.sleep(0.05)
    wall = time.time() - t0
    ok = True
    print(f"take 'demo' ({start['takes']}): {duration} s played in {wall:.2f} s wall, clock {state['time']:.5f} s")
    if state["playing"] or state["error"]:
        print(f"FAILED: the take did not play to its end: {state}")
        return False
    if not abs(state["time"] - duration) <= 0.5 * start["dt"] + 1e-9:
        print(f"FAILED: the take stopped at {state['time']} s, not at its duration {duration} s")
        ok = False
    page_end = browser.execute_script("""
        const m = window.myoshell, out = [];
        for (let i = 0; i < m.vertexCount; ++i) out.push(m.vertex(i));
        return out;""")
    if len(page_end) != len(native_end):
        print(f"FAILED: the page has {len(page_end)} vertices, run's last frame {len(native_end)}")
        return False
    error = max(abs(p[c] - n[c]) for p, n in zip(page_end, native_end) for c in range(3))
    moved = max(sum((p[c] - r[c]) ** 2 for c in range(3)) ** 0.5
                for p, r in zip(page_end, browser.execute_script(
                    "const m = window.myoshell, out = []; for (let i = 0; i < m.vertexCount; ++i) "
                    "out.push(m.restVertex(i)); return out;")))
    print(f"take's last frame vs `myoshell run`'s: largest vertex difference {error:.2e} cm "
          f"(the face moved up to {moved:.3f} cm from rest)")
    if not (moved > 0.1):
        print("FAILED: the take's last frame barely moves the face: the comparison would prove nothing")
        ok = False
    if not (error <= 1e-4):
        print("FAILED: the take's last frame differs from run's by more than 1e-4 cm")
        ok = False
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dist")
    ap.add_argument("myoshell")
    ap.add_argument("scenes", help="the scenes folder (the shipped take, demo.json)")
    ap.add_argument("--screenshot", default="")
    ap.add_argument("--figure", default="", help="write the page's picture beside the native one (PNG)")
    ap.add_argument("--measure", action="store_true", help="print load time, steps/s, frame rate as JSON")
    a = ap.parse_args()

    chromium = shutil.which("chromium")
    driver = shutil.which("chromedriver")
    if not chromium:
        skip("chromium is not installed (scripts/setup --test installs it)")
    if not driver:
        skip("chromedriver is not installed (Debian's chromium-driver; scripts/setup --test)")
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
    except ImportError:
        skip("python3-selenium is not installed (scripts/setup --test)")
    if not shutil.which("emcc"):
        skip("emscripten is not installed: the page cannot be built (scripts/setup --web)")
    for f in ["index.html", "app.js", "favicon.svg", "myoshell_web.js", "myoshell_web.wasm", "face.myoweb"]:
        if not os.path.exists(os.path.join(a.dist, f)):
            print(f"FAILED: {a.dist}/{f} is missing: build the page with `make web`")
            return 1

    # The native shape first (the basis cache is the test's, MYOSHELL_CACHE).
    with tempfile.TemporaryDirectory() as tmp:
        obj = os.path.join(tmp, "pose.obj")
        rest = os.path.join(tmp, "rest.obj")
        subprocess.run([a.myoshell, "pose", "--set", "zygomaticus_major_left=1", "--gravity", "off", "--out", obj],
                       check=True, stdout=subprocess.DEVNULL)
        subprocess.run([a.myoshell, "pose", "--gravity", "off", "--out", rest], check=True, stdout=subprocess.DEVNULL)
        native = obj_vertices(obj)
        native_rest = obj_vertices(rest)
        au12 = os.path.join(tmp, "au12.obj")
        subprocess.run([a.myoshell, "pose", "--set", "zygomaticus_major_left=0.8", "--set", "zygomaticus_major_right=0.8",
                        "--gravity", "off", "--out", au12], check=True, stdout=subprocess.DEVNULL)
        native_au12 = obj_vertices(au12)
        # The take as `myoshell run` plays it: its last frame.
        run = os.path.join(tmp, "run")
        subprocess.run([a.myoshell, "run", os.path.join(a.scenes, "demo.json"), "--out", run, "--format", "obj"],
                       check=True, stdout=subprocess.DEVNULL)
        frames = sorted(os.listdir(os.path.join(run, "obj")))
        native_take_end = obj_vertices(os.path.join(run, "obj", frames[-1]))
        # The native picture of that frame.
        render = os.path.join(tmp, "render")
        subprocess.run([a.myoshell, "render", os.path.join(a.scenes, "demo.json"), "--out", render, "--frames",
                        f"{len(frames) - 1}:{len(frames) - 1}", "--view", "front", "--size", "600x600", "--sheet", "0"],
                       check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(render, "png", sorted(os.listdir(os.path.join(render, "png")))[-1]), "rb") as f:
            native_png = f.read()

    port = free_port()
    server = subprocess.Popen([sys.executable, "-m", "http.server", str(port), "--bind", "127.0.0.1", "-d", a.dist],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    browser = None
    try:
        opts = webdriver.ChromeOptions()
        opts.binary_location = chromium
        for arg in ["--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
                    "--window-size=1200,800"]:
            opts.add_argument(arg)
        opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
        for _ in range(50):  # the server is up when it accepts a connection
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
                break
            except OSError:
                time.sleep(0.1)
        browser = webdriver.Chrome(service=Service(driver), options=opts)
        browser.set_script_timeout(60)
        t0 = time.time()
        browser.get(f"http://127.0.0.1:{port}/index.html")
        state = None
        while time.time() - t0 < 60:
            state = browser.execute_script("return {ready: window.myoshell.ready, error: window.myoshell.error};")
            if state["ready"] or state["error"]:
                break
            time.sleep(0.1)
        wall_load = time.time() - t0
        if not state or not state["ready"]:
            print(f"FAILED: the page did not become ready in 60 s: {state}")
            return 1

        page = browser.execute_script("""
            const m = window.myoshell;
            m.setGravity(false);
            m.setActivation('zygomaticus_major_left', 1);
            const seconds = m.settle();
            const i = m.landmarkVertex('mouth_corner_left');
            return {i, seconds, p: m.vertex(i), rest: m.restVertex(i), load: m.loadSeconds, build: m.buildSeconds,
                    n: m.vertexCount};""")
        i = page["i"]
        moved_page = [page["p"][c] - page["rest"][c] for c in range(3)]
        moved_native = [native[i][c] - native_rest[i][c] for c in range(3)]
        error = max(abs(moved_page[c] - moved_native[c]) for c in range(3))
        length = sum(x * x for x in moved_native) ** 0.5
        print(f"left mouth corner (vertex {i}): page moved {moved_page}, pose moved {moved_native} "
              f"(|d| {length:.4f} cm), largest difference {error:.2e} cm")
        ok = True
        if page["n"] != len(native):
            print(f"FAILED: the page has {page['n']} vertices, pose's OBJ {len(native)}")
            ok = False
        if not (length > 0.1):
            print("FAILED: pose barely moves the mouth corner: the comparison would prove nothing")
            ok = False
        if not (error <= 1e-3):
            print("FAILED: the page's settled mouth corner differs from pose's by more than 1e-3 cm")
            ok = False

        ok = check_action_unit(browser, native_au12, native_rest) and ok
        ok = check_grab(browser) and ok
        ok = check_take(browser, native_take_end) and ok
        ok = check_picture(browser, native_png, a.figure) and ok

        measured = {"load_seconds_page": page["load"], "load_seconds_wall": wall_load,
                    "build_seconds": page["build"], "settle_seconds": page["seconds"]}
        if a.measure:
            bench = browser.execute_script("""
                const m = window.myoshell;
                m.setActivation('zygomaticus_major_left', 0.5);
                m.benchmark(20);
                return m.benchmark(400);""")
            # The frame loop's own figures (real time, drawing each frame), positions uploaded and then the
            # modes as morph targets on the GPU, each after 3 s (the counter's window is 1 s).
            for gpu in (False, True):
                browser.execute_script(f"window.myoshell.gpuMorph({'true' if gpu else 'false'}); "
                                       "window.myoshell.setActivation('zygomaticus_major_left', 0.5);")
                time.sleep(3)
                loop = browser.execute_script("return {fps: window.myoshell.framesPerSecond, "
                                              "steps: window.myoshell.stepsPerSecond};")
                key = "gpu_morph" if gpu else "positions_uploaded"
                measured.update({"steps_per_second_benchmark": bench, f"frames_per_second_{key}": loop["fps"],
                                 f"steps_per_second_in_loop_{key}": loop["steps"]})
            browser.execute_script("window.myoshell.gpuMorph(false);")
        if a.screenshot:
            browser.execute_script("window.myoshell.settle();")
            time.sleep(0.5)
            browser.save_screenshot(a.screenshot)
        print(json.dumps(measured))

        errors = [e for e in browser.get_log("browser") if e.get("level") == "SEVERE"]
        for e in errors:
            print(f"FAILED: console error: {e.get('message')}")
        ok = ok and not errors
        print("PASSED" if ok else "FAILED")
        return 0 if ok else 1
    finally:
        if browser:
            browser.quit()
        server.terminate()
        server.wait()


if __name__ == "__main__":
    sys.exit(main())
