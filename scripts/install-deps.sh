#!/usr/bin/env bash
# Installs the Debian 12 packages ReamSim needs, only those that are missing. Idempotent.
# As root it calls apt-get directly; otherwise through sudo.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config ccache
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev libtbb-dev
  libvtk9-dev libvtk9-qt-dev qtbase5-dev libqt5opengl5-dev
  libopenmesh-dev libhidapi-dev nlohmann-json3-dev
  libvtk-dicom-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libgoogle-perftools-dev
  xvfb xauth
  locales
)

# A decimal-comma locale for the tests that check files are written the same whatever the user's locale
# (Qt sets the C library's locale from the environment; the tests named "...InADecimalCommaLocale").
ensure_test_locale() {
  if ! locale -a 2>/dev/null | grep -qi '^de_DE\.utf-\?8$'; then
    echo "install-deps: generating the de_DE.UTF-8 locale for the tests"
    $SUDO localedef -i de_DE -f UTF-8 de_DE.UTF-8
  fi
}
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  ensure_test_locale
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq "${missing[@]}"
ensure_test_locale
