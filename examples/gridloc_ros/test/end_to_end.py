#!/usr/bin/python3
"""End-to-end test of gridloc_ros (issue 18; ctest label `ros`).

Starts roscore on a free loopback port, then the node three times: with the bundled
wheelchair's sonar ring from its file (a map on `map`, an `initialpose`, one firing as 14
`sensor_msgs/Range`, then `~localize`), the same ring from tf (`~sonar_frames`, the mounts
base_link -> sonar_i on /tf_static), and with a laser (`global_localization`, one
`sensor_msgs/LaserScan`, then `~localize`). Each sonar answer must be `localized` within 10 cm
and 7 degrees of the truth, and the map -> odom transform must be on tf. The laser's one scan
from no prior is a guess the drive must bear out (`~settle_first`): its answer is
`not localized`, with the pose within 10 cm and 7 degrees. Readings come from `gridloc simulate`. Everything started
is stopped. Exits 77 (ctest: skipped) when ROS 1 is not installed.
"""
import argparse
import json
import math
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time


def skip(why):
    print(f"SKIP: {why}")
    sys.exit(77)


try:
    import rospy
    from geometry_msgs.msg import PoseWithCovarianceStamped, TransformStamped
    from nav_msgs.msg import OccupancyGrid
    from sensor_msgs.msg import LaserScan, Range
    from std_srvs.srv import Empty, Trigger
    from tf2_msgs.msg import TFMessage
except ImportError as error:
    skip(f"ROS 1's Python packages are not installed ({error}); cmake/quickstart.sh test installs them")
if shutil.which("roscore") is None:
    skip("roscore is not installed (Debian: ros-core-dev / python3-roslaunch)")

TRUTH = (2.0, 1.5, 0.3)  # in the furnished room, clear of the furniture


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def read_map(yaml_path):
    """A map_server YAML and its PGM as a latched OccupancyGrid (trinary)."""
    fields = {}
    for line in open(yaml_path):
        line = line.split("#", 1)[0].strip()
        if ":" in line:
            key, value = line.split(":", 1)
            fields[key.strip()] = value.strip()
    image = os.path.join(os.path.dirname(yaml_path), fields["image"])
    data = open(image, "rb").read()
    tokens, pos = [], 0
    while len(tokens) < 4:  # P5 width height maxval, comments allowed
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        tokens.append(data[pos:end])
        pos = end
    width, height, maxval = int(tokens[1]), int(tokens[2]), int(tokens[3])
    pixels = data[pos + 1:pos + 1 + width * height]
    negate = int(fields.get("negate", "0"))
    occupied, free = float(fields.get("occupied_thresh", "0.65")), float(fields.get("free_thresh", "0.196"))
    grid = OccupancyGrid()
    grid.header.frame_id = "map"
    grid.info.resolution = float(fields["resolution"])
    grid.info.width, grid.info.height = width, height
    origin = [float(v) for v in fields["origin"].strip("[]").split(",")]
    grid.info.origin.position.x, grid.info.origin.position.y = origin[0], origin[1]
    grid.info.origin.orientation.z = math.sin(origin[2] / 2)
    grid.info.origin.orientation.w = math.cos(origin[2] / 2)
    cells = []
    for row in range(height - 1, -1, -1):  # the image's top row is the grid's last
        for col in range(width):
            p = pixels[row * width + col] / maxval
            occ = p if negate else 1.0 - p
            cells.append(100 if occ > occupied else 0 if occ < free else -1)
    grid.data = cells
    return grid


class Run:
    """roscore and the node, stopped on exit."""

    def __init__(self, workdir):
        self.port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{self.port}",
                        ROS_HOSTNAME="127.0.0.1", ROS_HOME=workdir, ROS_LOG_DIR=workdir)
        self.workdir = workdir
        self.processes = []

    def start(self, command, name):
        log = open(os.path.join(self.workdir, name + ".log"), "w")
        p = subprocess.Popen(command, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                             start_new_session=True)
        self.processes.append((p, name))
        return p

    def stop(self, process):
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGINT)
            try:
                process.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()

    def stop_all(self):
        for p, _ in reversed(self.processes):
            self.stop(p)

    def log(self, name):
        path = os.path.join(self.workdir, name + ".log")
        return open(path).read() if os.path.exists(path) else ""


def wait_for(what, check, timeout=30.0):
    deadline = time.time() + timeout
    while time.time() < deadline:
        value = check()
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"timed out waiting for {what}")


def localize_until_ready(localize, not_ready):
    """Calls ~localize until the node has what it needs; returns its answer."""
    def ready():
        answer = localize()
        return answer if answer.message not in not_ready else None
    return wait_for("the node to be ready", ready)


def right_pose(answer, label, verdict):
    """The answer's JSON pose, checked: `verdict`, within 10 cm and 7 degrees of the truth."""
    pose = json.loads(answer.message)
    off_m = math.hypot(pose["x"] - TRUTH[0], pose["y"] - TRUTH[1])
    off_deg = abs(math.degrees(math.remainder(pose["theta"] - TRUTH[2], 2 * math.pi)))
    assert pose["verdict"] == verdict, f"{label}: {pose}"
    assert off_m <= 0.10 and off_deg <= 7.0, f"{label}: {off_m:.3f} m {off_deg:.1f} deg off: {pose}"
    return f"{off_m * 100:.1f} cm {off_deg:.2f} deg from the truth"


def check_answer(answer, label):
    assert answer.success, f"{label}: not localized: {answer.message}"
    print(f"{label}: localized {right_pose(answer, label, 'localized')}")


def check_guess(answer, label):
    """A first place from no prior, not yet borne out by a drive: right, `not localized`."""
    assert not answer.success, f"{label}: localized from one scan: {answer.message}"
    held_back = json.loads(answer.message)["held_back"]
    assert held_back == "confirming", f"{label}: held back as {held_back}: {answer.message}"
    print(f"{label}: not localized yet (confirming), {right_pose(answer, label, 'not localized')}")


def simulate(gridloc, maps, extra):
    command = [gridloc, "simulate", "--map", os.path.join(maps, "room_furnished.yaml"),
               "--pose", ",".join(str(v) for v in TRUTH)] + extra
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


def ring_mounts(maps):
    """The bundled ring's sonars as (x, y, yaw) mounts in the robot frame."""
    import yaml
    ring = yaml.safe_load(open(os.path.join(maps, "sensors", "wheelchair_14.yaml")))
    return [(s["radius_m"] * math.cos(math.radians(s["bearing_deg"])),
             s["radius_m"] * math.sin(math.radians(s["bearing_deg"])),
             math.radians(s["heading_deg"])) for s in ring["sonars"]]


def static_transforms(maps):
    """odom -> base_link (the robot at the odometry origin) and base_link -> sonar_i."""
    transforms = []
    odom = TransformStamped()
    odom.header.frame_id, odom.child_frame_id = "odom", "base_link"
    odom.header.stamp = rospy.Time.now()
    odom.transform.rotation.w = 1.0
    transforms.append(odom)
    for i, (x, y, yaw) in enumerate(ring_mounts(maps)):
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id = "base_link", f"sonar_{i}"
        t.header.stamp = rospy.Time.now()
        t.transform.translation.x, t.transform.translation.y = x, y
        t.transform.rotation.z, t.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        transforms.append(t)
    return TFMessage(transforms)


def fire(publishers, ranges):
    for i, r in enumerate(ranges):
        msg = Range()
        msg.header.frame_id = f"sonar_{i}"
        msg.header.stamp = rospy.Time.now()
        msg.radiation_type = Range.ULTRASOUND
        msg.field_of_view, msg.min_range, msg.max_range = math.radians(12), 0.15, 6.0
        msg.range = r
        publishers["sonar"].publish(msg)


def sonar_case(run, args, publishers, tf_seen, name, parameters, firings):
    """The node `name` with a sonar ring; `firings` firings are published after the prior."""
    tf_seen.clear()
    node = run.start([args.node, "__name:=" + name] + parameters, "node_" + name)
    localize = rospy.ServiceProxy(f"/{name}/localize", Trigger)
    rospy.wait_for_service(f"/{name}/localize", timeout=30)
    prior = PoseWithCovarianceStamped()
    prior.header.frame_id = "map"
    prior.header.stamp = rospy.Time.now()
    prior.pose.pose.position.x, prior.pose.pose.position.y = TRUTH[0] + 0.2, TRUTH[1] - 0.15
    yaw = TRUTH[2] + math.radians(8)
    prior.pose.pose.orientation.z, prior.pose.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    prior.pose.covariance[0] = prior.pose.covariance[7] = 0.3 ** 2
    prior.pose.covariance[35] = math.radians(15) ** 2
    wait_for("initialpose's subscriber", lambda: publishers["initialpose"].get_num_connections() > 0)
    publishers["initialpose"].publish(prior)
    ranges = json.loads(simulate(args.gridloc, args.maps, ["--realistic", "--seed", "3"]))["ranges_m"]
    wait_for("sonar's subscriber", lambda: publishers["sonar"].get_num_connections() > 0)
    time.sleep(0.5)  # the prior reaches the node before the firing
    for _ in range(firings):
        fire(publishers, ranges)
        time.sleep(0.3)
    localize_until_ready(localize, {"no map yet", "no complete sonar firing yet"})
    check_answer(localize(), f"sonar ring ({name}), initialpose, ~localize")
    wait_for("map -> odom on tf", lambda: tf_seen.get("odom") is not None)
    run.stop(node)


def laser_case(run, args, publishers, tf_seen):
    tf_seen.clear()
    # Another name: rospy's publishers here did not reconnect to a restarted node of the same
    # name (rospy 1.15, measured).
    node = run.start([args.node, "__name:=gridloc_laser", "_laser_max_range:=6.0"], "node_laser")
    localize = rospy.ServiceProxy("/gridloc_laser/localize", Trigger)
    rospy.wait_for_service("/gridloc_laser/localize", timeout=30)
    localize_until_ready(localize, {"no map yet"})
    rospy.ServiceProxy("/global_localization", Empty)()
    lines = simulate(args.gridloc, args.maps, ["--scan", "--beams", "360", "--max-range", "6"])
    beams = [[float(v) for v in l.split(",")] for l in lines.splitlines() if l and not l.startswith("#")]
    scan = LaserScan()
    scan.header.frame_id = "base_laser"
    scan.header.stamp = rospy.Time.now()
    scan.angle_min = beams[0][0]
    scan.angle_increment = beams[1][0] - beams[0][0]
    scan.angle_max = beams[-1][0]
    scan.range_min, scan.range_max = 0.05, 6.0
    scan.ranges = [float("inf") if r >= 6.0 else r for _, r in beams]  # REP 117: no echo
    wait_for("scan's subscriber", lambda: publishers["scan"].get_num_connections() > 0)
    publishers["scan"].publish(scan)
    localize_until_ready(localize, {"no scan yet"})
    check_guess(localize(), "laser, global_localization, ~localize")
    run.stop(node)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--node", required=True)
    parser.add_argument("--gridloc", required=True)
    parser.add_argument("--maps", required=True)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="gridloc-ros-") as workdir:
        run = Run(workdir)
        os.environ.update(run.env)
        try:
            run.start(["roscore", "-p", str(run.port)], "roscore")
            import rosgraph
            wait_for("roscore", lambda: rosgraph.is_master_online())
            rospy.init_node("gridloc_test_driver", disable_signals=True)
            tf_seen = {}

            def on_tf(msg):
                for t in msg.transforms:
                    if t.header.frame_id == "map":
                        tf_seen[t.child_frame_id] = t
            rospy.Subscriber("/tf", TFMessage, on_tf)
            publishers = {
                "map": rospy.Publisher("/map", OccupancyGrid, queue_size=1, latch=True),
                "tf_static": rospy.Publisher("/tf_static", TFMessage, queue_size=1, latch=True),
                "initialpose": rospy.Publisher("/initialpose", PoseWithCovarianceStamped, queue_size=1),
                "sonar": rospy.Publisher("/sonar", Range, queue_size=20),
                "scan": rospy.Publisher("/scan", LaserScan, queue_size=1),
            }
            publishers["map"].publish(read_map(os.path.join(args.maps, "room_furnished.yaml")))
            publishers["tf_static"].publish(static_transforms(args.maps))
            ring_file = os.path.join(args.maps, "sensors", "wheelchair_14.yaml")
            sonar_case(run, args, publishers, tf_seen, "gridloc_sonar", ["_ring_file:=" + ring_file], 1)
            # The same ring from tf: the mounts base_link -> sonar_i and each Range's cone; the
            # first firing teaches the mounts, the second is localized.
            rospy.set_param("/gridloc_tf/sonar_frames", [f"sonar_{i}" for i in range(14)])
            sonar_case(run, args, publishers, tf_seen, "gridloc_tf", [], 2)
            laser_case(run, args, publishers, tf_seen)
        except Exception:
            for _, name in run.processes:
                sys.stderr.write(f"--- {name} log ---\n{run.log(name)[-3000:]}\n")
            raise
        finally:
            rospy.signal_shutdown("done")
            run.stop_all()
    print("gridloc_ros end-to-end: passed")


if __name__ == "__main__":
    main()
