#!/bin/sh
# Builds lanecast's browser front into web/dist/ (static files: serve them with any static
# server, e.g. `python3 -m http.server -d web/dist 8000`).
#
# Installs what is missing first (Debian 12): rustc-web and cargo-web (/usr/bin/rustc and
# /usr/bin/cargo 1.96, which build the wasm32 standard library from rust-web-src), lld-22
# (wasm-ld-22). `--test` also installs what the tests need: chromium, and web/node_modules from
# web/package-lock.json (playwright-core, which drives Debian's chromium).
#
# Usage: web/build.sh [--test] [--no-install]
set -eu

web=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$web")
test_deps=0
install=1
for a in "$@"; do
    case "$a" in
    --test) test_deps=1 ;;
    --no-install) install=0 ;;
    *) echo "usage: web/build.sh [--test] [--no-install]" >&2; exit 2 ;;
    esac
done

# --- what is missing ------------------------------------------------------------------------
need=""
for p in rustc-web cargo-web rust-web-src lld-22; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || need="$need $p"
done
if [ "$test_deps" = 1 ]; then
    dpkg-query -W -f='${Status}' chromium 2>/dev/null | grep -q "ok installed" || need="$need chromium"
fi
if [ -n "$need" ]; then
    if [ "$install" = 0 ]; then
        echo "web/build.sh: missing Debian packages:$need" >&2
        exit 1
    fi
    echo "web/build.sh: installing$need"
    sudo=""
    [ "$(id -u)" = 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $need
fi
if [ "$test_deps" = 1 ] && [ ! -d "$web/node_modules/playwright-core" ]; then
    command -v npm >/dev/null || { echo "web/build.sh: npm (node 20) is needed for the tests" >&2; exit 1; }
    (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
fi

# --- the module -----------------------------------------------------------------------------
# Debian's compiler and cargo (not rustup's, whose toolchain has no wasm32 std), the standard
# library built from source with SIMD128 on, in a target folder of its own.
cd "$root"
RUSTC_BOOTSTRAP=1 RUSTC=/usr/bin/rustc \
    CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER=wasm-ld-22 \
    RUSTFLAGS="-C target-feature=+simd128" \
    /usr/bin/cargo build --release --target wasm32-unknown-unknown \
    -Zbuild-std=std,panic_abort -p lanecast-web --target-dir target/web

# --- the static files -----------------------------------------------------------------------
dist="$web/dist"
rm -rf "$dist"
mkdir -p "$dist/scenes/meshes"
cp "$web"/www/* "$dist/"
cp target/web/wasm32-unknown-unknown/release/lanecast_web.wasm "$dist/lanecast.wasm"
# the menu: the seed scenes and the mesh scenes, with the meshes they name
menu="$dist/scenes/menu.json"
printf '[' >"$menu"
sep=""
for f in scenes/scene[1-7].sc scenes/bunny.sc scenes/teapot.sc scenes/armadillo.sc; do
    [ -f "$f" ] || continue
    cp "$f" "$dist/scenes/"
    meshes=""
    msep=""
    for m in $(sed -n 's/^[[:space:]]*mesh[[:space:]]\{1,\}\([^#[:space:]]*\).*/\1/p' "$f"); do
        cp "scenes/$m" "$dist/scenes/$m"
        meshes="$meshes$msep\"$m\""
        msep=","
    done
    printf '%s{"name":"%s","file":"%s","meshes":[%s]}' "$sep" "$(basename "$f" .sc)" "$(basename "$f")" "$meshes" >>"$menu"
    sep=","
done
printf ']\n' >>"$menu"
echo "web/build.sh: built $dist ($(du -sh "$dist" | cut -f1)); serve it with: python3 -m http.server -d web/dist 8000"
