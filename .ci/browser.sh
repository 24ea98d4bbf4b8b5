#!/bin/sh
# The browser tests (tests/browser) draw acphys view --html pages in headless Chromium. Install
# Debian's chromium when no Chromium is found and this can (root, with apt-get); otherwise say so.
# It never fails the chain: without a browser the tests skip, and under CI=true they fail, saying why.
if [ -n "$ACPHYS_CHROMIUM" ]; then
    echo "browser: ACPHYS_CHROMIUM=$ACPHYS_CHROMIUM"
    exit 0
fi
for name in chromium chromium-browser google-chrome google-chrome-stable; do
    if command -v "$name" >/dev/null 2>&1; then
        echo "browser: $(command -v "$name")"
        exit 0
    fi
done
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "browser: installing Debian's chromium (apt-get)"
    if apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null; then
        echo "browser: $(command -v chromium)"
    else
        echo "browser: could not install chromium; the browser tests will skip (and fail under CI=true)" >&2
    fi
else
    echo "browser: no Chromium and no way to install one here (needs root and apt-get):" \
        "the browser tests will skip (and fail under CI=true); install chromium to run them" >&2
fi
exit 0
