#!/usr/bin/env python3
"""web_serve.py - serve the web page (make web) on 127.0.0.1.

    python3 tests/web_serve.py DIR [PORT [REPORT]]

Serves DIR (GET; .wasm as application/wasm, nothing cached) on
127.0.0.1:PORT (0, the default: any free port) and prints the URL of
DIR/index.html on its first line. POST /report writes the request's body
into the file REPORT (make web-bench: the page posts its figures there),
and GET /wait answers once REPORT exists (the page's load waits on it).
Runs until it is killed. Python's standard library only."""
import http.server
import os
import sys
import time


def main():
    if len(sys.argv) < 2 or not os.path.isdir(sys.argv[1]):
        sys.stderr.write(__doc__)
        return 2
    root = os.path.abspath(sys.argv[1])
    port = int(sys.argv[2]) if len(sys.argv) > 2 else 0
    report = os.path.abspath(sys.argv[3]) if len(sys.argv) > 3 else None

    class Handler(http.server.SimpleHTTPRequestHandler):
        extensions_map = dict(
            http.server.SimpleHTTPRequestHandler.extensions_map,
            **{".wasm": "application/wasm", ".js": "text/javascript"})

        def __init__(self, *args, **kwargs):
            super().__init__(*args, directory=root, **kwargs)

        def end_headers(self):
            self.send_header("Cache-Control", "no-store")
            super().end_headers()

        def do_GET(self):
            # the bench's page holds its load event on this until its
            # report is in (or 10 minutes have passed)
            if self.path == "/wait" and report:
                for _ in range(6000):
                    if os.path.exists(report):
                        break
                    time.sleep(0.1)
                body = b"/* the report is in */\n"
                self.send_response(200)
                self.send_header("Content-Type", "text/javascript")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)
                return
            super().do_GET()

        def do_POST(self):
            if self.path != "/report" or not report:
                self.send_error(404)
                return
            body = self.rfile.read(int(self.headers.get("Content-Length", 0)))
            with open(report + ".part", "wb") as f:
                f.write(body)
            os.replace(report + ".part", report)
            self.send_response(204)
            self.end_headers()

        def log_message(self, fmt, *args):
            pass  # quiet: the checks print what matters

    server = http.server.ThreadingHTTPServer(("127.0.0.1", port), Handler)
    print("http://127.0.0.1:%d/index.html" % server.server_address[1],
          flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
