#include "ehd_capsule/ros/capsule_node.h"

namespace ehd::ros_node {

CapsuleNode::CapsuleNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), pnh_(private_nh), params_(ReadNodeParameters(pnh_, nh_)) {
  sim_ = std::make_unique<Simulation>(LoadScene(params_.scene, params_.overrides));
  if (params_.record) {
    ros::NodeHandle pnh = pnh_;
    recorder_ = std::make_unique<BagRecorder>(
        params_.bag, params_.overwrite, ros::this_node::getName(),
        [pnh](const std::string& topic) { return pnh.resolveName(topic); });
  }
  publishers_ = std::make_unique<NodePublishers>(nh_, pnh_, params_, *sim_, recorder_.get());
  publishers_->PublishStaticTransform();
  controller_ =
      std::make_unique<RunController>(pnh_, params_, *sim_, *publishers_, recorder_.get());
  publishers_->PublishScene();
  if (recorder_) {
    recorder_->Open();
    publishers_->RecordBagHeader();
  }
  publishers_->PublishSurfaceMesh();

  ROS_INFO_STREAM("ehd_capsule: scene '" << params_.scene << "'\n"
                                         << DescribeUnits(sim_->scene(), sim_->units())
                                         << sim_->Pipeline());
  const std::string warning = LargeRunWarning(sim_->scene(), sim_->units());
  if (!warning.empty()) ROS_WARN("ehd_capsule: %s", warning.c_str());
  if (params_.steps > 0) {
    ROS_INFO("ehd_capsule: will stop after %ld steps (t = %g %s)", params_.steps,
             params_.steps * sim_->units().dt, sim_->units().time_unit.c_str());
  }
}

}  // namespace ehd::ros_node
