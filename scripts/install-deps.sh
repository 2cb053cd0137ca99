#!/usr/bin/env bash
# Installs the Debian 12 packages palpate needs, skipping those already installed.
# Idempotent: a second run installs nothing and says so.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libcoin-dev libassimp-dev libgiftiio-dev libexpat1-dev zlib1g-dev
  libtomlplusplus-dev libcli11-dev libstb-dev libqhull-dev libmeshoptimizer-dev libvtk9-dev libcgal-dev libeigen3-dev
  libgdcm-dev libgdcm-tools mricron-data
  libepoxy-dev libglew-dev libegl-dev libegl1 libegl-mesa0 libgl1-mesa-dri libgl-dev libglfw3-dev libimgui-dev
  libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev
  xvfb xauth gnuplot-nox clang-format python3
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} Debian packages already installed"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
