#!/usr/bin/env bash
# Installs the Debian 12 packages pronk needs (run as root). Idempotent: does
# nothing when everything is already installed.
set -euo pipefail
pkgs=(cmake g++ make pkg-config libeigen3-dev libnlopt-cxx-dev coinor-libipopt-dev
      libcli11-dev nlohmann-json3-dev catch2 gnuplot-nox libopenmpi-dev openmpi-bin
      libsundials-dev libsuitesparse-dev libpagmo-dev)
# The Python module (pybind11 over Debian's python3) and what its tests and examples use.
pkgs+=(pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-scipy python3-matplotlib
       python3-optuna)
# `pip install .` (pyproject.toml: setuptools builds it, offline) and its test in a venv.
pkgs+=(python3-pip python3-venv python3-setuptools python3-wheel)
# The fuzzer needs clang 14 with its sanitizer runtimes; only the test job asks for it.
if [[ "${PRONK_WITH_FUZZ:-0}" == 1 ]]; then pkgs+=(clang-14 libclang-rt-14-dev); fi
# MuJoCo 2.2: the fourth fidelity, "model": "mujoco", and the MuJoCo peer of `pronk bench`
# (the CVODE peer uses the SUNDIALS installed above). pronk builds without it (CMake says so and
# such scenes are refused); PRONK_WITHOUT_MUJOCO=1 leaves it out.
if [[ "${PRONK_WITHOUT_MUJOCO:-0}" != 1 ]]; then pkgs+=(libmujoco-dev); fi
# The pages (view.html, report.html) and their browser test: Node, npm and Chromium; the test
# job (scripts/test.sh) asks for them. Node and npm may come from elsewhere (command found).
web=${PRONK_WITH_WEB:-0}
if [[ "$web" == 1 ]]; then
  pkgs+=(chromium)
  command -v node >/dev/null || pkgs+=(nodejs)
  command -v npm >/dev/null || pkgs+=(npm)
fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""; [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [[ "$web" == 1 ]]; then
  # The npm packages pinned by web/package-lock.json (three.js, uPlot; esbuild and
  # playwright-core) for the browser test and the check that the committed page templates
  # web/dist/*.html equal a fresh build (CTest web_templates). The templates are committed:
  # they are built here only if they are missing.
  dir=$(cd "$(dirname "$0")/../web" && pwd)
  if ! cmp -s "$dir/package-lock.json" "$dir/node_modules/.pronk-lock.json" 2>/dev/null; then
    (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
    cp "$dir/package-lock.json" "$dir/node_modules/.pronk-lock.json"
  fi
  [[ -f "$dir/dist/view.html" && -f "$dir/dist/report.html" ]] || node "$dir/build.mjs" >/dev/null
fi
