#!/usr/bin/env bash
# flex_nav installer: Debian's ROS Noetic packages, a venv from Debian's python3, exact pip pins
# and the generated action classes. Idempotent: a second run checks and changes nothing.
# Sourced by tools/demo.sh and tools/test.sh; can also be run on its own.
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="${FLEX_NAV_VENV:-$REPO/.venv}"   # override only for tests of the installer itself
APT_LOCK_TIMEOUT_S="${FLEX_NAV_APT_LOCK_TIMEOUT:-600}"   # [s] wait for another apt to release its lock

APT_PACKAGES=(
  python3-venv python3-rospy python3-roslaunch python3-rostest rosbash python3-rostopic python3-rosnode
  python3-rosbag python3-actionlib python3-tf2-ros python3-std-msgs python3-geometry-msgs python3-nav-msgs
  python3-sensor-msgs python3-std-srvs python3-genpy python3-genmsg python3-catkin-pkg libactionlib-msgs-dev
  ros-std-msgs ros-geometry-msgs ros-nav-msgs ros-actionlib-msgs ros-sensor-msgs ros-std-srvs
  python3-rosgraph-msgs python3-rosservice python3-roslib python3-rosmsg python3-tf2-msgs ros-tf2-msgs
  procps graphviz chromium chromium-driver
  rviz xvfb imagemagick python3-visualization-msgs ros-visualization-msgs tmux
  catkin ros-message-generation libgeometry-msgs-dev libnav-msgs-dev libstd-msgs-dev librostest-dev
)

say() { printf '[flex_nav install] %s\n' "$*"; }
die() {
  printf '\n[flex_nav install] ERROR: %s\n' "$1" >&2
  shift
  for line in "$@"; do printf '  %s\n' "$line" >&2; done
  exit 2
}

check_platform() {
  command -v apt-get >/dev/null 2>&1 && command -v dpkg-query >/dev/null 2>&1 ||
    die "this installer needs a Debian-based system with apt (ROS Noetic comes from Debian 12 'bookworm')." \
        "On another system install ROS Noetic yourself, then run: FLEX_NAV_SKIP_APT=1 $0"
}

missing_apt_packages() {
  local pkg status
  for pkg in "${APT_PACKAGES[@]}"; do
    status="$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)"
    [ "$status" = "installed" ] || printf '%s\n' "$pkg"
  done
}

install_apt() {
  if [ "${FLEX_NAV_SKIP_APT:-0}" = "1" ]; then say "apt: skipped (FLEX_NAV_SKIP_APT=1)"; return; fi
  check_platform
  local missing
  mapfile -t missing < <(missing_apt_packages)
  if [ "${#missing[@]}" -eq 0 ]; then say "apt: all ${#APT_PACKAGES[@]} ROS packages present"; return; fi
  say "apt: missing ${#missing[@]} package(s): ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
      sudo=(sudo -n)
    else
      die "installing Debian packages needs root, and this user ($(id -un)) is not root and has no password-less sudo." \
          "Ask an administrator to run once:" \
          "  sudo apt-get update && sudo apt-get install -y ${missing[*]}" \
          "then run this command again (it will skip the apt step)."
    fi
  fi
  local log
  log="$(mktemp)"
  local apt_opts=(-o "DPkg::Lock::Timeout=$APT_LOCK_TIMEOUT_S" -o Acquire::Retries=2 -q)
  say "apt: apt-get update (waits up to ${APT_LOCK_TIMEOUT_S} s for another apt's lock)"
  if ! "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get "${apt_opts[@]}" update >"$log" 2>&1 ||
       grep -qE '^(W|E): (Failed to fetch|Some index files failed)' "$log"; then
    explain_apt_failure "$log" "apt-get update"
  fi
  say "apt: apt-get install ${#missing[@]} package(s)"
  if ! "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get "${apt_opts[@]}" install -y --no-install-recommends \
       "${missing[@]}" >"$log" 2>&1; then
    explain_apt_failure "$log" "apt-get install"
  fi
  rm -f "$log"
  mapfile -t missing < <(missing_apt_packages)
  [ "${#missing[@]}" -eq 0 ] || die "apt finished but these packages are still not installed: ${missing[*]}"
}

explain_apt_failure() {
  local log="$1" what="$2"
  tail -n 15 "$log" >&2
  if grep -qiE 'could not get lock|unable to lock|is held by process|lock-frontend' "$log"; then
    die "$what: another package manager holds the apt lock (waited ${APT_LOCK_TIMEOUT_S} s)." \
        "Wait for it to finish (see: ps aux | grep -E 'apt|dpkg'), or raise the wait with FLEX_NAV_APT_LOCK_TIMEOUT=<seconds>," \
        "then run this command again."
  elif grep -qiE 'Temporary failure resolving|Could not resolve|Failed to fetch|Network is unreachable|Connection (refused|timed out)' "$log"; then
    die "$what: the Debian package mirror cannot be reached (no network?)." \
        "Connect this machine to the network (or to a local Debian mirror in /etc/apt/sources.list) and run this command again."
  elif grep -qiE 'Unable to locate package|has no installation candidate' "$log"; then
    die "$what: Debian does not offer one of the ROS packages on this release." \
        "flex_nav needs Debian 12 'bookworm' (or newer), whose 'main' carries ROS Noetic."
  fi
  die "$what failed; its last lines are above (full log: $log)."
}

make_venv() {
  local cfg="$VENV/pyvenv.cfg"
  if [ -x "$VENV/bin/python" ] && grep -q '^include-system-site-packages = true' "$cfg" 2>/dev/null &&
     [ "$(readlink -f "$VENV/bin/python")" = "$(readlink -f /usr/bin/python3)" ]; then
    say "venv: $VENV ok (Debian python3, system site packages)"
  else
    if [ -e "$VENV" ]; then say "venv: $VENV is not a Debian-python venv with system site packages; recreating"; rm -rf "$VENV"; fi
    say "venv: creating $VENV from /usr/bin/python3 --system-site-packages"
    /usr/bin/python3 -m venv --system-site-packages "$VENV" ||
      die "could not create the venv (is python3-venv installed?)."
  fi
}

pip_install() {
  local req="$REPO/requirements.txt" stamp="$VENV/.flex_nav-requirements.sha256"
  local want
  want="$(cat "$req" "$REPO/setup.py" | sha256sum | cut -d' ' -f1)"
  if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ] && "$VENV/bin/python" -c 'import flex_nav' 2>/dev/null; then
    say "pip: pinned requirements already installed"
    return
  fi
  say "pip: installing pinned requirements (requirements.txt)"
  local log
  log="$(mktemp)"
  if ! "$VENV/bin/python" -m pip install --disable-pip-version-check -q -r "$req" >"$log" 2>&1; then
    tail -n 15 "$log" >&2
    if grep -qiE 'CERTIFICATE_VERIFY_FAILED|SSLError' "$log"; then
      die "pip could not verify the package index's TLS certificate (a proxy with its own certificate authority?)." \
          "Point pip at the right CA bundle (PIP_CERT=/path/to/ca.pem or 'cert' in /etc/pip.conf) and run this command again."
    elif grep -qiE 'No matching distribution|Could not find a version|connection|resolve|Network' "$log"; then
      die "pip could not download the pinned packages (no network, or no access to the package index?)." \
          "Connect to PyPI (or set PIP_INDEX_URL to a mirror) and run this command again."
    fi
    die "pip install failed; its last lines are above (full log: $log)."
  fi
  # The package itself, editable, without touching the pins.
  if ! "$VENV/bin/python" -m pip install --disable-pip-version-check -q --no-deps --no-build-isolation -e "$REPO" >"$log" 2>&1; then
    tail -n 15 "$log" >&2
    die "pip install -e . failed; its last lines are above."
  fi
  rm -f "$log"
  printf '%s\n' "$want" >"$stamp"
}

generate_messages() {
  "$VENV/bin/python" "$REPO/tools/gen_actions.py" || die "generating the action classes failed (see above)."
}

warm_numba_cache() {
  # Compile the numba kernels once now, not in every planner/controller/localizer/mapper node started afterwards.
  local stamp="$VENV/.flex_nav-numba.sha256" want
  want="$({ find "$REPO/src/flex_nav/nav" "$REPO/src/flex_nav/localization" "$REPO/src/flex_nav/mapping" -name '*.py' |
    LC_ALL=C sort | xargs cat
    cat "$REPO/requirements.txt"; } | sha256sum | cut -d' ' -f1)"
  if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then say "numba: compiled kernels cached"; return; fi
  "$VENV/bin/python" -m flex_nav.nav.warm_cache || die "compiling the numba kernels failed (see above)."
  "$VENV/bin/python" -c 'from flex_nav.localization.localizer import warm_up
print(f"[flex_nav warm_cache] localizer kernels ready in {warm_up():.1f} s")' ||
    die "compiling the localizer's numba kernels failed (see above)."
  "$VENV/bin/python" -c 'from flex_nav.mapping.slam import warm_up
print(f"[flex_nav warm_cache] mapper kernels ready in {warm_up():.1f} s")' ||
    die "compiling the mapper's numba kernels failed (see above)."
  printf '%s\n' "$want" >"$stamp"
}

write_activate_hook() {
  # `source .venv/bin/activate` is the one line a user needs: it also puts this package on ROS_PACKAGE_PATH.
  local act="$VENV/bin/activate" marker="# flex_nav: package path"
  if ! grep -qF "$marker" "$act"; then
    cat >>"$act" <<HOOK

$marker
case ":\${ROS_PACKAGE_PATH:-}:" in *":$REPO:"*) ;; *) export ROS_PACKAGE_PATH="$REPO\${ROS_PACKAGE_PATH:+:\$ROS_PACKAGE_PATH}";; esac
HOOK
  fi
  # Debian's rostopic, rosmsg, rossrv and rosbag run /usr/bin/python3: they import flex_nav's message classes
  # from src/ (PYTHONPATH), and rosmsg finds the messages expanded from action/ (build/msg) in a catkin-style
  # share folder under the venv (CMAKE_PREFIX_PATH, marked by .catkin as catkin's devel space is).
  local share="$VENV/ros" tools_marker="# flex_nav: Debian's ROS tools"
  mkdir -p "$share/share/flex_nav"
  touch "$share/.catkin"
  ln -sfn "$REPO/build/msg" "$share/share/flex_nav/msg"
  if ! grep -qF "$tools_marker" "$act"; then
    cat >>"$act" <<HOOK
$tools_marker
case ":\${PYTHONPATH:-}:" in *":$REPO/src:"*) ;; *) export PYTHONPATH="$REPO/src\${PYTHONPATH:+:\$PYTHONPATH}";; esac
case ":\${CMAKE_PREFIX_PATH:-}:" in *":$share:"*) ;; *) export CMAKE_PREFIX_PATH="$share\${CMAKE_PREFIX_PATH:+:\$CMAKE_PREFIX_PATH}";; esac
HOOK
  fi
}

main() {
  install_apt
  make_venv
  generate_messages
  pip_install
  warm_numba_cache
  write_activate_hook
  say "ready. In a shell: source $VENV/bin/activate  (then rosrun/roslaunch/rostest find flex_nav)"
}

main "$@"
