#!/usr/bin/env bash
# The page's tests: build dist/ for them, serve it on 127.0.0.1 and run web/test.mjs in headless
# Chromium (WebGPU and WebGL2 on SwiftShader). Needs what web/build.sh needs, Chromium and
# `npm ci` in web/ (playwright-core). Arguments go to web/test.mjs (e.g. --only webgl2).
# The build uses Cargo.toml's `web-test` profile (no fat LTO, no wasm-opt: quicker to build
# than the page that is published); SHADOWLAB_WEB_PROFILE=web tests that one instead.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

profile="${SHADOWLAB_WEB_PROFILE:-web-test}"
if [ "$profile" = web-test ]; then
    SHADOWLAB_WEB_PROFILE=web-test SHADOWLAB_WASM_OPT=0 bash web/build.sh
else
    SHADOWLAB_WEB_PROFILE="$profile" bash web/build.sh
fi

# A free port on 127.0.0.1 (a secure context: WebGPU is allowed there).
port="$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
python3 -m http.server "$port" --bind 127.0.0.1 --directory dist >/dev/null 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
for _ in $(seq 50); do
    python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/')" 2>/dev/null && break
    sleep 0.2
done
node web/test.mjs --url "http://127.0.0.1:$port/" --out "${SHADOWLAB_WEB_TEST_OUT:-$root/target/web-test}" "$@"
