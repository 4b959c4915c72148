# Sourced by the scripts in this folder: paths and the ROS environment of Debian's ROS 1 (under /usr).
REPO_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# The catkin workspace sits beside the clone, never inside it (rosrun would walk into its symlink).
WS_DIR=${SEMANTIC_EDGE_VO_WS:-$(dirname "$REPO_DIR")/$(basename "$REPO_DIR")_ws}
SHARED_DIR=${SEMANTIC_EDGE_VO_SHARED:-$(cd "$REPO_DIR/.." && pwd)/shared}
# Debian's python3 must come first: a pyenv/venv python3 lacks catkin_pkg and rospy.
export PATH=/usr/bin:/bin:$PATH
export ROS_HOME=${ROS_HOME:-$WS_DIR/ros_home}
export ROS_HOSTNAME=${ROS_HOSTNAME:-localhost}
export SEMANTIC_EDGE_VO_SHARED=$SHARED_DIR

# Runs a command as root: directly when we are root, through sudo otherwise.
as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

# Sources the workspace (needed by roslaunch, rosrun and nodelet loading). Not under `set -u`.
source_workspace() {
  # shellcheck disable=SC1091
  source "$WS_DIR/devel/setup.bash"
}
