// Basic numeric types shared by every module.
#pragma once
#include <Eigen/Dense>  // Geometry (cross) and LU (inverse) are used throughout
#include <cstdint>

namespace dspdem {

using Real = double;
using Index = std::int32_t;
using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;

}  // namespace dspdem
