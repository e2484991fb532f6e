// gridloc_ros: gridloc's Localizer as a ROS 1 node (issue 18). Built as C++17 against the
// ROS headers; gridloc itself is reached through bridge.hpp only (see there).
//
// Topics in: map (nav_msgs/OccupancyGrid, or ~map_file), sonar (sensor_msgs/Range, one per
// sonar, frame ~sonar_frame_prefix + index in ~ring_file) or scan (sensor_msgs/LaserScan),
// initialpose (geometry_msgs/PoseWithCovarianceStamped); odometry from tf (~odom_frame ->
// ~base_frame). Out: ~pose (PoseWithCovarianceStamped), ~verdict (std_msgs/String, JSON),
// diagnostics, and the ~global_frame -> ~odom_frame tf while localized. Services:
// global_localization (std_srvs/Empty), ~localize (std_srvs/Trigger).
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/Range.h>
#include <std_msgs/String.h>
#include <std_srvs/Empty.h>
#include <std_srvs/Trigger.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2/utils.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bridge.hpp"

namespace gridloc_ros {
namespace {

Pose pose_of(const geometry_msgs::Pose& pose) {
  return {pose.position.x, pose.position.y, tf2::getYaw(pose.orientation)};
}

tf2::Transform transform_of(const Pose& pose) {
  tf2::Quaternion q;
  q.setRPY(0.0, 0.0, pose.theta);
  return tf2::Transform(q, tf2::Vector3(pose.x, pose.y, 0.0));
}

std::string answer_json(const Answer& a) {
  std::ostringstream out;
  out << "{\"verdict\":\"" << a.verdict << "\",\"confidence\":" << a.confidence
      << ",\"x\":" << a.pose.x << ",\"y\":" << a.pose.y << ",\"theta\":" << a.pose.theta
      << ",\"hypotheses\":" << a.hypotheses << ",\"elapsed_ms\":" << a.elapsed_ms
      << ",\"held_back\":\"" << a.held_back << "\"}";
  return out.str();
}

class Node {
 public:
  Node(ros::NodeHandle& nh, ros::NodeHandle& private_nh)
      : nh_(nh), private_nh_(private_nh), listener_(buffer_) {
    read_parameters();
    pose_pub_ = private_nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("pose", 2, true);
    verdict_pub_ = private_nh_.advertise<std_msgs::String>("verdict", 2, true);
    diagnostics_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("diagnostics", 2);
    initial_pose_sub_ = nh_.subscribe("initialpose", 2, &Node::on_initial_pose, this);
    global_srv_ = nh_.advertiseService("global_localization", &Node::on_global, this);
    localize_srv_ = private_nh_.advertiseService("localize", &Node::on_localize, this);
    if (!options_.ring_file.empty() || !sonar_frames_.empty()) {
      sonar_sub_ = nh_.subscribe("sonar", 100, &Node::on_sonar, this);
    } else {
      scan_sub_ = nh_.subscribe("scan", 2, &Node::on_scan, this);
    }
    // AMCL's habit: the last map -> odom is sent again at 10 Hz, slightly ahead in time.
    tf_timer_ = nh_.createTimer(ros::Duration(0.1), [this](const ros::TimerEvent&) {
      if (publish_tf_ && have_map_to_odom_) publish_tf(ros::Time::now() + ros::Duration(0.1));
    });
    if (!options_.map_file.empty()) {
      have_map_ = true;
      try_build();
    } else {
      map_sub_ = nh_.subscribe("map", 1, &Node::on_map, this);
    }
  }

 private:
  void read_parameters() {
    private_nh_.param<std::string>("map_file", options_.map_file, "");
    private_nh_.param<std::string>("ring_file", options_.ring_file, "");
    private_nh_.param("laser_max_range", options_.laser_max_range, options_.laser_max_range);
    private_nh_.param("resolution", options_.resolution, options_.resolution);
    private_nh_.param("odometry_error_per_m", options_.odometry_error_per_m,
                      options_.odometry_error_per_m);
    private_nh_.param("odometry_turn_deg_per_m", options_.odometry_turn_deg_per_m,
                      options_.odometry_turn_deg_per_m);
    private_nh_.param("settle_first", options_.settle_first, options_.settle_first);
    private_nh_.param("reported_floor_m", options_.reported_floor_m, options_.reported_floor_m);
    private_nh_.param("reported_floor_deg", options_.reported_floor_deg,
                      options_.reported_floor_deg);
    private_nh_.param<std::string>("sonar_frame_prefix", sonar_prefix_, "sonar_");
    private_nh_.param("sonar_frames", sonar_frames_, std::vector<std::string>{});
    if (!options_.ring_file.empty()) sonar_frames_.clear();  // the ring file wins
    mounts_.resize(sonar_frames_.size());
    private_nh_.param<std::string>("global_frame", global_frame_, "map");
    private_nh_.param<std::string>("odom_frame", odom_frame_, "odom");
    private_nh_.param<std::string>("base_frame", base_frame_, "base_link");
    private_nh_.param("publish_tf", publish_tf_, true);
  }

  /// Builds the localizer once the map (and, for sonars from tf, every mount) is known.
  void try_build() {
    if (!have_map_) return;
    options_.sonars.clear();
    for (const auto& mount : mounts_) {
      if (!mount) return;
      options_.sonars.push_back(*mount);
    }
    build(map_);
  }

  /// (Re)builds the localizer on a map; a prior given before applies now.
  void build(const GridMap& map) {
    try {
      bridge_ = std::make_unique<Bridge>(map, options_);
    } catch (const std::exception& e) {
      ROS_ERROR("gridloc: %s", e.what());
      return;
    }
    readings_.assign(static_cast<std::size_t>(bridge_->sonar_count()),
                     std::numeric_limits<double>::quiet_NaN());
    fresh_.assign(readings_.size(), false);
    ROS_INFO("gridloc: ready (%s)", bridge_->sonar() ? "sonar ring" : "laser");
    if (pending_prior_) apply_prior(*pending_prior_);
  }

  void on_map(const nav_msgs::OccupancyGrid::ConstPtr& msg) {
    GridMap map;
    map.width = static_cast<int>(msg->info.width);
    map.height = static_cast<int>(msg->info.height);
    map.resolution = msg->info.resolution;
    map.origin = pose_of(msg->info.origin);
    map.data.assign(msg->data.begin(), msg->data.end());
    map_ = std::move(map);
    have_map_ = true;
    try_build();
  }

  void apply_prior(const geometry_msgs::PoseWithCovarianceStamped& msg) {
    std::array<double, 36> covariance{};
    for (std::size_t i = 0; i < 36; ++i) covariance[i] = msg.pose.covariance[i];
    try {
      observe_odometry(msg.header.stamp);
      bridge_->set_prior(pose_of(msg.pose.pose), covariance);
      pending_prior_.reset();
    } catch (const std::exception& e) {
      ROS_ERROR("gridloc: initialpose: %s", e.what());
    }
  }

  void on_initial_pose(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg) {
    if (msg->header.frame_id != global_frame_ && !msg->header.frame_id.empty()) {
      ROS_WARN("gridloc: initialpose in frame '%s', not '%s': ignored",
               msg->header.frame_id.c_str(), global_frame_.c_str());
      return;
    }
    pending_prior_ = std::make_unique<geometry_msgs::PoseWithCovarianceStamped>(*msg);
    if (bridge_) apply_prior(*msg);
  }

  bool on_global(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    if (bridge_) bridge_->reset();
    localized_ = false;
    return true;
  }

  bool on_localize(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    if (!bridge_) {
      response.success = false;
      response.message = "no map yet";
      return true;
    }
    const bool sonar = bridge_->sonar();
    const bool ready = sonar ? complete() : static_cast<bool>(last_scan_);
    if (!ready) {
      response.success = false;
      response.message = sonar ? "no complete sonar firing yet" : "no scan yet";
      return true;
    }
    try {
      const Answer a = sonar ? localize_sonar(ros::Time::now()) : localize_scan(last_scan_);
      response.success = a.verdict == "localized";
      response.message = answer_json(a);
    } catch (const std::exception& e) {
      response.success = false;
      response.message = e.what();
    }
    return true;
  }

  /// The sonar index a Range's frame names (ring order), or -1.
  int sonar_index(const std::string& frame) const {
    if (!sonar_frames_.empty()) {
      const auto at = std::find(sonar_frames_.begin(), sonar_frames_.end(), frame);
      return at == sonar_frames_.end() ? -1 : static_cast<int>(at - sonar_frames_.begin());
    }
    if (frame.compare(0, sonar_prefix_.size(), sonar_prefix_) != 0) return -1;
    try {
      const int i = std::stoi(frame.substr(sonar_prefix_.size()));
      return i >= 0 && i < static_cast<int>(readings_.size()) ? i : -1;
    } catch (const std::exception&) {
      return -1;
    }
  }

  bool complete() const {
    for (double r : readings_) {
      if (std::isnan(r)) return false;
    }
    return !readings_.empty();
  }

  /// A sonar's mount from tf (base -> its frame) and its cone and ranges from its Range.
  void learn_mount(int i, const sensor_msgs::Range& msg) {
    try {
      const geometry_msgs::TransformStamped t =
          buffer_.lookupTransform(base_frame_, msg.header.frame_id, ros::Time(0));
      SonarMount mount;
      mount.mount = {t.transform.translation.x, t.transform.translation.y,
                     tf2::getYaw(t.transform.rotation)};
      mount.field_of_view = msg.field_of_view;
      mount.min_range = msg.min_range;
      mount.max_range = msg.max_range;
      mounts_[static_cast<std::size_t>(i)] = mount;
      try_build();
    } catch (const tf2::TransformException& e) {
      ROS_WARN_THROTTLE(10.0, "gridloc: no mount for sonar '%s' yet (%s)",
                        msg.header.frame_id.c_str(), e.what());
    }
  }

  void on_sonar(const sensor_msgs::Range::ConstPtr& msg) {
    const int i = sonar_index(msg->header.frame_id);
    if (i >= 0 && !sonar_frames_.empty() && !mounts_[static_cast<std::size_t>(i)]) {
      learn_mount(i, *msg);
    }
    if (!bridge_) return;
    if (i < 0) {
      ROS_WARN_THROTTLE(10.0, "gridloc: Range in frame '%s' is not one of the ring's sonars",
                        msg->header.frame_id.c_str());
      return;
    }
    readings_[i] = msg->range;
    fresh_[i] = true;
    for (bool f : fresh_) {
      if (!f) return;
    }
    try {  // every sonar has fired since the last firing: localize
      localize_sonar(msg->header.stamp);
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "gridloc: %s", e.what());
    }
  }

  Answer localize_sonar(const ros::Time& stamp) {
    fresh_.assign(fresh_.size(), false);
    observe_odometry(stamp);
    const Answer a = bridge_->add_sonar(stamp.toSec(), readings_);
    publish(a, stamp);
    return a;
  }

  void on_scan(const sensor_msgs::LaserScan::ConstPtr& msg) {
    last_scan_ = msg;
    if (!bridge_) return;
    try {
      localize_scan(msg);
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "gridloc: %s", e.what());
    }
  }

  Answer localize_scan(const sensor_msgs::LaserScan::ConstPtr& msg) {
    observe_odometry(msg->header.stamp);
    const Answer a = bridge_->add_scan(msg->header.stamp.toSec(), msg->angle_min,
                                       msg->angle_increment, msg->range_max, msg->ranges);
    publish(a, msg->header.stamp);
    return a;
  }

  /// The odometry pose (odom -> base) at `stamp`, or the latest; without one the robot is
  /// taken to stand still.
  void observe_odometry(const ros::Time& stamp) {
    geometry_msgs::TransformStamped t;
    try {
      t = buffer_.lookupTransform(odom_frame_, base_frame_, stamp, ros::Duration(0.05));
    } catch (const tf2::TransformException&) {
      try {
        t = buffer_.lookupTransform(odom_frame_, base_frame_, ros::Time(0));
      } catch (const tf2::TransformException& e) {
        ROS_WARN_THROTTLE(30.0, "gridloc: no odometry (%s); the robot is taken to stand still",
                          e.what());
        bridge_->add_odometry(odometry_);
        return;
      }
    }
    odometry_ = {t.transform.translation.x, t.transform.translation.y,
                 tf2::getYaw(t.transform.rotation)};
    bridge_->add_odometry(odometry_);
  }

  void publish(const Answer& a, const ros::Time& stamp) {
    geometry_msgs::PoseWithCovarianceStamped pose;
    pose.header.stamp = stamp;
    pose.header.frame_id = global_frame_;
    pose.pose.pose.position.x = a.pose.x;
    pose.pose.pose.position.y = a.pose.y;
    tf2::Quaternion q;
    q.setRPY(0.0, 0.0, a.pose.theta);
    pose.pose.pose.orientation.x = q.x();
    pose.pose.pose.orientation.y = q.y();
    pose.pose.pose.orientation.z = q.z();
    pose.pose.pose.orientation.w = q.w();
    for (std::size_t i = 0; i < 36; ++i) pose.pose.covariance[i] = a.covariance[i];
    pose_pub_.publish(pose);
    std_msgs::String verdict;
    verdict.data = answer_json(a);
    verdict_pub_.publish(verdict);
    publish_diagnostics(a, stamp);
    localized_ = a.verdict == "localized";
    if (localized_) {
      map_to_odom_ = transform_of(a.pose) * transform_of(odometry_).inverse();
      have_map_to_odom_ = true;
      if (publish_tf_) publish_tf(stamp);
    }
  }

  void publish_tf(const ros::Time& stamp) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = global_frame_;
    t.child_frame_id = odom_frame_;
    t.transform.translation.x = map_to_odom_.getOrigin().x();
    t.transform.translation.y = map_to_odom_.getOrigin().y();
    const tf2::Quaternion q = map_to_odom_.getRotation();
    t.transform.rotation.x = q.x();
    t.transform.rotation.y = q.y();
    t.transform.rotation.z = q.z();
    t.transform.rotation.w = q.w();
    broadcaster_.sendTransform(t);
  }

  void publish_diagnostics(const Answer& a, const ros::Time& stamp) {
    diagnostic_msgs::DiagnosticArray array;
    array.header.stamp = stamp;
    diagnostic_msgs::DiagnosticStatus status;
    status.name = ros::this_node::getName() + ": localization";
    status.hardware_id = "gridloc";
    status.level = a.verdict == "localized" ? diagnostic_msgs::DiagnosticStatus::OK
                                            : diagnostic_msgs::DiagnosticStatus::WARN;
    status.message = a.verdict;
    const auto value = [&](const std::string& key, double v) {
      diagnostic_msgs::KeyValue kv;
      kv.key = key;
      std::ostringstream text;
      text << v;
      kv.value = text.str();
      status.values.push_back(kv);
    };
    value("confidence", a.confidence);
    value("hypotheses", a.hypotheses);
    value("update_ms", a.elapsed_ms);
    value("search_slices_done", a.search_slices_done);
    value("search_slices", a.search_slices);
    value("search_progress", a.search_progress);
    diagnostic_msgs::KeyValue held_back;
    held_back.key = "held_back";
    held_back.value = a.held_back;
    status.values.push_back(held_back);
    array.status.push_back(status);
    diagnostics_pub_.publish(array);
  }

  ros::NodeHandle& nh_;
  ros::NodeHandle& private_nh_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  tf2_ros::TransformBroadcaster broadcaster_;
  BridgeOptions options_;
  std::string sonar_prefix_, global_frame_, odom_frame_, base_frame_;
  std::vector<std::string> sonar_frames_;  ///< sonars from tf, in ring order
  std::vector<std::optional<SonarMount>> mounts_;
  GridMap map_;
  bool have_map_ = false;
  bool publish_tf_ = true;
  std::unique_ptr<Bridge> bridge_;
  std::unique_ptr<geometry_msgs::PoseWithCovarianceStamped> pending_prior_;
  std::vector<double> readings_;
  std::vector<bool> fresh_;
  sensor_msgs::LaserScan::ConstPtr last_scan_;
  Pose odometry_;
  bool localized_ = false, have_map_to_odom_ = false;
  tf2::Transform map_to_odom_;
  ros::Timer tf_timer_;
  ros::Publisher pose_pub_, verdict_pub_, diagnostics_pub_;
  ros::Subscriber map_sub_, sonar_sub_, scan_sub_, initial_pose_sub_;
  ros::ServiceServer global_srv_, localize_srv_;
};

}  // namespace
}  // namespace gridloc_ros

int main(int argc, char** argv) {
  ros::init(argc, argv, "gridloc");
  ros::NodeHandle nh, private_nh("~");
  gridloc_ros::Node node(nh, private_nh);
  ros::spin();
  return 0;
}
