#!/usr/bin/python3
"""Checks a study's report.html (compare/report_html.py) the way a reader meets it: in headless
Chromium (Debian's `chromium`), driven over the DevTools protocol on a pipe (--remote-debugging-pipe:
no port, no websocket library).

    /usr/bin/python3 tests/common/check_report.py [--screenshot PNG] REPORT_DIR...

For each folder: the page loads with no console error, no exception and no failed request (a
missing file, a blocked network load); every image is a data: URI that decoded; every src/href
(html.parser) is a data: URI or a file that exists beside the page; every value marked data-key
equals the value at that JSON pointer of summary.json (report.json for a calibration, front.json for a front) as its
data-format shows it (numbers to their 4 significant digits); the page shows no other number;
the keys a reader needs are there (every gated metric's value, limit and verdict, every warning,
the body and far-field errors with the reference's own error, every flag that is true).
Prints one line per folder; exit 1 on the first failure.
"""
import argparse
import base64
import html.parser
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--remote-debugging-pipe", "--window-size=1100,1400", "--hide-scrollbars"]
NUMBER = re.compile(r"(?<![\w.])[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w])")


class Browser:
    """Chromium with its DevTools protocol on descriptors 3 (commands) and 4 (replies)."""

    def __init__(self):
        self.profile = tempfile.mkdtemp(prefix="check_report_")
        to_child, self.commands = os.pipe()
        self.replies, from_child = os.pipe()

        def descriptors():
            os.dup2(to_child, 3)
            os.dup2(from_child, 4)

        self.process = subprocess.Popen(
            ["chromium", *FLAGS, f"--user-data-dir={self.profile}", "about:blank"], pass_fds=(3, 4),
            preexec_fn=descriptors, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_child)
        os.close(from_child)
        self.buffer = b""
        self.next_id = 0
        self.events = []
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.call(f"{domain}.enable", session=True)

    def message(self, deadline):
        while b"\0" not in self.buffer:
            if time.time() > deadline:
                raise RuntimeError("chromium did not answer within 60 s")
            chunk = os.read(self.replies, 1 << 16)
            if not chunk:
                raise RuntimeError("chromium ended")
            self.buffer += chunk
        text, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(text)

    def call(self, method, session=False, **params):
        self.next_id += 1
        request = {"id": self.next_id, "method": method, "params": params}
        if session:
            request["sessionId"] = self.session
        os.write(self.commands, json.dumps(request).encode() + b"\0")
        deadline = time.time() + 60
        while True:
            m = self.message(deadline)
            if m.get("id") == self.next_id:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m["result"]
            self.events.append(m)

    def wait_for(self, method):
        deadline = time.time() + 60
        while not any(e.get("method") == method for e in self.events):
            self.events.append(self.message(deadline))

    def evaluate(self, expression):
        r = self.call("Runtime.evaluate", session=True, expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"evaluate: {r['exceptionDetails']}")
        return r["result"]["value"]

    def close(self):
        self.process.kill()
        self.process.wait()
        os.close(self.commands)
        os.close(self.replies)
        shutil.rmtree(self.profile, ignore_errors=True)


def errors_of(events):
    """The console errors, exceptions and failed requests among the protocol's events."""
    out = []
    for e in events:
        method, p = e.get("method"), e.get("params", {})
        if method == "Runtime.exceptionThrown":
            out.append(f"exception: {p['exceptionDetails'].get('text')}")
        elif method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert", "warning"):
            out.append(f"console {p['type']}: {[a.get('value') for a in p.get('args', [])]}")
        elif method == "Log.entryAdded" and p["entry"]["level"] in ("error", "warning"):
            out.append(f"log {p['entry']['level']}: {p['entry']['text']} {p['entry'].get('url', '')}")
        elif method == "Network.loadingFailed":
            out.append(f"request failed: {p.get('errorText')} {p.get('blockedReason', '')}")
    return out


PAGE = r"""(() => {
  const marked = [...document.querySelectorAll('[data-key]')].map(e => [e.dataset.key, e.dataset.format, e.textContent]);
  const body = document.body.cloneNode(true);
  body.querySelectorAll('[data-key], [data-file], style').forEach(e => e.replaceWith(' '));
  const images = [...document.images].map(i => [i.getAttribute('src').slice(0, 30), i.complete && i.naturalWidth > 0]);
  return {marked, rest: body.textContent, images, title: document.title};
})()"""


class Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.refs = []

    def handle_starttag(self, tag, attrs):
        self.refs += [(tag, k, v) for k, v in attrs if k in ("src", "href")]


def lookup(data, pointer):
    value = data
    for part in pointer.split("/")[1:]:
        part = part.replace("~1", "/").replace("~0", "~")
        value = value[int(part)] if isinstance(value, list) else value[part]
    return value


def check_value(value, fmt, text):
    """None if `text` shows `value` in format `fmt`, else what is wrong."""
    if fmt == "num":
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return f"{value!r} is not a number"
        shown = float(text)
        if isinstance(value, int):
            return None if shown == value else f"shows {text}, JSON {value}"
        return None if abs(shown - value) <= 5e-4 * abs(value) + 1e-300 else f"shows {text}, JSON {value!r}"
    expected = {"text": lambda: str(value), "list": lambda: ", ".join(map(str, value)),
                "pass": lambda: "ok" if value is True else "EXCEEDED" if value is False else None,
                "flag": lambda: text if value is True else None,
                "modelled": lambda: "modelled" if value is True else "not modelled" if value is False else None}[fmt]()
    return None if expected == text else f"shows {text!r}, JSON {value!r}"


def required(data):
    """JSON pointers the page must show."""
    keys = [f"/warnings/{i}" for i in range(len(data.get("warnings", [])))]
    if data.get("model") == "front":  # every point's time and headline errors, the case point's verdicts
        keys += ["/gate/checked", "/case_point", "/reference/dofs"]
        for i, p in enumerate(data["points"]):
            keys += [f"/points/{i}/label", f"/points/{i}/seconds/min", f"/points/{i}/seconds/median"]
            keys += [f"/points/{i}/errors/{m}" for m in data["headline"]]
        keys += [f"/reference/errors/{v['metric']}" for v in data["verdicts"] if v["point"] == data["case_point"]]
        keys += [f"/skipped/{i}" for i in range(len(data["skipped"]))]
        return keys
    if "metrics" not in data:  # a calibration: every coefficient it sets, every case's (and held-out case's) errors
        keys += ["/objective/start", "/objective/fitted"]
        keys += [f"/fitted/{k}" for k in data["coefficients_used"]]
        for group in ("cases", "held_out"):
            for c, entry in data.get(group, {}).items():
                keys += [f"/{group}/{c}/{w}/{f}" for w in ("before", "after") for f in data["fields"]
                         if entry[w].get(f) is not None]
                keys += [f"/{group}/{c}/threshold/coefficient", f"/{group}/{c}/threshold/fitted"]
        return keys
    keys += ["/gate/checked"]
    for name, m in data["metrics"].items():
        esc = name.replace("~", "~0").replace("/", "~1")
        if "limit" in m:  # a component the rule set does not model is not gated: no verdict
            keys += [f"/metrics/{esc}/value", f"/metrics/{esc}/limit"]
            keys += [f"/metrics/{esc}/passed" if "passed" in m else f"/metrics/{esc}/modelled"]
        if m.get("modelled") is False:
            keys.append(f"/metrics/{esc}/modelled")
        keys += [f"/metrics/{esc}/{k}" for k, v in m.items() if isinstance(v, bool) and k != "passed" and v]
    if data.get("model") == "agent":  # every compared field's errors, the threshold in effect
        keys += ["/unresolved_reference_error", "/agent/threshold/gamma_in_effect"]
        for scope in ("body", "far"):
            for f in data["fields"]:
                keys += [f"/metrics/{scope}.{f}.rel_l2/value", f"/metrics/{scope}.{f}.rel_l2/reference_error"]
                if "agents_only" in data["metrics"][f"{scope}.{f}.rel_l2"]:
                    keys.append(f"/metrics/{scope}.{f}.rel_l2/agents_only")
        keys += ["/agent/applied", "/agent/rigid_reaction", "/agent/lost", "/agent/rule_set"]
        keys += [f"/agent/coefficients/{c}" for c in data["agent"]["coefficients_used"]]
        keys += [f"/loads/{i}/force" for i in range(len(data["loads"]))]
    return keys


def check(browser, folder, screenshot):
    page = os.path.abspath(os.path.join(folder, "report.html"))
    if not os.path.isfile(page):
        return ["no report.html"]
    sources = [os.path.join(folder, n) for n in ("summary.json", "report.json", "front.json")]
    source = next((s for s in sources if os.path.exists(s)), sources[1])
    with open(source) as f:
        data = json.load(f)
    problems = []
    # Every reference resolves without a network: a data: URI or a file beside the page.
    parser = Links()
    with open(page, encoding="utf-8") as f:
        parser.feed(f.read())
    for tag, attr, ref in parser.refs:
        if ref.startswith("data:"):
            header, payload = ref.split(",", 1)
            try:
                base64.b64decode(payload, validate=True)
            except ValueError:
                problems.append(f"<{tag} {attr}>: a data: URI that does not decode")
        elif re.match(r"^[a-z]+:", ref) or ref.startswith("/"):
            problems.append(f"<{tag} {attr}={ref!r}>: not a file beside the page")
        elif not os.path.isfile(os.path.join(folder, ref)):
            problems.append(f"<{tag} {attr}={ref!r}>: no such file")
    # The page in the browser.
    browser.events.clear()
    browser.call("Page.navigate", session=True, url="file://" + page)
    browser.wait_for("Page.loadEventFired")
    shown = browser.evaluate(PAGE)
    time.sleep(0.3)  # late console messages
    browser.call("Runtime.evaluate", session=True, expression="0")
    problems += errors_of(browser.events)
    for src, loaded in shown["images"]:
        if not src.startswith("data:image/") or not loaded:
            problems.append(f"image {src}...: not an embedded image that loaded")
    seen = set()
    for key, fmt, text in shown["marked"]:
        seen.add(key)
        try:
            why = check_value(lookup(data, key), fmt, text.strip())
        except (KeyError, IndexError, ValueError) as e:
            why = f"not in {os.path.basename(source)} or not a number ({e})"
        if why:
            problems.append(f"{key}: {why}")
    stray = NUMBER.findall(shown["rest"])
    if stray:
        problems.append(f"numbers shown that are not summary values: {stray[:10]}")
    missing = [k for k in required(data) if k not in seen]
    if missing:
        problems.append(f"not on the page: {missing[:10]}")
    if screenshot:
        shot = browser.call("Page.captureScreenshot", session=True, format="png")
        with open(screenshot, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
    if not problems:
        print(f"{page}: ok ({len(shown['marked'])} values, {len(shown['images'])} images, {len(parser.refs)} links)")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--screenshot", help="also save the first page's screenshot here (PNG)")
    args = ap.parse_args()
    browser = Browser()
    try:
        for i, folder in enumerate(args.folders):
            problems = check(browser, folder, args.screenshot if i == 0 else None)
            if problems:
                print(f"{folder}/report.html: FAILED: " + "; ".join(problems))
                return 1
    finally:
        browser.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
