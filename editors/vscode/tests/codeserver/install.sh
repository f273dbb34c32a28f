#!/usr/bin/env bash
# Installs what tests/editors/test_vscode_codeserver.py needs to run the extension in a real VS Code:
# code-server 4.100.3 (VS Code 1.100 served to a browser; the last release that runs on Node 20),
# Debian's Chromium, and Playwright for Python (driving that Chromium, no browser download) into
# the virtual environment given as $1 (default: the repository's .venv).
#
# code-server's own postinstall cannot run here: @vscode/ripgrep downloads its binary from GitHub
# and node-pty fetches node-gyp through npx, and only the npm registry and Debian are reachable.
# So the package is installed with --ignore-scripts and its postinstall is done step by step:
# Debian's ripgrep stands in for the download, the native modules (kerberos, node-pty, spdlog,
# @parcel/watcher, argon2, ...) are built from source against the installed Node's headers.
# Idempotent: a finished install is kept (node_modules/.mcc-installed) and the script returns.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../../../.." && pwd)"
python="${1:-$repo/.venv/bin/python}"

packages=(chromium ripgrep g++ make pkg-config python3 libkrb5-dev libx11-dev libxkbfile-dev libsecret-1-dev)
missing=()
for package in "${packages[@]}"; do
    dpkg -s "$package" > /dev/null 2>&1 || missing+=("$package")
done
if [ "${#missing[@]}" -gt 0 ]; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" > /dev/null
fi

"$python" -m pip install --quiet "playwright>=1.40,<2"

# code-server 4.100.3 runs on Node.js 20 only. Where the machine has another (Debian 12's nodejs is
# 18), Node.js 20 comes from the npm registry's node-linux-<arch> package, which ships the binary and
# the headers the native modules are built against; the test runs code-server with it (node20/).
node_major="$(node -p 'process.versions.node.split(".")[0]' 2>/dev/null || echo none)"
if [ "$node_major" != 20 ] || [ -n "${MCC_NODE20_FROM_NPM:-}" ]; then
    case "$(uname -m)" in
        x86_64) arch=x64 ;;
        aarch64) arch=arm64 ;;
        *) echo "install.sh: no Node.js 20 package for $(uname -m); install Node.js 20" >&2; exit 1 ;;
    esac
    node20="$here/node20/node_modules/node-linux-$arch"
    if [ ! -x "$node20/bin/node" ]; then
        npm install --prefix "$here/node20" --no-save --no-audit --no-fund --loglevel=error "node-linux-$arch@20"
    fi
    export PATH="$node20/bin:$PATH" npm_config_nodedir="$node20"
fi

stamp="$here/node_modules/.mcc-installed"
if [ -f "$stamp" ]; then
    exit 0
fi
cd "$here"
npm ci --ignore-scripts --no-audit --no-fund --loglevel=error
npm_config_build_from_source=true npm rebuild argon2 --loglevel=error > /dev/null

cd "$here/node_modules/code-server/lib/vscode"
npm install --omit=dev --ignore-scripts --no-audit --no-fund --loglevel=error
mkdir -p node_modules/@vscode/ripgrep/bin           # its postinstall skips the download when bin/ exists
ln -sf "$(command -v rg)" node_modules/@vscode/ripgrep/bin/rg
npm_config_yes=true npm rebuild --loglevel=error > /dev/null
# the rest of code-server's postinstall.sh (vscode_install), for Linux
ln -sfn node_modules node_modules.asar
ln -sf code-linux.sh bin/remote-cli/code-server
ln -sf browser-linux.sh bin/helpers/browser.sh
(cd extensions && npm install --omit=dev --no-audit --no-fund --loglevel=error > /dev/null)

XDG_CONFIG_HOME="$(mktemp -d)" node "$here/node_modules/code-server/out/node/entry.js" --version > /dev/null
touch "$stamp"
