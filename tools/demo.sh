#!/usr/bin/env bash
# The README's demo command: installs what is missing, then runs the simulated navigation demo headless
# (Flex Planner, TurtleBot 2, the paper's obstacle course). Extra arguments go to the demo (see --help).
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$REPO/tools/install.sh"
export PATH="$REPO/.venv/bin:$PATH"
export ROS_PACKAGE_PATH="$REPO${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}"
export ROS_IP=127.0.0.1
cd "$REPO"
exec "$REPO/.venv/bin/python" -m flex_nav.apps.nav_demo "$@"
