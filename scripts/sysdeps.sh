#!/usr/bin/env bash
# Install the Debian packages betvdesign needs, when missing and when root.
#   runtime: pango (WeasyPrint PDF rendering) and fonts
#   test:    runtime + chromium (browser test of the HTML report) + poppler-utils (PDF tests)
set -euo pipefail
what="${1:-test}"
pkgs=()
have_lib() { ldconfig -p 2>/dev/null | grep -q "$1"; }
have_lib libpango-1.0.so.0 || pkgs+=(libpango-1.0-0)
have_lib libpangoft2-1.0.so.0 || pkgs+=(libpangoft2-1.0-0)
fc-list 2>/dev/null | grep -qi dejavu || pkgs+=(fonts-dejavu-core fontconfig)
if [[ "$what" == "test" ]]; then
    command -v chromium >/dev/null || pkgs+=(chromium)
    command -v pdfinfo >/dev/null || pkgs+=(poppler-utils)
fi
if ((${#pkgs[@]} == 0)); then
    exit 0
fi
if [[ "$(id -u)" == "0" ]] && command -v apt-get >/dev/null; then
    echo "sysdeps: installing ${pkgs[*]}" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${pkgs[@]}" >/dev/null
else
    echo "sysdeps: missing ${pkgs[*]} (not root: install them with apt-get; dependent tests will skip)" >&2
fi
