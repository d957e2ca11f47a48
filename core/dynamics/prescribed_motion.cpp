#include "dynamics/prescribed_motion.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace hofem {

PrescribedMotion fixed_nodes(std::vector<int> nodes) { return PrescribedMotion{std::move(nodes), {}, {}, {}}; }

PrescribedMotion translation(std::vector<int> nodes, const Eigen::Vector3d& velocity, double until) {
  PrescribedMotion m{std::move(nodes), {}, {}, {}};
  m.position = [velocity, until](const Eigen::Vector3d& X, double t) -> Eigen::Vector3d {
    return X + std::clamp(t, 0.0, until) * velocity;
  };
  m.velocity = [velocity, until](const Eigen::Vector3d&, double t) -> Eigen::Vector3d {
    return t >= 0.0 && t < until ? velocity : Eigen::Vector3d::Zero();
  };
  return m;
}

PrescribedMotion rotation(std::vector<int> nodes, const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                          double omega, double until, const Eigen::Vector3d& velocity) {
  if (!(axis.norm() > 0.0)) throw std::invalid_argument("rotation: the axis must be a non-zero vector");
  const Eigen::Vector3d a = axis.normalized();
  PrescribedMotion m{std::move(nodes), {}, {}, {}};
  m.position = [=](const Eigen::Vector3d& X, double t) -> Eigen::Vector3d {
    const double s = std::clamp(t, 0.0, until);
    return point + s * velocity + Eigen::AngleAxisd(omega * s, a) * (X - point);
  };
  // d/dt R(w t) r = w a x (R r); d2/dt2 = w^2 a x (a x R r).
  m.velocity = [=](const Eigen::Vector3d& X, double t) -> Eigen::Vector3d {
    if (t < 0.0 || t >= until) return Eigen::Vector3d::Zero();
    return velocity + omega * a.cross(Eigen::AngleAxisd(omega * t, a) * (X - point));
  };
  m.acceleration = [=](const Eigen::Vector3d& X, double t) -> Eigen::Vector3d {
    if (t < 0.0 || t >= until) return Eigen::Vector3d::Zero();
    return omega * omega * a.cross(a.cross(Eigen::AngleAxisd(omega * t, a) * (X - point)));
  };
  return m;
}

}  // namespace hofem
