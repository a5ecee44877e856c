// Linear-algebra types used everywhere: Eigen, double precision, SI units.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace peensim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace peensim
