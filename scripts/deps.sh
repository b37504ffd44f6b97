# Sourced by scripts/run and scripts/test: installs the Debian 12 packages Sublift needs, only
# when some are missing (one dpkg query when all are there). Uses sudo when not root.
SUBLIFT_PACKAGES="build-essential cmake ninja-build pkg-config
  libglfw3-dev libimgui-dev libstb-dev libglm-dev libopenmesh-dev libtinygltf-dev
  nlohmann-json3-dev libosd-dev libeigen3-dev libepoxy-dev libegl-dev libgl-dev
  libopengl-dev libglx-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0
  libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth ccache"
# The fuzz build (docs/fuzzing.md), which is also the test suite's sanitizer build: clang with
# libFuzzer's runtime.
SUBLIFT_FUZZ_PACKAGES="clang-14 libclang-rt-14-dev"

# `sublift_install_deps tests` also brings Node.js for the test suite's glTF validator and
# clang for its sanitizer and fuzz phases; `sublift_install_deps fuzz` brings clang.
sublift_install_deps() {
  local missing="" packages="$SUBLIFT_PACKAGES"
  case "${1:-}" in tests|fuzz) packages="$packages $SUBLIFT_FUZZ_PACKAGES" ;; esac
  for p in $packages; do
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

# ccache, when installed, for every build: a rebuild after a small change or in a fresh build
# folder recompiles only what changed. CCACHE_BASEDIR lets worktrees of the repo share hits.
sublift_launcher_args() {
  if command -v ccache >/dev/null; then
    export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$SUBLIFT_ROOT")}"
    echo "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache"
  fi
}

# Configures build dir $1 (once) with extra cmake args $2..: Release, Ninja, ccache if installed.
sublift_configure() {
  local dir="$1"
  shift
  [ -f "$dir/build.ninja" ] && return 0
  # shellcheck disable=SC2046
  cmake -S "$SUBLIFT_ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release $(sublift_launcher_args) "$@"
}

# Configures (once) and builds build dir $1 with extra cmake args $3..; $2 is the target ("all").
sublift_build() {
  local dir="$1" target="$2"
  shift 2
  sublift_configure "$dir" "$@" || return 1
  sublift_launcher_args >/dev/null
  cmake --build "$dir" --target "$target" -j "$(nproc)"
}

# The fuzz build in dir $1, which is also the test suite's sanitizer build (docs/fuzzing.md):
# clang-14, ASan + UBSan everywhere, libFuzzer's coverage, no GUI, no benchmarks, only the tests
# of the sanitizer pass. Builds the targets $2.. ("all": those tests; "fuzz": the fuzz targets).
sublift_build_fuzz() {
  local dir="$1"
  shift
  sublift_configure "$dir" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14 -DSUBLIFT_FUZZ=ON \
    -DSUBLIFT_WITH_GUI=OFF -DSUBLIFT_WITH_BENCH=OFF -DSUBLIFT_TEST_SUBSET=sanitize || return 1
  sublift_launcher_args >/dev/null
  cmake --build "$dir" --target "$@" -j "$(nproc)"
}
