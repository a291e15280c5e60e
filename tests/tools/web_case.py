#!/usr/bin/env python3
"""Runs one scripted case of clpc's browser page in headless Chromium.

    web_case.py SITE_DIR CL_FILE MACHINE OUT_DIR [SCREENSHOT.png]

Copies the built page (SITE_DIR: index.html, app.js, clpc.js, clpc.wasm) and the CL file
into a scratch folder, serves it on 127.0.0.1 (Python's http.server, a plain static server),
opens index.html?case=FILE&machine=MACHINE in headless Chromium and writes what the page
shows into OUT_DIR: gcode.nc (#gcode), log.txt (#log, clpc's standard error), certificate.txt,
diagnostics.txt (one line per clickable diagnostic: its CL line, a tab, its text) and state.txt
(the page's data-state: "done" when the case ran); with SCREENSHOT.png, a second run draws
the page into it (1400 x 1500 pixels: the README's picture). Exits 1 when Chromium fails.
"""
import functools
import html
import http.server
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def element(dom, tag, ident):
    m = re.search(r'<%s id="%s"[^>]*>(.*?)</%s>' % (tag, ident, tag), dom, re.S)
    return html.unescape(m.group(1)) if m else ""


def main(argv):
    site, cl_file, machine, out = argv[1:5]
    os.makedirs(out, exist_ok=True)
    with tempfile.TemporaryDirectory() as root:
        for name in os.listdir(site):
            if os.path.isfile(os.path.join(site, name)):
                shutil.copy(os.path.join(site, name), root)
        os.makedirs(os.path.join(root, "cases"))
        shutil.copy(cl_file, os.path.join(root, "cases"))
        handler = functools.partial(QuietHandler, directory=root)
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        url = "http://127.0.0.1:%d/index.html?case=cases/%s&machine=%s" % (
            server.server_address[1], os.path.basename(cl_file), machine)
        profile = os.path.join(root, "profile")
        chromium = ["timeout", "180", "chromium", "--headless", "--no-sandbox", "--disable-gpu",
                    "--user-data-dir=" + profile, "--virtual-time-budget=60000"]
        run = subprocess.run(chromium + ["--dump-dom", url], capture_output=True, text=True,
                             env=dict(os.environ, HOME=root))
        if len(argv) > 5 and run.returncode == 0:
            shot = subprocess.run(chromium + ["--hide-scrollbars", "--window-size=1400,1500",
                                              "--screenshot=" + os.path.abspath(argv[5]), url],
                                  capture_output=True, text=True, env=dict(os.environ, HOME=root))
            if shot.returncode != 0:
                run = shot
        server.shutdown()
    if run.returncode != 0:
        sys.stderr.write(run.stderr)
        return 1
    dom = run.stdout
    state = re.search(r'<body data-state="([a-z]*)"', dom)
    with open(os.path.join(out, "state.txt"), "w") as f:
        f.write(state.group(1) if state else "")
    with open(os.path.join(out, "gcode.nc"), "w") as f:
        f.write(element(dom, "pre", "gcode"))
    with open(os.path.join(out, "log.txt"), "w") as f:
        f.write(element(dom, "pre", "log"))
    with open(os.path.join(out, "certificate.txt"), "w") as f:
        f.write(element(dom, "p", "certificate"))
    with open(os.path.join(out, "diagnostics.txt"), "w") as f:
        for line, text in re.findall(r'<li class="[a-z]+" data-line="(\d+)">(.*?)</li>', dom, re.S):
            f.write(line + "\t" + html.unescape(text).split("\n")[0] + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
