#!/bin/sh
# What CI runs for the browser front, from a clean clone on Debian 12: installs what is
# missing (web/build.sh --test: rustc-web, cargo-web, rust-web-src, lld-22, chromium, and
# playwright-core from web/package-lock.json), builds web/dist, builds the native command line
# the tests compare against, and runs the web crate's own tests (natively), the node test (the
# module against the CLI, byte for byte), the page's camera rules (page.test.mjs) and the
# browser test (the served page in headless chromium). Exits non-zero on any failure.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
web/build.sh --test
# the native reference (a no-op when .ci/run has built it already)
[ -n "${LANECAST_BIN:-}" ] || cargo build --release --bin lanecast
# the web crate's own tests (state, picking, shading), natively
cargo test --release -p lanecast-web
node --test --test-concurrency=1 web/tests/
