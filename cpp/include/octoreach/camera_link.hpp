#pragma once
/// \file camera_link.hpp
/// \brief The link of a robot's head camera: the frame a planner's inspect actions look from. Given, or found
/// from the link names and the SRDF where it is unambiguous.

#include <string>

#include "octoreach/robot.hpp"

namespace octoreach {

/// \brief A camera link and why it was chosen.
struct CameraLink {
  std::string link;
  std::string reason;  ///< "given", or how find_camera_link found it
};

/// \brief The robot's head camera. Camera links are those whose names say so (camera, cam, kinect, xtion, rgb,
/// rgbd, depth, optical, stereo, realsense, ...), grouped by the rigid body they sit on (links joined by fixed
/// joints); when they sit on several bodies, only the bodies on the head count (a link named head or neck, or moved
/// by an SRDF group named head, among the body's ancestors). One body left: its first camera link (parents
/// first). No camera link at all: the end of the head (the head-named body with no head-named body below it),
/// when there is one. The planner's inspect actions use the link's position; its axes are the URDF's (a camera link
/// often looks along +x), so an exploration chain ends at the camera's optical frame (+z forward) instead.
/// \throws std::invalid_argument naming the candidates and asking for the link when none or several remain
CameraLink find_camera_link(const Robot& robot);

/// \brief `given` when it is not empty (reason "given"; std::invalid_argument naming the nearest links when the
/// robot lacks it), else find_camera_link(robot).
CameraLink camera_link(const Robot& robot, const std::string& given = "");

}  // namespace octoreach
