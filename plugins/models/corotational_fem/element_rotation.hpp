// Per-element rotation for corotational FEM: the rotation R that best matches a deformation
// gradient F, so that R^T F - I measures strain without the rigid part.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tacta::models::corotational {

// Polar rotation of F by a warm-started quaternion iteration that maximises tr(R^T F) over
// proper rotations (the idea of Mueller, Bender, Chentanez and Macklin, "A robust method to
// extract the rotational part of deformations", MIG 2016). It never returns a reflection and
// stays defined for flat or inverted elements. `rotation` holds the previous result on entry
// (identity when none) and the new one on exit. Returns the iterations used.
int polar_rotation(const Eigen::Matrix3d& deformation, Eigen::Quaterniond& rotation,
                   int max_iterations);

// Rotation U V^T from the SVD of F with reflections removed as in Irving, Teran and Fedkiw,
// "Invertible finite elements for robust simulation of large deformation" (SCA 2004): when
// det(U) or det(V) is negative, the column of the smallest singular value is negated, so R is
// proper and an inverted element sees a negative principal stretch that pushes it back.
Eigen::Matrix3d svd_rotation(const Eigen::Matrix3d& deformation);

}  // namespace tacta::models::corotational
