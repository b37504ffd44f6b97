# Sourced by scripts/run and scripts/test: installs the Debian 12 packages Sublift needs, only
# when some are missing (one dpkg query when all are there). Uses sudo when not root.
SUBLIFT_PACKAGES="build-essential cmake ninja-build pkg-config
  libglfw3-dev libimgui-dev libstb-dev libglm-dev libopenmesh-dev libtinygltf-dev
  nlohmann-json3-dev libosd-dev libeigen3-dev libepoxy-dev libegl-dev libgl-dev
  libopengl-dev libglx-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0
  libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth"

# `sublift_install_deps tests` also brings Node.js for the test suite's glTF validator.
sublift_install_deps() {
  local missing=""
  for p in $SUBLIFT_PACKAGES; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed"; then
      missing="$missing $p"
    fi
  done
  # Node.js runs the Khronos glTF validator in the tests (tests/gltf_validate.mjs); Debian 12's
  # nodejs + npm only for the tests and only when no node/npm is on the PATH already.
  if [ "${1:-}" = tests ] && { ! command -v node >/dev/null || ! command -v npm >/dev/null; }; then
    missing="$missing nodejs npm"
  fi
  [ -z "$missing" ] && return 0
  echo "sublift: installing missing packages:$missing"
  local sudo=""
  if [ "$(id -u)" != 0 ]; then
    command -v sudo >/dev/null || { echo "sublift: need root or sudo to install:$missing" >&2; return 1; }
    sudo="sudo"
  fi
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q || return 1
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $missing || return 1
}

# Configures (once) and builds build dir $1 with extra cmake args $3..; $2 is the target ("all").
sublift_build() {
  local dir="$1" target="$2"
  shift 2
  if [ ! -f "$dir/build.ninja" ]; then
    cmake -S "$SUBLIFT_ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" || return 1
  fi
  cmake --build "$dir" --target "$target" -j "$(nproc)"
}
