#!/usr/bin/env bash
# Build the page into dist/: index.html, shadowlab.js and shadowlab_bg.wasm (eframe's web layout),
# with Cargo.toml's `web` profile (optimised for size, fat LTO; SHADOWLAB_WEB_PROFILE=web-test
# builds the faster one web/test.sh tests with).
# Serve dist/ over http (127.0.0.1 or https: WebGPU needs a secure context), e.g.
#   python3 -m http.server 8080 --bind 127.0.0.1 --directory dist
# Needs the wasm32-unknown-unknown target (rustup target add wasm32-unknown-unknown; or Debian's
# rustc-web, cargo-web, rust-web-src and lld, used with a standard library built here) and
# wasm-bindgen-cli at the version of wasm-bindgen in Cargo.lock. wasm-opt (binaryen), if found,
# shrinks the wasm; SHADOWLAB_WASM_OPT=0 skips it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
target=wasm32-unknown-unknown
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target-web}"
dist="$root/dist"
profile="${SHADOWLAB_WEB_PROFILE:-web}"

say() { printf 'web/build.sh: %s\n' "$*" >&2; }

bindgen_version="$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)"
if ! command -v wasm-bindgen >/dev/null || [ "$(wasm-bindgen --version | awk '{print $2}')" != "$bindgen_version" ]; then
    say "needs wasm-bindgen $bindgen_version (the version in Cargo.lock): cargo install wasm-bindgen-cli --version $bindgen_version"
    exit 2
fi

build=(rustc --lib --profile "$profile" --target "$target" --crate-type cdylib)
if command -v rustup >/dev/null && rustup target list --installed 2>/dev/null | grep -qx "$target"; then
    say "building with rustup's $target target"
    cargo "${build[@]}"
elif [ -x /usr/bin/rustc ] && [ -d /usr/lib/rustlib/src/rust/library ] && command -v wasm-ld >/dev/null; then
    # Debian's rustc-web knows the target but ships no standard library for it: build one.
    say "building with /usr/bin/rustc (Debian rustc-web) and a standard library built here"
    PATH="/usr/bin:$PATH" RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 \
        CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER=wasm-ld \
        /usr/bin/cargo "${build[@]}" -Zbuild-std=std,panic_abort
else
    say "no $target toolchain: rustup target add $target (or apt-get install rustc-web cargo-web rust-web-src lld)"
    exit 2
fi

rm -rf "$dist"
mkdir -p "$dist"
wasm-bindgen --target web --no-typescript --out-dir "$dist" --out-name shadowlab \
    "$CARGO_TARGET_DIR/$target/$profile/shadowlab.wasm"
cp web/index.html "$dist/index.html"
# The framework's libraries a student's page runs with (their Worker loads them from here; kept out
# of the wasm): the same files the desktop program includes.
mkdir -p "$dist/fonts"
cp assets/fonts/NotoSansCJKsc-Regular-subset.otf assets/fonts/OFL.txt "$dist/fonts/"
mkdir -p "$dist/homework/lib"
cp assets/homework/framework/lib/three.min.js assets/homework/framework/lib/three.LICENSE \
    assets/homework/framework/lib/gl-matrix-min.js "$dist/homework/lib/"

wasm="$dist/shadowlab_bg.wasm"
wasm_opt="$(command -v wasm-opt || true)"
[ -z "$wasm_opt" ] && [ -x web/node_modules/.bin/wasm-opt ] && wasm_opt=web/node_modules/.bin/wasm-opt
if [ "${SHADOWLAB_WASM_OPT:-1}" = 0 ]; then
    say "wasm-opt skipped (SHADOWLAB_WASM_OPT=0): the wasm is unshrunk"
elif [ -n "$wasm_opt" ]; then
    say "shrinking the wasm with $wasm_opt -Oz"
    "$wasm_opt" -Oz --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
        --enable-mutable-globals --enable-reference-types --enable-multivalue "$wasm" -o "$wasm.opt"
    mv "$wasm.opt" "$wasm"
else
    say "no wasm-opt found (npm install binaryen in web/, or apt-get install binaryen): the wasm is unshrunk"
fi
say "dist/: $(du -b "$wasm" | cut -f1) bytes of wasm, $(gzip -9c "$wasm" | wc -c) gzipped"
